//! candump logs (`CandumpParser`, `candump -L` lines): a parsed record
//! written back as a line parses to the same record (stamps keep
//! microseconds).

use crate::check::{named, same};
use shroud_drivers::can::{format_candump_line, parse_candump_line, CandumpParser};

pub fn run(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let mut parser = CandumpParser::default();
    for line in text.lines() {
        match parser.push_line(line) {
            Some(Ok(record)) => {
                let again = parse_candump_line(&format_candump_line(&record), 1)
                    .expect("a written line parses")
                    .expect("a written line holds a record");
                let mut expected = record.clone();
                expected.stamp_ns -= expected.stamp_ns % 1000;
                same(&expected, &again, "records after a round trip");
            }
            Some(Err(e)) => named(&e),
            None => {}
        }
    }
}

pub fn seeds() -> Vec<Vec<u8>> {
    vec![b"# candump log\n(1700000000.123456) can0 123#DEADBEEF\n\
           (1700000000.200000) can1 12345678#0102030405060708\n\
           (1700000001.000001) vcan0 7FF#R2\n(1.5) can0 001#\n\n; note\n"
        .to_vec()]
}
