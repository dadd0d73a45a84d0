//! DBC databases (`CanDatabase::parse`) and the frames they decode. An
//! input is DBC text, a NUL byte, then frames as [`crate::can_records`].
//! A decoded message's values, encoded again, decode the same.

use crate::can_records::{record, records};
use crate::check::{named, same};
use shroud_drivers::dbc::{CanDatabase, BUILTIN};

pub fn run(data: &[u8]) {
    let (text, frames) = match data.iter().position(|&b| b == 0) {
        Some(nul) => (&data[..nul], &data[nul + 1..]),
        None => (data, &[][..]),
    };
    let Ok(text) = std::str::from_utf8(text) else {
        return;
    };
    let database = match CanDatabase::parse(text) {
        Ok(database) => database,
        Err(e) => return named(&e),
    };
    for r in records(frames) {
        match database.decode(&r.frame) {
            Some(Ok(message)) => {
                let values: Vec<(&str, f64)> = message.iter().collect();
                let spec = database
                    .message_by_id(r.frame.id, r.frame.extended)
                    .expect("a decoded id");
                match spec.encode(&values) {
                    Ok(frame) => {
                        let again = spec.decode(&frame).expect("an encoded frame decodes");
                        same(
                            &values,
                            &again.iter().collect::<Vec<_>>(),
                            "signal values after a round trip",
                        );
                    }
                    Err(e) => named(&e),
                }
            }
            Some(Err(e)) => named(&e),
            None => {}
        }
    }
}

pub fn seeds() -> Vec<Vec<u8>> {
    BUILTIN
        .iter()
        .map(|(_, text)| {
            let database = CanDatabase::parse(text).expect("a built-in database parses");
            let mut input = text.as_bytes().to_vec();
            input.push(0);
            for spec in database.messages() {
                let mut frame = shroud_drivers::can::CanFrame::new(
                    spec.id,
                    spec.extended,
                    &[0x5A; 8][..usize::from(spec.len)],
                )
                .expect("a built-in message's frame");
                frame.data[0] ^= 0x81;
                input.extend(record(&frame, 1));
            }
            input
        })
        .collect()
}
