//! Tests of the DBC codec: golden frames of the shipped devices (bytes worked
//! out by hand from research note §2.1/§2.2), layouts, multiplexing, every
//! validation, and property tests that nothing panics and every shipped signal
//! round-trips.

use proptest::prelude::*;

use super::*;
use crate::can::CanFrame;

/// Equal up to float rounding of `raw * factor + offset`.
fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * b.abs().max(1.0)
}

fn frame(id: u32, extended: bool, data: &[u8]) -> CanFrame {
    CanFrame::new(id, extended, data).unwrap()
}

fn db(name: &str) -> CanDatabase {
    builtin(name).unwrap()
}

/// Decodes `frame` with `db` and checks each `(signal, value)`.
fn assert_decodes(db: &CanDatabase, frame: &CanFrame, expected: &[(&str, f64)]) {
    let decoded = db.decode(frame).expect("id in database").unwrap();
    for (name, want) in expected {
        let got = decoded.get(name).unwrap_or(f64::NAN);
        assert!(close(got, *want), "{name}: got {got}, want {want}");
    }
}

/// Wraps message/signal lines into a minimal DBC file.
fn dbc(body: &str) -> String {
    format!("VERSION \"\"\n\nNS_ :\n\nBS_:\n\nBU_: X Y\n\n{body}\n")
}

fn parse_err(body: &str) -> DbcError {
    match CanDatabase::parse(&dbc(body)) {
        Ok(_) => panic!("parsed:\n{body}"),
        Err(e) => e,
    }
}

// ---------------------------------------------------------------- golden frames

#[test]
fn ars408_cluster_general_golden() {
    // Research note §2.2 test vector: 701#034FB2048020018A.
    let db = db("ars408");
    let f = frame(
        0x701,
        false,
        &[0x03, 0x4F, 0xB2, 0x04, 0x80, 0x20, 0x01, 0x8A],
    );
    assert_decodes(
        &db,
        &f,
        &[
            ("ID", 3.0),
            ("DistLong", 10.0),
            ("DistLat", 0.9),
            ("VrelLong", 0.0),
            ("VrelLat", 0.0),
            ("DynProp", 1.0),
            ("RCS", 5.0),
        ],
    );
    // And back: the same bytes.
    let back = db
        .encode(
            "Cluster_1_General",
            &[
                ("ID", 3.0),
                ("DistLong", 10.0),
                ("DistLat", 0.9),
                ("VrelLong", 0.0),
                ("VrelLat", 0.0),
                ("DynProp", 1.0),
                ("RCS", 5.0),
            ],
        )
        .unwrap();
    assert_eq!(back, f);
}

#[test]
fn ars408_radar_configuration_tier4_example() {
    // `cansend can0 200#F8000000089C0000` (tier4/ars408_driver README).
    let db = db("ars408");
    let bytes = [0xF8, 0x00, 0x00, 0x00, 0x08, 0x9C, 0x00, 0x00];
    let set = [
        "OutputType_valid",
        "SendQuality_valid",
        "SendExtInfo_valid",
        "SortIndex_valid",
        "StoreInNVM_valid",
        "SendQuality",
        "SendExtInfo",
        "SortIndex",
        "StoreInNVM",
        "OutputType",
    ];
    let m = db.message("RadarConfiguration").unwrap();
    let decoded = m.decode(&frame(0x200, false, &bytes)).unwrap();
    for (name, value) in decoded.iter() {
        let want = if set.contains(&name) { 1.0 } else { 0.0 };
        assert_eq!(value, want, "{name}");
    }
    assert_eq!(decoded.iter().count(), 20);
    let values: Vec<(&str, f64)> = m
        .signals
        .iter()
        .map(|s| {
            (
                s.name.as_str(),
                if set.contains(&s.name.as_str()) {
                    1.0
                } else {
                    0.0
                },
            )
        })
        .collect();
    assert_eq!(m.encode(&values).unwrap().payload(), &bytes);
}

#[test]
fn ars408_radar_state_straddling_fields() {
    // MaxDistanceCfg 15|10 = 100 (200 m): byte1 = 100 >> 2, byte2 bits 7..6 = 100 & 3.
    // RadarPowerCfg 25|3 = 0b101: bits 25, 24, then 39. SensorID 34|3 = 3 (bits 33, 32).
    // RCS_Threshold 60|3 = 1 (bit 58). VoltageError bit 17.
    let db = db("ars408");
    let f = frame(
        0x201,
        false,
        &[0x00, 0x19, 0x02, 0x02, 0x83, 0x00, 0x00, 0x04],
    );
    assert_decodes(
        &db,
        &f,
        &[
            ("MaxDistanceCfg", 200.0),
            ("VoltageError", 1.0),
            ("PersistentError", 0.0),
            ("RadarPowerCfg", 5.0),
            ("SensorID", 3.0),
            ("SortIndex", 0.0),
            ("RCS_Threshold", 1.0),
        ],
    );
}

#[test]
fn tf03_little_endian_golden() {
    // Dist 1234 cm = 0x04D2, Strength 567 = 0x0237, both LE, then two
    // reserved bytes: 6 in all (research note §2.1, TF03 manual p.12).
    let db = db("benewake_tf03");
    let f = frame(0x003, false, &[0xD2, 0x04, 0x37, 0x02, 0, 0]);
    assert_decodes(&db, &f, &[("Dist", 1234.0), ("Strength", 567.0)]);
    let back = db
        .encode("TF03_Measurement", &[("Dist", 1234.0), ("Strength", 567.0)])
        .unwrap();
    assert_eq!(back, f);
}

#[test]
fn tfmini_i_timestamp_golden() {
    let db = db("benewake_tfmini_i");
    let f = frame(
        0x003,
        false,
        &[0xD2, 0x04, 0x37, 0x02, 0x78, 0x56, 0x34, 0x12],
    );
    assert_decodes(
        &db,
        &f,
        &[
            ("Dist", 1234.0),
            ("Strength", 567.0),
            ("Timestamp", f64::from(0x1234_5678u32)),
        ],
    );
}

#[test]
fn tf02_legacy_big_endian_extended_golden() {
    // Extended id 0x00090002; B0 DIST_H, B1 DIST_L, B2-3 STRENGTH BE, B4 time, B5 SIG.
    let db = db("benewake_tf02");
    let f = frame(
        0x0009_0002,
        true,
        &[0x04, 0xD2, 0x02, 0x37, 0x10, 0x08, 0, 0],
    );
    assert_decodes(
        &db,
        &f,
        &[
            ("Dist", 1234.0),
            ("Strength", 567.0),
            ("ExposureTime", 16.0),
            ("Reliability", 8.0),
        ],
    );
    // The same id as a standard frame is another device's.
    assert!(db.message_by_id(0x0009_0002, false).is_none());
    let m = db.message("TF02_Measurement").unwrap();
    assert_eq!((m.id, m.extended, m.len), (0x0009_0002, true, 8));
}

// ---------------------------------------------------------------- layouts

const LAYOUT: &str = "BO_ 291 Layout: 8 X
 SG_ IntelStraddle : 12|10@1+ (1,0) [0|0] \"\" Y
 SG_ MotoStraddle : 34|10@0+ (1,0) [0|0] \"\" Y
 SG_ IntelSigned : 24|8@1- (0.5,0) [0|0] \"\" Y
 SG_ MotoSigned : 55|12@0- (1,0) [0|0] \"\" Y
";

#[test]
fn straddling_and_signed_layouts_match_hand_computed_bytes() {
    let db = CanDatabase::parse(&dbc(LAYOUT)).unwrap();
    // IntelStraddle 0x2AB at bits 12..21: byte1 = 0xB0, byte2 = 0x2A.
    // MotoStraddle 0x2AB, MSB at bit 34: byte4 bits 2..0 = 0b101, byte5 bits 7..1 = 0b0101011.
    // IntelSigned -3.5 / 0.5 = -7 = 0xF9 in byte 3.
    // MotoSigned -1000 = 0xC18 (12 bits), MSB at bit 55: byte6 = 0xC1, byte7 = 0x80.
    let bytes = [0x00, 0xB0, 0x2A, 0xF9, 0x05, 0x56, 0xC1, 0x80];
    let f = db
        .encode(
            "Layout",
            &[
                ("IntelStraddle", 683.0),
                ("MotoStraddle", 683.0),
                ("IntelSigned", -3.5),
                ("MotoSigned", -1000.0),
            ],
        )
        .unwrap();
    assert_eq!(f.payload(), &bytes);
    assert_decodes(
        &db,
        &frame(0x123, false, &bytes),
        &[
            ("IntelStraddle", 683.0),
            ("MotoStraddle", 683.0),
            ("IntelSigned", -3.5),
            ("MotoSigned", -1000.0),
        ],
    );
    let m = db.message("Layout").unwrap();
    assert_eq!(m.signal("MotoSigned").unwrap().raw(&bytes), 0xC18);
}

// ---------------------------------------------------------------- multiplexing

const MUX: &str = "BO_ 100 Mux: 4 X
 SG_ Page M : 0|8@1+ (1,0) [0|0] \"\" Y
 SG_ Temp m0 : 8|16@1- (0.1,0) [0|0] \"degC\" Y
 SG_ Volt m1 : 8|16@1+ (0.01,0) [0|0] \"V\" Y
 SG_ Count : 24|8@1+ (1,0) [0|0] \"\" Y
";

#[test]
fn multiplexed_signals_follow_their_multiplexor() {
    let db = CanDatabase::parse(&dbc(MUX)).unwrap();
    let m = db.message("Mux").unwrap();
    assert_eq!(m.multiplexor().map(|s| s.name.as_str()), Some("Page"));
    assert_eq!(
        m.signal("Volt").unwrap().multiplex,
        Multiplex::Multiplexed(1)
    );

    // Page 0: Temp = 0xFFE7 = -25 raw = -2.5 degC.
    let d = m.decode(&frame(100, false, &[0, 0xE7, 0xFF, 5])).unwrap();
    assert_eq!(d.get("Page"), Some(0.0));
    assert!(close(d.get("Temp").unwrap(), -2.5));
    assert_eq!(d.get("Volt"), None);
    assert_eq!(d.get("Count"), Some(5.0));

    // Page 1: Volt = 1000 * 0.01.
    let d = m.decode(&frame(100, false, &[1, 0xE8, 0x03, 5])).unwrap();
    assert_eq!(d.get("Temp"), None);
    assert!(close(d.get("Volt").unwrap(), 10.0));

    // Page 2 selects neither.
    let d = m.decode(&frame(100, false, &[2, 0xE8, 0x03, 5])).unwrap();
    assert_eq!(d.values.iter().filter(|v| v.is_none()).count(), 2);

    // Encoding writes only the selected page; the other page's value is ignored.
    let f = m
        .encode(&[
            ("Page", 1.0),
            ("Volt", 10.0),
            ("Temp", -2.5),
            ("Count", 5.0),
        ])
        .unwrap();
    assert_eq!(f.payload(), &[1, 0xE8, 0x03, 5]);
    assert!(matches!(
        m.encode(&[("Page", 0.0), ("Volt", 10.0), ("Count", 5.0)]),
        Err(DbcError::MissingSignal { signal, .. }) if signal == "Temp"
    ));
    assert!(m.encode(&[("Page", 2.0), ("Count", 5.0)]).is_ok());
}

// ---------------------------------------------------------------- encode refusals

#[test]
fn encode_refuses_bad_values_and_names() {
    let db = db("benewake_tf03");
    let ok = [("Dist", 1.0), ("Strength", 2.0)];
    assert!(db.encode("TF03_Measurement", &ok).is_ok());
    assert!(matches!(
        db.encode("TF03_Measurement", &[("Dist", 65536.0), ("Strength", 2.0)]),
        Err(DbcError::ValueOutOfRange { message, signal, .. })
            if message == "TF03_Measurement" && signal == "Dist"
    ));
    assert!(matches!(
        db.encode("TF03_Measurement", &[("Dist", -1.0), ("Strength", 2.0)]),
        Err(DbcError::ValueOutOfRange { .. })
    ));
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        assert!(matches!(
            db.encode("TF03_Measurement", &[("Dist", bad), ("Strength", 2.0)]),
            Err(DbcError::ValueOutOfRange { .. })
        ));
    }
    assert_eq!(
        db.encode("TF03_Measurement", &[("Dist", 1.0)]),
        Err(DbcError::MissingSignal {
            message: "TF03_Measurement".into(),
            signal: "Strength".into()
        })
    );
    assert_eq!(
        db.encode(
            "TF03_Measurement",
            &[("Dist", 1.0), ("Strength", 2.0), ("Bogus", 0.0)]
        ),
        Err(DbcError::UnknownSignal {
            message: "TF03_Measurement".into(),
            signal: "Bogus".into()
        })
    );
    assert_eq!(
        db.encode("Nope", &ok),
        Err(DbcError::UnknownMessage("Nope".into()))
    );
    // The range's own ends encode, half a step past them does not.
    let ars = self::db("ars408");
    let cluster = |dist_long: f64| {
        ars.encode(
            "Cluster_1_General",
            &[
                ("ID", 0.0),
                ("DistLong", dist_long),
                ("DistLat", 0.9),
                ("VrelLong", 0.0),
                ("VrelLat", 0.0),
                ("DynProp", 0.0),
                ("RCS", 0.0),
            ],
        )
    };
    assert!(cluster(-500.0).is_ok());
    assert!(cluster(1138.2).is_ok());
    assert!(cluster(1138.4).is_err());
    assert!(cluster(-500.2).is_err());
}

#[test]
fn database_decode_sorts_frames() {
    let db = db("ars408");
    assert!(db.decode(&frame(0x123, false, &[0; 8])).is_none());
    assert!(db.decode(&frame(0x701, true, &[0; 8])).is_none());
    assert_eq!(
        db.decode(&frame(0x701, false, &[0; 4])),
        Some(Err(DbcError::ShortFrame {
            message: "Cluster_1_General".into(),
            found: 4,
            expected: 8
        }))
    );
    let remote = CanFrame::remote(0x600, false, 5).unwrap();
    assert!(matches!(
        db.decode(&remote),
        Some(Err(DbcError::ShortFrame { .. }))
    ));
}

#[test]
fn id_offset_moves_every_id() {
    let db = db("ars408");
    let moved = db.with_id_offset(0x10).unwrap();
    assert_eq!(moved.message("RadarState").unwrap().id, 0x211);
    assert_eq!(moved.message("Cluster_1_General").unwrap().id, 0x711);
    assert!(moved.message_by_id(0x201, false).is_none());
    assert_eq!(
        moved.message_by_id(0x61A, false).map(|m| m.name.as_str()),
        Some("Obj_0_Status")
    );
    let f = frame(
        0x711,
        false,
        &[0x03, 0x4F, 0xB2, 0x04, 0x80, 0x20, 0x01, 0x8A],
    );
    assert_decodes(&moved, &f, &[("DistLong", 10.0)]);
    for (a, b) in db.messages().iter().zip(moved.messages()) {
        assert_eq!(a.id + 0x10, b.id);
    }
    // Cluster_1_General 0x701 + 0x100 is the first to leave the 11-bit range.
    assert!(matches!(
        db.with_id_offset(0x100),
        Err(DbcError::BadId { message, id: 0x801 }) if message == "Cluster_1_General"
    ));
    assert!(matches!(
        self::db("benewake_tf02").with_id_offset(0x1FFF_0000),
        Err(DbcError::BadId { .. })
    ));
}

#[test]
fn builtin_messages_have_the_agreed_names() {
    // (message, id, len, signal count) per database.
    type Expected<'a> = &'a [(&'a str, u32, u8, usize)];
    let expected: [(&str, Expected); 4] = [
        (
            "ars408",
            &[
                ("RadarState", 0x201, 8, 16),
                ("RadarConfiguration", 0x200, 8, 20),
                ("Cluster_0_Status", 0x600, 5, 4),
                ("Cluster_1_General", 0x701, 8, 7),
                ("Cluster_2_Quality", 0x702, 5, 8),
                ("Obj_0_Status", 0x60A, 4, 3),
                ("Obj_1_General", 0x60B, 8, 7),
                ("Obj_2_Quality", 0x60C, 7, 10),
                ("Obj_3_Extended", 0x60D, 8, 7),
                ("VersionID", 0x700, 4, 5),
            ],
        ),
        ("benewake_tf03", &[("TF03_Measurement", 0x003, 6, 2)]),
        ("benewake_tfmini_i", &[("TFminiI_Measurement", 0x003, 8, 3)]),
        ("benewake_tf02", &[("TF02_Measurement", 0x0009_0002, 8, 4)]),
    ];
    for (name, messages) in expected {
        let db = db(name);
        assert_eq!(db.messages().len(), messages.len(), "{name}");
        for (message, id, len, signals) in messages {
            let m = db.message(message).unwrap_or_else(|| panic!("{message}"));
            assert_eq!(
                (m.id, m.len, m.signals.len()),
                (*id, *len, *signals),
                "{message}"
            );
        }
    }
    let ars = db("ars408");
    for m in ["Cluster_1_General", "Obj_1_General"] {
        let m = ars.message(m).unwrap();
        for s in [
            "ID", "DistLong", "DistLat", "VrelLong", "VrelLat", "DynProp", "RCS",
        ] {
            assert!(m.signal(s).is_some(), "{s}");
        }
    }
    let dist_long = ars
        .message("Cluster_1_General")
        .unwrap()
        .signal("DistLong")
        .unwrap();
    assert_eq!((dist_long.min, dist_long.max), (-500.0, 1138.2));
    assert_eq!(dist_long.unit, "m");
    assert_eq!(dist_long.order, ByteOrder::Motorola);
}

#[test]
fn builtin_signals_do_not_overlap() {
    for (name, _) in BUILTIN {
        for m in db(name).messages() {
            let mut used = [0u8; 8];
            for s in &m.signals {
                // All ones in the signal's bits, nothing elsewhere.
                let mut bits = [0u8; 8];
                let all_ones = if s.signed {
                    s.offset - s.factor // raw -1
                } else {
                    (2f64.powi(i32::from(s.size)) - 1.0) * s.factor + s.offset
                };
                s.encode(all_ones, &mut bits).unwrap();
                assert_eq!(s.raw(&bits).count_ones(), u32::from(s.size), "{}", s.name);
                for (u, b) in used.iter_mut().zip(bits) {
                    assert_eq!(*u & b, 0, "{name} {}: {} overlaps", m.name, s.name);
                    *u |= b;
                }
            }
        }
    }
}

// ---------------------------------------------------------------- parse validation

#[test]
fn every_validation_has_its_error() {
    let sig = |def: &str| format!("BO_ 16 M: 8 X\n SG_ {def} \"\" Y");
    type Check = fn(&DbcError) -> bool;
    let cases: Vec<(String, Check)> = vec![
        ("BO_ oops".into(), |e| matches!(e, DbcError::Parse(_))),
        (
            "BO_ 16 A: 8 X\n SG_ S : 0|8@1+ (1,0) [0|0] \"\" Y\n\nBO_ 16 B: 8 X\n".into(),
            |e| matches!(e, DbcError::DuplicateId { id: 16, extended: false, first, second } if first == "A" && second == "B"),
        ),
        ("BO_ 16 A: 8 X\n\nBO_ 17 A: 8 X\n".into(), |e| {
            matches!(e, DbcError::DuplicateMessage(n) if n == "A")
        }),
        (
            "BO_ 16 M: 8 X\n SG_ S : 0|8@1+ (1,0) [0|0] \"\" Y\n SG_ S : 8|8@1+ (1,0) [0|0] \"\" Y\n".into(),
            |e| matches!(e, DbcError::DuplicateSignal { signal, .. } if signal == "S"),
        ),
        ("BO_ 2048 M: 8 X\n".into(), |e| matches!(e, DbcError::BadId { id: 2048, .. })),
        // can-dbc keeps only the low 16 bits: 65552 would pass as 0x10.
        ("BO_ 65552 M: 8 X\n".into(), |e| matches!(e, DbcError::BadId { id: 65552, .. })),
        // Bit 30 set besides the extended flag: 0x4000_0001 is no 29-bit id.
        ("BO_ 3221225473 M: 8 X\n".into(), |e| {
            matches!(e, DbcError::BadId { id: 0x4000_0001, .. })
        }),
        ("BO_ 16 M: 9 X\n".into(), |e| matches!(e, DbcError::BadLength { len: 9, .. })),
        (sig("S : 60|8@1+ (1,0) [0|0]"), |e| {
            matches!(e, DbcError::SignalOutOfFrame { start_bit: 60, size: 8, len: 8, .. })
        }),
        (
            "BO_ 16 M: 1 X\n SG_ S : 7|16@0+ (1,0) [0|0] \"\" Y".into(),
            |e| matches!(e, DbcError::SignalOutOfFrame { len: 1, .. }),
        ),
        (sig("S : 99999|8@1+ (1,0) [0|0]"), |e| {
            matches!(e, DbcError::SignalOutOfFrame { .. })
        }),
        (sig("S : 0|0@1+ (1,0) [0|0]"), |e| matches!(e, DbcError::BadSignal { .. })),
        (sig("S : 0|65@1+ (1,0) [0|0]"), |e| matches!(e, DbcError::BadSignal { .. })),
        (sig("S : 0|8@1+ (0,0) [0|0]"), |e| matches!(e, DbcError::BadSignal { .. })),
        (sig("S : 0|8@1+ (1e999,0) [0|0]"), |e| matches!(e, DbcError::BadSignal { .. })),
        (sig("S : 0|8@1+ (1,1e999) [0|0]"), |e| matches!(e, DbcError::BadSignal { .. })),
        (sig("S : 0|8@1+ (1,0) [5|1]"), |e| matches!(e, DbcError::BadSignal { .. })),
        (
            format!("{}\n\nSIG_VALTYPE_ 16 S : 1;\n", sig("S : 0|32@1+ (1,0) [0|0]")),
            |e| matches!(e, DbcError::BadSignal { message, signal, .. } if message == "M" && signal == "S"),
        ),
        (
            "BO_ 16 M: 8 X\n SG_ A M : 0|8@1+ (1,0) [0|0] \"\" Y\n SG_ B m1M : 8|8@1+ (1,0) [0|0] \"\" Y\n SG_ C m2 : 16|8@1+ (1,0) [0|0] \"\" Y\n".into(),
            |e| matches!(e, DbcError::BadSignal { signal, .. } if signal == "B"),
        ),
        (
            "BO_ 16 M: 8 X\n SG_ A M : 0|8@1+ (1,0) [0|0] \"\" Y\n SG_ C m2 : 16|8@1+ (1,0) [0|0] \"\" Y\n\nSG_MUL_VAL_ 16 C A 2-3;\n".into(),
            |e| matches!(e, DbcError::BadSignal { signal, .. } if signal == "C"),
        ),
        (sig("S m1 : 0|8@1+ (1,0) [0|0]"), |e| {
            matches!(e, DbcError::BadMultiplex { .. })
        }),
        (
            "BO_ 16 M: 8 X\n SG_ A M : 0|8@1+ (1,0) [0|0] \"\" Y\n SG_ B M : 8|8@1+ (1,0) [0|0] \"\" Y\n".into(),
            |e| matches!(e, DbcError::BadMultiplex { .. }),
        ),
    ];
    for (body, is_expected) in cases {
        let e = parse_err(&body);
        assert!(is_expected(&e), "{body}\n-> {e:?}");
    }
}

#[test]
fn parse_errors_say_where() {
    let DbcError::Parse(text) = parse_err("BO_ 16 M: 8 X\n SG_ S : 0|8@1+ (1,0 [0|0] \"\" Y")
    else {
        panic!("not a parse error")
    };
    assert!(text.contains(':'), "{text}");
}

#[test]
fn size_and_count_limits() {
    let big = " ".repeat(MAX_DBC_BYTES + 1);
    assert_eq!(
        CanDatabase::parse(&big),
        Err(DbcError::TooLarge {
            bytes: MAX_DBC_BYTES + 1,
            limit: MAX_DBC_BYTES
        })
    );
    let many: String = (0..=MAX_MESSAGES)
        .map(|i| format!("BO_ {} M{i}: 0 X\n\n", i | (1 << 31)))
        .collect();
    assert_eq!(
        CanDatabase::parse(&dbc(&many)),
        Err(DbcError::TooManyMessages {
            found: MAX_MESSAGES + 1,
            limit: MAX_MESSAGES
        })
    );
    // Vector's pseudo-message for unassigned signals is not a frame: skipped.
    let db = CanDatabase::parse(&dbc(
        "BO_ 3221225472 VECTOR__INDEPENDENT_SIG_MSG: 0 Vector__XXX\n SG_ Lost : 0|8@1+ (1,0) [0|0] \"\" Y\n",
    ))
    .unwrap();
    assert!(db.messages().is_empty());
}

// ---------------------------------------------------------------- properties

/// Every (database, message) of the shipped files.
fn builtin_messages() -> Vec<MessageSpec> {
    BUILTIN
        .iter()
        .flat_map(|(name, _)| db(name).messages().to_vec())
        .collect()
}

/// One line-level or byte-level edit of a DBC text.
#[derive(Debug, Clone)]
enum Mutation {
    DeleteLine(usize),
    DuplicateLine(usize),
    ReplaceLine(usize, String),
    FlipByte(usize, u8),
    Truncate(usize),
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        any::<usize>().prop_map(Mutation::DeleteLine),
        any::<usize>().prop_map(Mutation::DuplicateLine),
        (
            any::<usize>(),
            prop_oneof![
                "\\PC{0,40}",
                " SG_ [A-Z]{1,3} [Mm0-9]{0,3} : [0-9]{1,5}\\|[0-9]{1,3}@[01][+-] \\([0-9e.-]{1,6},[0-9e.-]{1,6}\\) \\[[0-9.-]{1,6}\\|[0-9.-]{1,6}\\] \"\" HOST",
                "BO_ [0-9]{1,11} [A-Z]{1,3}: [0-9]{1,3} X",
                "SIG_VALTYPE_ [0-9]{1,4} [A-Z]{1,3} : [0-3];",
            ]
        )
            .prop_map(|(i, l)| Mutation::ReplaceLine(i, l)),
        (any::<usize>(), any::<u8>()).prop_map(|(i, b)| Mutation::FlipByte(i, b)),
        any::<usize>().prop_map(Mutation::Truncate),
    ]
}

fn mutate(text: &str, mutations: &[Mutation]) -> String {
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    let mut bytes_edits = Vec::new();
    for m in mutations {
        let n = lines.len().max(1);
        match m {
            Mutation::DeleteLine(i) if !lines.is_empty() => {
                lines.remove(i % n);
            }
            Mutation::DuplicateLine(i) if !lines.is_empty() => {
                let l = lines[i % n].clone();
                lines.insert(i % n, l);
            }
            Mutation::ReplaceLine(i, l) if !lines.is_empty() => lines[i % n] = l.clone(),
            other => bytes_edits.push(other.clone()),
        }
    }
    let mut bytes = lines.join("\n").into_bytes();
    for m in bytes_edits {
        match m {
            Mutation::FlipByte(i, b) if !bytes.is_empty() => {
                let n = bytes.len();
                bytes[i % n] ^= b;
            }
            Mutation::Truncate(i) => bytes.truncate(i % (bytes.len() + 1)),
            _ => {}
        }
    }
    String::from_utf8_lossy(&bytes).into_owned()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn builtin_signals_round_trip(
        message in 0usize..64,
        seeds in proptest::collection::vec(any::<u64>(), 20),
    ) {
        let messages = builtin_messages();
        let m = &messages[message % messages.len()];
        // One value per signal, spread over the signal's whole raw range.
        let values: Vec<(&str, f64)> = m
            .signals
            .iter()
            .zip(&seeds)
            .map(|(s, seed)| {
                let raw = seed >> (64 - u32::from(s.size));
                let raw = if s.signed {
                    (raw as f64) - 2f64.powi(i32::from(s.size) - 1)
                } else {
                    raw as f64
                };
                (s.name.as_str(), raw * s.factor + s.offset)
            })
            .collect();
        let f = m.encode(&values).unwrap();
        prop_assert_eq!(usize::from(f.len), usize::from(m.len));
        let d = m.decode(&f).unwrap();
        for (name, want) in &values {
            let got = d.get(name).unwrap();
            prop_assert!(close(got, *want), "{} {}: got {}, want {}", m.name, name, got, want);
        }
    }

    #[test]
    fn random_frames_decode_without_panic(
        id in 0u32..0x800,
        extended in any::<bool>(),
        data in proptest::collection::vec(any::<u8>(), 0..=8),
    ) {
        let mux = CanDatabase::parse(&dbc(MUX)).unwrap();
        let layout = CanDatabase::parse(&dbc(LAYOUT)).unwrap();
        let f = frame(id, extended, &data);
        for m in builtin_messages().iter().chain(mux.messages()).chain(layout.messages()) {
            let _ = m.decode(&f);
            let mut at_id = f;
            at_id.id = m.id;
            at_id.extended = m.extended;
            if let Ok(d) = m.decode(&at_id) {
                prop_assert_eq!(d.values.len(), m.signals.len());
                for (_, v) in d.iter() {
                    prop_assert!(v.is_finite());
                }
            }
        }
    }

    #[test]
    fn mutated_builtin_text_never_panics(
        file in 0usize..4,
        mutations in proptest::collection::vec(mutation(), 1..6),
    ) {
        let (_, text) = BUILTIN[file];
        let mutated = mutate(text, &mutations);
        if let Ok(db) = CanDatabase::parse(&mutated) {
            // Whatever was accepted decodes and encodes without panicking.
            for m in db.messages() {
                let _ = m.decode(&frame(0, false, &[0xA5; 8]));
                let values: Vec<(&str, f64)> =
                    m.signals.iter().map(|s| (s.name.as_str(), s.min)).collect();
                let _ = m.encode(&values);
            }
        }
    }

    #[test]
    fn random_text_never_panics(text in "\\PC{0,200}") {
        let _ = CanDatabase::parse(&text);
        let _ = CanDatabase::parse(&dbc(&text));
    }

    #[test]
    fn encode_never_panics_on_any_value(value in any::<f64>(), message in 0usize..64) {
        let messages = builtin_messages();
        let m = &messages[message % messages.len()];
        let values: Vec<(&str, f64)> =
            m.signals.iter().map(|s| (s.name.as_str(), value)).collect();
        if let Ok(f) = m.encode(&values) {
            prop_assert!(m.decode(&f).is_ok());
        }
    }
}
