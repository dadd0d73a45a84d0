//! Round trips shared by targets: a decoded value, written by shroud's own
//! writer, must read back as the same value.

use crate::check::same;
use shroud_shapes::format::PlyCloud;

/// `cloud`, written by `write` and read by `parse`, must give the same points
/// and intensity (the count of skipped invalid points is the reader's, not
/// the cloud's).
pub fn cloud<E: std::fmt::Debug>(
    cloud: &PlyCloud,
    write: impl FnOnce(&[[f32; 3]], Option<&[f32]>) -> Vec<u8>,
    parse: impl FnOnce(&[u8]) -> Result<PlyCloud, E>,
) {
    let bytes = write(&cloud.points, cloud.intensity.as_deref());
    let again = parse(&bytes).unwrap_or_else(|e| panic!("a written cloud does not read: {e:?}"));
    same(&cloud.points, &again.points, "points after a round trip");
    same(
        &cloud.intensity,
        &again.intensity,
        "intensity after a round trip",
    );
}

/// `value` encoded by `encode` must decode (by `decode`) to a value that
/// encodes to the same bytes: encoding is a function of the decoded value.
pub fn stable<T, E: std::fmt::Debug>(
    value: &T,
    encode: impl Fn(&T) -> Vec<u8>,
    decode: impl FnOnce(&[u8]) -> Result<T, E>,
) {
    let bytes = encode(value);
    let again =
        decode(&bytes).unwrap_or_else(|e| panic!("an encoded value does not decode: {e:?}"));
    assert!(
        encode(&again) == bytes,
        "re-encoding a decoded value changed its bytes"
    );
}

/// A decoded wire message must encode, and decode again to the same message.
pub fn message<T: std::fmt::Debug, E: std::fmt::Debug>(
    value: &T,
    to_bytes: impl FnOnce(&T) -> Result<Vec<u8>, E>,
    from_bytes: impl FnOnce(&[u8]) -> Result<T, E>,
) -> T {
    let bytes =
        to_bytes(value).unwrap_or_else(|e| panic!("a decoded message does not encode: {e:?}"));
    let again =
        from_bytes(&bytes).unwrap_or_else(|e| panic!("an encoded message does not decode: {e:?}"));
    same(value, &again, "messages after a round trip");
    again
}
