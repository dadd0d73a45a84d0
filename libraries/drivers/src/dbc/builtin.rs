//! The DBC files shroud ships for the CAN devices it drives, embedded in the
//! binary and looked up by name. They were written for shroud from the
//! devices' public documentation (research note §2.1, §2.2).

use super::CanDatabase;

/// `(name, DBC text)` of every shipped database.
pub const BUILTIN: [(&str, &str); 4] = [
    // Continental ARS408-21 radar, sensor id 0 (move ids with `with_id_offset`).
    ("ars408", include_str!("../../dbc/ars408_21.dbc")),
    // Benewake TF03-CAN.
    (
        "benewake_tf03",
        include_str!("../../dbc/benewake_tf03_can.dbc"),
    ),
    // Benewake TFmini-i-CAN and TF02-i-CAN (same frame).
    (
        "benewake_tfmini_i",
        include_str!("../../dbc/benewake_tfmini_i_can.dbc"),
    ),
    // Legacy Benewake TF02 CAN: extended id, big-endian payload.
    (
        "benewake_tf02",
        include_str!("../../dbc/benewake_tf02_can.dbc"),
    ),
];

/// The shipped database named, parsed; `None` for an unknown name. (The
/// tests prove every shipped file parses.)
pub fn builtin(name: &str) -> Option<CanDatabase> {
    BUILTIN
        .iter()
        .find(|(n, _)| *n == name)
        .and_then(|(_, text)| CanDatabase::parse(text).ok())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_builtin_parses() {
        for (name, text) in BUILTIN {
            if let Err(e) = CanDatabase::parse(text) {
                panic!("{name}: {e}");
            }
            assert!(builtin(name).is_some());
        }
        assert!(builtin("nope").is_none());
    }
}
