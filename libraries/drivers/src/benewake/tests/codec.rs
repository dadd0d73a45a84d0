//! Golden vectors of the data frame, the command builders and the replies
//! (sensors.md §1.3, TFmini-S manual Table 12, TF03 manual §4.3).

use crate::benewake::{
    command_id, encode_frame, sum8, BenewakeModel, Command, CommandFrame, DataFrame, DistanceUnit,
    FirmwareVersion, FrameError, Reading, Reply, ReplyError, TfminiDistanceMode, Validity,
};

#[test]
fn golden_data_frame_is_16_cm_strength_288() {
    let bytes = [0x59, 0x59, 0x10, 0x00, 0x20, 0x01, 0x00, 0x00, 0xE3];
    let frame = DataFrame::parse(&bytes).unwrap();
    assert_eq!(frame.distance, 16);
    assert_eq!(frame.strength, 288);
    assert_eq!(frame.aux, 0);
    assert_eq!(frame.encode(), bytes);
    let reading = Reading::classify(frame, BenewakeModel::TfminiPlus, DistanceUnit::Centimetre);
    assert_eq!(reading.validity, Validity::Valid);
    assert_eq!(reading.range_m, 0.16);
    assert_eq!(reading.ray().intensity, Some(288.0));
}

#[test]
fn data_frame_rejects_a_bad_sum_and_a_bad_header() {
    let mut bytes = [0x59, 0x59, 0x10, 0x00, 0x20, 0x01, 0x00, 0x00, 0xE4];
    assert_eq!(
        DataFrame::parse(&bytes),
        Err(FrameError::BadChecksum {
            expected: 0xE3,
            found: 0xE4
        })
    );
    bytes[1] = 0x58;
    assert_eq!(DataFrame::parse(&bytes), Err(FrameError::BadHeader));
}

#[test]
fn temperature_is_raw_over_8_minus_256() {
    let frame = DataFrame {
        distance: 100,
        strength: 1000,
        aux: (25 + 256) * 8,
    };
    assert_eq!(frame.temperature_c(), 25.0);
    let reading = Reading::classify(frame, BenewakeModel::TfLuna, DistanceUnit::Centimetre);
    assert_eq!(reading.temperature_c, Some(25.0));
    assert_eq!(reading.distance_mode, None);
}

#[test]
fn original_tfmini_bytes_6_7_are_distance_mode_and_reserved() {
    let short = DataFrame {
        distance: 100,
        strength: 1000,
        aux: 0xAB02,
    };
    let reading = Reading::classify(short, BenewakeModel::Tfmini, DistanceUnit::Centimetre);
    assert_eq!(reading.distance_mode, Some(TfminiDistanceMode::Short));
    assert_eq!(reading.temperature_c, None);
    let long = DataFrame {
        aux: 0x0007,
        ..short
    };
    assert_eq!(long.tfmini_distance_mode(), TfminiDistanceMode::Long);
    let other = DataFrame {
        aux: 0x0003,
        ..short
    };
    assert_eq!(other.tfmini_distance_mode(), TfminiDistanceMode::Other(3));
}

#[test]
fn golden_command_frames() {
    let cases: [(Command, &[u8]); 14] = [
        (Command::Version, &[0x5A, 0x04, 0x01, 0x5F]),
        (Command::SoftReset, &[0x5A, 0x04, 0x02, 0x60]),
        (
            Command::FrameRate(100),
            &[0x5A, 0x06, 0x03, 0x64, 0x00, 0xC7],
        ),
        // TFmini Plus manual §7.2: 1000 is sent as E8 03.
        (
            Command::FrameRate(1000),
            &[0x5A, 0x06, 0x03, 0xE8, 0x03, 0x4E],
        ),
        (Command::FrameRate(0), &[0x5A, 0x06, 0x03, 0x00, 0x00, 0x63]),
        (Command::Trigger, &[0x5A, 0x04, 0x04, 0x62]),
        (
            Command::OutputFormat(DistanceUnit::Centimetre),
            &[0x5A, 0x05, 0x05, 0x01, 0x65],
        ),
        (
            Command::OutputFormat(DistanceUnit::Millimetre),
            &[0x5A, 0x05, 0x05, 0x06, 0x6A],
        ),
        (
            Command::OutputEnable(false),
            &[0x5A, 0x05, 0x07, 0x00, 0x66],
        ),
        (Command::OutputEnable(true), &[0x5A, 0x05, 0x07, 0x01, 0x67]),
        (
            Command::Baud(115_200),
            &[0x5A, 0x08, 0x06, 0x00, 0xC2, 0x01, 0x00, 0x2B],
        ),
        // TFmini-S manual Table 12: 256000 = 00 E8 03 00.
        (
            Command::Baud(256_000),
            &[0x5A, 0x08, 0x06, 0x00, 0xE8, 0x03, 0x00, 0x53],
        ),
        (Command::FactoryReset, &[0x5A, 0x04, 0x10, 0x6E]),
        (Command::Save, &[0x5A, 0x04, 0x11, 0x6F]),
    ];
    for (command, expected) in cases {
        assert_eq!(command.encode(), expected, "{command:?}");
    }
}

#[test]
fn sum8_is_the_low_byte_of_the_sum() {
    assert_eq!(sum8(&[]), 0);
    assert_eq!(sum8(&[0xFF, 0x02]), 0x01);
    assert_eq!(sum8(&[0x5A, 0x04, 0x01]), 0x5F);
}

#[test]
fn version_reply_is_v3_v2_v1() {
    // TF03 manual §4.3.1: bytes 112, 50, 9 are version 9.50.112.
    let bytes = [0x5A, 0x07, 0x01, 112, 50, 9, 0x0D];
    let frame = CommandFrame::parse(&bytes).unwrap();
    let version = FirmwareVersion {
        major: 9,
        minor: 50,
        patch: 112,
    };
    assert_eq!(frame.reply(), Reply::Version(version));
    assert_eq!(version.to_string(), "9.50.112");
}

#[test]
fn echo_and_status_replies() {
    let parse = |bytes: &[u8]| CommandFrame::parse(bytes).unwrap().reply();
    assert_eq!(
        parse(&[0x5A, 0x06, 0x03, 0x64, 0x00, 0xC7]),
        Reply::FrameRate(100)
    );
    assert_eq!(
        parse(&[0x5A, 0x05, 0x05, 0x06, 0x6A]),
        Reply::OutputFormat(6)
    );
    assert_eq!(
        parse(&[0x5A, 0x05, 0x07, 0x01, 0x67]),
        Reply::OutputEnable(true)
    );
    assert_eq!(
        parse(&[0x5A, 0x05, 0x07, 0x00, 0x66]),
        Reply::OutputEnable(false)
    );
    assert_eq!(
        parse(&[0x5A, 0x08, 0x06, 0x00, 0xC2, 0x01, 0x00, 0x2B]),
        Reply::Baud(115_200)
    );
    // TF03 manual §4.3.2: "Success: 5A 05 02 00 61".
    assert_eq!(
        parse(&[0x5A, 0x05, 0x02, 0x00, 0x61]),
        Reply::Status {
            command: command_id::SOFT_RESET,
            ok: true
        }
    );
    assert_eq!(
        parse(&encode_frame(command_id::SAVE, &[1])),
        Reply::Status {
            command: command_id::SAVE,
            ok: false
        }
    );
    assert_eq!(
        parse(&encode_frame(0x42, &[1, 2])),
        Reply::Unrecognised {
            id: 0x42,
            payload_len: 2
        }
    );
    // A version reply of the wrong size is not a version.
    assert_eq!(
        parse(&encode_frame(command_id::VERSION, &[1, 2])),
        Reply::Unrecognised {
            id: command_id::VERSION,
            payload_len: 2
        }
    );
}

#[test]
fn tfmini_s_manual_status_sums_do_not_follow_the_scheme() {
    // The TFmini-S manual prints the save reply as `5A 05 11 00 6F`; the sum
    // of 5A 05 11 00 is 0x70. The driver keeps to the scheme (as the TF03
    // manual's `5A 05 02 00 61` does): such a reply is rejected.
    assert_eq!(
        CommandFrame::parse(&[0x5A, 0x05, 0x11, 0x00, 0x6F]),
        Err(ReplyError::BadChecksum {
            expected: 0x70,
            found: 0x6F
        })
    );
}

#[test]
fn command_frame_parse_rejects_bad_lengths() {
    assert_eq!(CommandFrame::parse(&[]), Err(ReplyError::BadHeader));
    assert_eq!(CommandFrame::parse(&[0x5A]), Err(ReplyError::BadLength(0)));
    assert_eq!(
        CommandFrame::parse(&[0x5A, 3, 1]),
        Err(ReplyError::BadLength(3))
    );
    assert_eq!(
        CommandFrame::parse(&[0x5A, 17, 1]),
        Err(ReplyError::BadLength(17))
    );
    assert_eq!(
        CommandFrame::parse(&[0x5A, 5, 1, 0x60]),
        Err(ReplyError::LengthMismatch {
            expected: 5,
            got: 4
        })
    );
}

#[test]
fn every_command_round_trips_through_the_reply_parser() {
    let commands = [
        Command::FrameRate(250),
        Command::OutputFormat(DistanceUnit::Centimetre),
        Command::Baud(921_600),
        Command::OutputEnable(true),
    ];
    for command in commands {
        let frame = CommandFrame::parse(&command.encode()).unwrap();
        assert_eq!(frame.id(), command.id());
        assert_eq!(frame.payload(), command.payload().as_slice());
    }
}

#[test]
fn encode_frame_caps_the_payload() {
    let bytes = encode_frame(0x42, &[0; 40]);
    assert_eq!(bytes.len(), 16);
    assert_eq!(bytes[1], 16);
    assert!(CommandFrame::parse(&bytes).is_ok());
}
