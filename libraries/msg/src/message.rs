//! Which message travels on which topic kind, and how a received payload is
//! decoded: what a node's typed inputs and outputs are declared with.

use crate::{
    BlendCommandMessage, CloudMessage, CloudView, CollisionMessage, JointStateMessage,
    MessageError, NodeStatusMessage, SmoothPatchesMessage, SurrogateMessage, TopicKind,
};

/// A message of shroud's wire schema: the one topic kind it is published on,
/// and its decoder (every decoder checks the version and the fields a
/// consumer relies on, and refuses the rest by name).
pub trait Message: serde::Serialize {
    /// The kind of topic (`shroud/<ns>/<kind>/<name>`) it travels on.
    const KIND: TopicKind;

    /// What a received payload decodes to: the message itself, or a view
    /// that borrows the payload's bulk arrays (a cloud's points are then
    /// read where they lie).
    type View<'a>;

    fn decode(bytes: &[u8]) -> Result<Self::View<'_>, MessageError>;
}

impl Message for CloudMessage {
    const KIND: TopicKind = TopicKind::Cloud;
    type View<'a> = CloudView<'a>;

    fn decode(bytes: &[u8]) -> Result<CloudView<'_>, MessageError> {
        CloudView::from_bytes(bytes)
    }
}

/// A type whose encoding is a message `M`: `M` itself, or a view of one
/// (a [`CloudView`] borrowing its points encodes as a [`CloudMessage`]), so
/// that an output declared for `M` publishes either.
pub trait WireOf<M: Message>: serde::Serialize {}

impl<M: Message> WireOf<M> for M {}

impl WireOf<CloudMessage> for CloudView<'_> {}

/// The owned messages: decoded and validated by their own `from_bytes`.
macro_rules! owned_message {
    ($($message:ty => $kind:ident, $decode:path;)*) => {$(
        impl Message for $message {
            const KIND: TopicKind = TopicKind::$kind;
            type View<'a> = $message;

            fn decode(bytes: &[u8]) -> Result<$message, MessageError> {
                $decode(bytes)
            }
        }
    )*};
}

owned_message! {
    SurrogateMessage => Surrogate, SurrogateMessage::decode;
    JointStateMessage => Joints, JointStateMessage::from_bytes;
    CollisionMessage => Collision, CollisionMessage::from_bytes;
    NodeStatusMessage => Status, NodeStatusMessage::from_bytes;
    BlendCommandMessage => Blend, BlendCommandMessage::from_bytes;
    SmoothPatchesMessage => Smooth, SmoothPatchesMessage::from_bytes;
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Encodes with the type's own encoder and decodes through the trait.
    fn round_trip<M: Message>(message: &M, bytes: Vec<u8>) -> Result<(), MessageError> {
        M::decode(&bytes).map(|_| ())?;
        assert_eq!(bytes, crate::blob::encode(message)?);
        Ok(())
    }

    #[test]
    fn each_message_decodes_through_its_kind() -> Result<(), MessageError> {
        let joints = JointStateMessage::new(1, 2, "arm", vec!["j".into()], vec![0.5]);
        round_trip(&joints, joints.to_bytes()?)?;
        assert_eq!(JointStateMessage::KIND, TopicKind::Joints);
        let points = [[1.0f32, 2.0, 3.0]];
        let cloud = CloudView::new(3, 4, "s", crate::SensorPose::default(), &points);
        let bytes = cloud.to_bytes()?;
        let view = <CloudMessage as Message>::decode(&bytes)?;
        assert_eq!(view.len(), 1);
        assert_eq!(bytes, view.to_message()?.to_bytes()?);
        let collision = crate::sample_collision(crate::GuardVerdict::Clear);
        round_trip(&collision, collision.to_bytes()?)?;
        let status = NodeStatusMessage::new("n", "fit", 1);
        round_trip(&status, status.to_bytes()?)?;
        Ok(())
    }

    #[test]
    fn a_foreign_payload_is_refused_by_name() {
        let err = <JointStateMessage as Message>::decode(b"\x01\x02").unwrap_err();
        assert!(matches!(err, MessageError::Malformed(_)), "{err}");
    }
}
