//! Golden vectors of the codec pieces (spec C-42-03320B §6, §7, §8;
//! sensors.md §1.1 "Test vectors").

use super::support::*;
use crate::scip::*;

#[test]
fn encoding_golden_vectors() {
    assert_eq!(decode(b"1Dh"), Some(5432));
    assert_eq!(encode(5432, 3).as_deref(), Some(&b"1Dh"[..]));
    assert_eq!(decode(b"m2@0"), Some(16_000_000));
    assert_eq!(encode(16_000_000, 4).as_deref(), Some(&b"m2@0"[..]));
    assert_eq!(decode(b"CB"), Some(1234));
    assert_eq!(encode(1234, 2).as_deref(), Some(&b"CB"[..]));
}

#[test]
fn encoding_rejects_out_of_range() {
    assert_eq!(encode(4096, 2), None, "2 characters hold 12 bits");
    assert_eq!(encode(1, 5), None);
    assert_eq!(decode(b""), None);
    assert_eq!(decode(b"1Dp"), None, "'p' = 0x70 is above the encoding");
    assert_eq!(decode(b"/0"), None, "'/' = 0x2F is below it");
    assert_eq!(decode(b"ooooo"), None);
}

#[test]
fn line_sum_golden_vectors() {
    assert_eq!(line_sum(b"00"), b'P');
    assert_eq!(line_sum(b"99"), b'b');
    assert_eq!(strip_sum(b"00P"), Some(&b"00"[..]));
    assert_eq!(strip_sum(b"00Q"), None);
    assert_eq!(strip_sum(b"P"), None, "a sum needs a body");
}

#[test]
fn parameter_lines_accept_sum_with_or_without_separator() {
    assert_eq!(strip_parameter_sum(b"DMIN:20;4"), Some(&b"DMIN:20;"[..]));
    assert_eq!(strip_parameter_sum(b"AMIN:44;7"), Some(&b"AMIN:44;"[..]));
    // Summed over the ';' too ("AMIN:44;" sums to '2').
    assert_eq!(strip_parameter_sum(b"AMIN:44;2"), Some(&b"AMIN:44;"[..]));
    assert_eq!(strip_parameter_sum(b"AMIN:44;8"), None);
    let pairs = parse_pairs(&[b"DMIN:20;4".to_vec(), b"AMIN:44;7".to_vec()]).unwrap();
    assert_eq!(
        pairs,
        vec![("DMIN".into(), "20".into()), ("AMIN".into(), "44".into())]
    );
    assert_eq!(
        parse_pairs(&[b"DMIN:20;5".to_vec()]),
        Err(ParamError::BadChecksum)
    );
    assert_eq!(
        parse_pairs(&[b"DMIN20;".to_vec()]).map_err(|e| e.kind()),
        Err("bad_checksum")
    );
}

#[test]
fn pp_reply_gives_urg04lx_geometry() {
    let mut lines = LineSplitter::new();
    let mut replies = ReplyAssembler::new();
    let assembled: Vec<_> = URG04LX_PP
        .bytes()
        .filter_map(|b| lines.push(b))
        .filter_map(|e| replies.push(e))
        .collect();
    let [Assembled::Reply(reply)] = assembled.as_slice() else {
        panic!("one reply expected, got {assembled:?}");
    };
    assert_eq!(reply.echo, b"PP");
    assert_eq!(Status::parse(&reply.lines[0]), Ok(Status::OK));
    let pairs = parse_pairs(&reply.lines[1..]).unwrap();
    let geometry = ScipGeometry::from_pairs(&pairs).unwrap();
    assert_eq!(
        geometry,
        ScipGeometry {
            dmin_mm: 20,
            dmax_mm: 5600,
            ares: 1024,
            amin: 44,
            amax: 725,
            afrt: 384,
            scan_rpm: 600,
        }
    );
    assert_eq!(geometry.revolution_ns(), 100_000_000.0);
}

#[test]
fn pp_without_a_key_is_rejected() {
    let lines = [param("DMIN", "20"), param("DMAX", "5600")];
    let lines = lines.map(|l| l.trim_end().as_bytes().to_vec());
    let pairs = parse_pairs(&lines).unwrap();
    assert_eq!(
        ScipGeometry::from_pairs(&pairs),
        Err(ParamError::Missing("ARES"))
    );
}

#[test]
fn qt_reply_assembles() {
    assert_eq!(Command::Qt.to_bytes(None).unwrap(), b"QT\n");
    let mut lines = LineSplitter::new();
    let mut replies = ReplyAssembler::new();
    let got: Vec<_> = b"QT\n00P\n\n"
        .iter()
        .filter_map(|&b| lines.push(b))
        .filter_map(|e| replies.push(e))
        .collect();
    assert_eq!(
        got,
        vec![Assembled::Reply(Reply {
            echo: b"QT".to_vec(),
            lines: vec![b"00P".to_vec()],
            damaged: false,
        })]
    );
}

#[test]
fn command_builders() {
    let text = |c: Command| String::from_utf8(c.to_bytes(None).unwrap()).unwrap();
    assert_eq!(text(Command::Bm), "BM\n");
    assert_eq!(text(Command::Rs), "RS\n");
    assert_eq!(text(Command::Rb), "RB\n");
    assert_eq!(text(Command::Vv), "VV\n");
    assert_eq!(text(Command::Pp), "PP\n");
    assert_eq!(text(Command::Ii), "II\n");
    assert_eq!(text(Command::Tm(TimeMode::Enter)), "TM0\n");
    assert_eq!(text(Command::Tm(TimeMode::Read)), "TM1\n");
    assert_eq!(text(Command::Tm(TimeMode::Leave)), "TM2\n");
    assert_eq!(text(Command::SetBitRate(115_200)), "SS115200\n");
    assert_eq!(text(Command::SetBitRate(19_200)), "SS019200\n");
    assert_eq!(text(Command::Scip2), "SCIP2.0\n");
    let md = ScanRequest {
        kind: ScanKind::Md,
        start: 44,
        end: 725,
        cluster: 1,
        interval: 0,
        scans: 0,
    };
    assert_eq!(text(Command::Scan(md.clone())), "MD0044072501000\n");
    let gd = ScanRequest {
        kind: ScanKind::Gd,
        ..md.clone()
    };
    assert_eq!(text(Command::Scan(gd)), "GD0044072501\n");
    let me = ScanRequest {
        kind: ScanKind::Me,
        cluster: 3,
        interval: 2,
        scans: 10,
        ..md.clone()
    };
    let tag = Tag::new("a.b_c+d@1 2").unwrap();
    assert_eq!(
        Command::Scan(me).to_bytes(Some(&tag)).unwrap(),
        b"ME0044072503210;a.b_c+d@1 2\n"
    );
    assert_eq!(Tag::new("12345678901234567"), Err(CommandError::TagTooLong));
    assert_eq!(Tag::new("a;b"), Err(CommandError::TagCharacter));
    let too_far = ScanRequest { end: 10_000, ..md };
    assert!(Command::Scan(too_far).to_bytes(None).is_err());
}

#[test]
fn scan_echo_matching_ignores_only_the_remaining_count() {
    let md = ScanRequest {
        kind: ScanKind::Md,
        start: 44,
        end: 725,
        cluster: 1,
        interval: 0,
        scans: 0,
    };
    assert!(md.matches_echo(b"MD0044072501000", None));
    assert!(md.matches_echo(b"MD0044072501099", None));
    assert!(!md.matches_echo(b"MD00440725010x9", None));
    assert!(!md.matches_echo(b"MD0044072502000", None));
    assert!(!md.matches_echo(b"MS0044072501000", None));
    let gd = ScanRequest {
        kind: ScanKind::Gd,
        ..md
    };
    assert!(gd.matches_echo(b"GD0044072501", None));
    assert!(!gd.matches_echo(b"GD0044072502", None));
}

#[test]
fn value_count_rounds_partial_clusters_up() {
    let request = |start, end, cluster| ScanRequest {
        kind: ScanKind::Md,
        start,
        end,
        cluster,
        interval: 0,
        scans: 0,
    };
    assert_eq!(request(44, 725, 1).value_count(), 682);
    assert_eq!(request(44, 725, 2).value_count(), 341);
    assert_eq!(request(44, 725, 3).value_count(), 228);
    assert_eq!(request(0, 0, 1).value_count(), 1);
}

#[test]
fn line_splitter_takes_lf_cr_and_crlf() {
    let mut lines = LineSplitter::new();
    let got: Vec<_> = b"a\nb\rc\r\nd\r"
        .iter()
        .chain(b"\ne\n\n")
        .filter_map(|&b| lines.push(b))
        .collect();
    let line = |s: &str| LineEvent::Line(s.as_bytes().to_vec());
    assert_eq!(
        got,
        vec![
            line("a"),
            line("b"),
            line("c"),
            line("d"),
            line("e"),
            line("")
        ]
    );
}

#[test]
fn line_splitter_skips_oversize_lines() {
    let mut lines = LineSplitter::new();
    let mut input = vec![b'x'; MAX_LINE_LEN + 10];
    input.extend_from_slice(b"\nok\n");
    let got: Vec<_> = input.iter().filter_map(|&b| lines.push(b)).collect();
    assert_eq!(
        got,
        vec![LineEvent::Oversize, LineEvent::Line(b"ok".to_vec())]
    );
    let mut exact = vec![b'y'; MAX_LINE_LEN];
    exact.push(b'\n');
    let got: Vec<_> = exact.iter().filter_map(|&b| lines.push(b)).collect();
    assert_eq!(got, vec![LineEvent::Line(vec![b'y'; MAX_LINE_LEN])]);
}

#[test]
fn reply_assembler_drops_overlong_replies() {
    let mut replies = ReplyAssembler::new();
    let line = || LineEvent::Line(b"0Dh".to_vec());
    let mut got: Vec<_> = (0..MAX_REPLY_LINES + 5)
        .filter_map(|_| replies.push(line()))
        .collect();
    got.extend(replies.push(LineEvent::Line(Vec::new())));
    assert_eq!(got, vec![Assembled::Overflow]);
    replies.push(LineEvent::Line(b"QT".to_vec()));
    assert!(matches!(
        replies.push(LineEvent::Line(Vec::new())),
        Some(Assembled::Reply(r)) if r.echo == b"QT"
    ));
}

#[test]
fn status_codes_are_classified_and_named() {
    let class = |code: &[u8; 2]| Status(*code).class();
    assert_eq!(class(b"00"), StatusClass::Ok);
    assert_eq!(class(b"99"), StatusClass::Streaming);
    assert_eq!(class(b"98"), StatusClass::Resumed);
    assert_eq!(class(b"04"), StatusClass::ParameterError);
    assert_eq!(class(b"10"), StatusClass::LaserOff);
    assert_eq!(class(b"33"), StatusClass::Verifying);
    assert_eq!(class(b"50"), StatusClass::HardwareFault);
    assert_eq!(class(b"97"), StatusClass::HardwareFault);
    assert_eq!(class(b"0L"), StatusClass::Abnormal);
    assert_eq!(class(b"0E"), StatusClass::Unsupported);
    assert_eq!(class(b"0C"), StatusClass::InvalidCommand);
    assert_eq!(class(b"0I"), StatusClass::FirmwareUpdate);
    assert_eq!(class(b"15"), StatusClass::Other);
    assert_eq!(Status(*b"0L").error_kind(), "device_error_abnormal");
    assert_eq!(Status(*b"52").describe(), "52 (hardware trouble)");
    assert_eq!(Status::parse(b"99b"), Ok(Status(*b"99")));
    assert_eq!(Status::parse(b"0Ee"), Ok(Status(*b"0E")));
    assert_eq!(Status::parse(b"99c"), Err(StatusLineError::BadChecksum));
    assert_eq!(Status::parse(b"E"), Err(StatusLineError::Malformed));
}

#[test]
fn md_reply_for_urg04lx_with_a_value_straddling_lines() {
    let values = urg04lx_values();
    let bytes = streamed_scan(MD_FULL, 0x12345, &values, 3);
    let text = String::from_utf8(bytes.clone()).unwrap();
    let lines: Vec<&str> = text.split('\n').collect();
    assert_eq!(lines[0], "MD0044072501000");
    assert_eq!(lines[1], "99b");
    assert_eq!(lines[2].len(), 5, "4-character timestamp and its sum");
    // 682 values * 3 = 2046 characters: 31 full lines and one of 62.
    assert_eq!(lines.len(), 3 + 32 + 2);
    assert!(lines[3..34].iter().all(|l| l.len() == 65));
    assert_eq!(lines[34].len(), 63);
    // Value 21 (5432 = "1Dh") starts at character 63 of the first line.
    assert_eq!(&lines[3][63..64], "1");
    assert_eq!(&lines[4][..2], "Dh");

    let request = ScanRequest {
        kind: ScanKind::Md,
        start: 44,
        end: 725,
        cluster: 1,
        interval: 0,
        scans: 0,
    };
    let data_lines: Vec<Vec<u8>> = lines[2..35].iter().map(|l| l.as_bytes().to_vec()).collect();
    let data = decode_scan(&data_lines, &request).unwrap();
    assert_eq!(data.timestamp_ms, 0x12345);
    assert_eq!(data.ranges, values);
    assert_eq!(data.intensities, None);
}

#[test]
fn scan_data_errors_are_named() {
    let request = ScanRequest {
        kind: ScanKind::Md,
        start: 0,
        end: 1,
        cluster: 1,
        interval: 0,
        scans: 0,
    };
    let lines = |v: &[String]| {
        v.iter()
            .map(|l| l.trim_end().as_bytes().to_vec())
            .collect::<Vec<_>>()
    };
    let good = scan_lines(7, &[100, 200], 3);
    assert_eq!(
        decode_scan(&lines(&good), &request).unwrap().ranges,
        vec![100, 200]
    );
    let short = scan_lines(7, &[100], 3);
    assert_eq!(
        decode_scan(&lines(&short), &request).unwrap_err().kind(),
        "incomplete_scan"
    );
    let long = scan_lines(7, &[100, 200, 300], 3);
    assert_eq!(
        decode_scan(&lines(&long), &request).unwrap_err().kind(),
        "malformed_reply"
    );
    let mut bad = lines(&good);
    bad[1][0] ^= 1;
    assert_eq!(
        decode_scan(&bad, &request).unwrap_err().kind(),
        "bad_checksum"
    );
}

#[test]
fn me_data_interleaves_range_and_intensity() {
    let request = ScanRequest {
        kind: ScanKind::Me,
        start: 10,
        end: 12,
        cluster: 1,
        interval: 0,
        scans: 0,
    };
    let raw: Vec<String> = scan_lines(1, &[500, 70, 600, 80, 700, 90], 3);
    let lines: Vec<Vec<u8>> = raw
        .iter()
        .map(|l| l.trim_end().as_bytes().to_vec())
        .collect();
    let data = decode_scan(&lines, &request).unwrap();
    assert_eq!(data.ranges, vec![500, 600, 700]);
    assert_eq!(data.intensities, Some(vec![70, 80, 90]));
}

#[test]
fn ms_data_uses_two_characters() {
    let request = ScanRequest {
        kind: ScanKind::Ms,
        start: 0,
        end: 2,
        cluster: 1,
        interval: 0,
        scans: 0,
    };
    let raw = scan_lines(1, &[1234, 20, 4095], 2);
    let lines: Vec<Vec<u8>> = raw
        .iter()
        .map(|l| l.trim_end().as_bytes().to_vec())
        .collect();
    assert_eq!(
        decode_scan(&lines, &request).unwrap().ranges,
        vec![1234, 20, 4095]
    );
}
