//! A ROS 2 message type: its name, its RIHS01 type hash and its payload
//! codec; and `ros_message!`, which declares one from its `.msg` fields.

use crate::cdr::{decode_payload, encode_payload, CdrDecode, CdrEncode, CdrError};

/// A ROS 2 message shroud can publish or read, with its identity on the wire.
pub trait RosMessage: CdrEncode + CdrDecode {
    /// The ROS type name, `package/msg/Name`.
    const TYPE_NAME: &'static str;
    /// The REP-2011 type hash rmw_zenoh puts in keys and tokens
    /// (`RIHS01_<sha256 hex>`; the literals come from rosbags' `hash_rihs01`,
    /// checked by tests/golden.rs).
    const TYPE_HASH: &'static str;

    /// The whole payload: CDR_LE header and the message.
    fn encode(&self) -> Vec<u8> {
        encode_payload(self)
    }

    /// Reads a whole payload (CDR_LE or CDR_BE).
    fn decode(bytes: &[u8]) -> Result<Self, CdrError> {
        decode_payload(bytes)
    }
}

/// Declares a plain struct mirroring a ROS `.msg` (fields in the `.msg`'s
/// order, which is the wire order), derives its CDR codec field by field and
/// implements [`RosMessage`] with the given type name and hash.
macro_rules! ros_message {
    (
        $(#[$meta:meta])*
        $type_name:literal, $type_hash:literal;
        pub struct $ty:ident { $($(#[$field_meta:meta])* pub $field:ident: $field_ty:ty),* $(,)? }
    ) => {
        $(#[$meta])*
        #[derive(Debug, Clone, PartialEq, Default)]
        pub struct $ty { $($(#[$field_meta])* pub $field: $field_ty),* }

        impl $crate::cdr::CdrEncode for $ty {
            fn encode_cdr(&self, writer: &mut $crate::cdr::CdrWriter) {
                $($crate::cdr::CdrEncode::encode_cdr(&self.$field, writer);)*
            }
        }

        impl $crate::cdr::CdrDecode for $ty {
            const MIN_CDR_BYTES: usize =
                0 $(+ <$field_ty as $crate::cdr::CdrDecode>::MIN_CDR_BYTES)*;

            fn decode_cdr(
                reader: &mut $crate::cdr::CdrReader<'_>,
                _field: &'static str,
            ) -> Result<Self, $crate::cdr::CdrError> {
                Ok(Self {$(
                    $field: $crate::cdr::CdrDecode::decode_cdr(
                        reader,
                        concat!(stringify!($ty), ".", stringify!($field)),
                    )?,
                )*})
            }
        }

        impl $crate::msgs::RosMessage for $ty {
            const TYPE_NAME: &'static str = $type_name;
            const TYPE_HASH: &'static str = $type_hash;
        }
    };
}
