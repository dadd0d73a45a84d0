//! Scripted handshakes: what the host writes, and the sensor bytes written by
//! hand from the spec (sums from the spec's rule, see `support`).

use super::support::*;
use crate::device::{DeviceDriver, DeviceState, DriverOutput};
use crate::scip::*;

/// Checks that the outputs' writes are exactly `expected`.
fn assert_writes(out: &[DriverOutput], expected: &[&str]) {
    assert_eq!(writes(out), expected, "outputs: {out:?}");
}

#[test]
fn usb_handshake_transcript() {
    let mut rig = Rig::new(ScipConfig::default());
    let out = rig.connect();
    assert_eq!(
        out,
        vec![
            DriverOutput::State(DeviceState::Connecting),
            DriverOutput::FlushInput,
            DriverOutput::Write(b"QT\n".to_vec()),
        ]
    );

    let out = rig.feed(b"QT\n00P\n\n");
    assert_eq!(out[0], DriverOutput::State(DeviceState::Configuring));
    assert_writes(&out, &["VV\n"]);

    assert_writes(&rig.feed(&vv_reply()), &["PP\n"]);
    assert_writes(&rig.feed(URG04LX_PP.as_bytes()), &["II\n"]);
    assert_eq!(rig.driver.geometry().map(|g| g.ares), Some(1024));

    let out = rig.feed(&ii_reply("Sensor works well."));
    assert!(out.contains(&DriverOutput::Health {
        ok: true,
        detail: "STAT: Sensor works well.".into()
    }));
    assert_writes(&out, &["TM0\n"]);

    assert_writes(&rig.feed(b"TM0\n00P\n\n"), &["TM1\n"]);
    let out = rig.answer_tm1(5);
    assert_writes(&out, &["TM1\n", "TM1\n", "TM1\n", "TM1\n", "TM2\n"]);
    assert_writes(&rig.feed(b"TM2\n00P\n\n"), &["MD0044072501000\n"]);

    let out = rig.feed(b"MD0044072501000\n00P\n\n");
    assert_eq!(out[0], DriverOutput::State(DeviceState::Streaming));
    let pairs = identity(&out).expect("identity at stream start");
    assert_eq!(
        identity_value(&pairs, "PROD").as_deref(),
        Some("SOKUIKI Sensor URG-04LX")
    );
    assert_eq!(identity_value(&pairs, "SERI").as_deref(), Some("H0722112"));
    assert_eq!(identity_value(&pairs, "DMAX").as_deref(), Some("5600"));
    assert_eq!(
        identity_value(&pairs, "STAT").as_deref(),
        Some("Sensor works well.")
    );
    assert_eq!(
        identity_value(&pairs, "scan_command").as_deref(),
        Some("MD")
    );
    assert_eq!(identity_value(&pairs, "steps").as_deref(), Some("44..725"));
    assert_eq!(identity_value(&pairs, "intensity").as_deref(), Some("no"));
    assert!(identity_value(&pairs, "clock_sync")
        .unwrap()
        .starts_with("TM1 sync"));
    assert_eq!(rig.driver.state(), &DeviceState::Streaming);

    let out = rig.feed(&rig.md_scan(120));
    let got = scans(&out);
    assert_eq!(got.len(), 1);
    assert_eq!(got[0].rays.len(), 682);

    let stats = rig.driver.stats();
    assert_eq!(stats.commands, 12, "QT VV PP II TM0 5xTM1 TM2 MD");
    assert_eq!(stats.handshakes, 1);
    assert_eq!(stats.scans, 1);
    assert_eq!(stats.total_errors(), 0, "{stats}");
}

#[test]
fn scip11_sensor_is_switched_to_scip20() {
    let mut rig = Rig::new(ScipConfig::default());
    assert_writes(&rig.connect(), &["QT\n"]);
    // SCIP 1.1 does not know QT: echo, a bare `E`, LF (urg_c
    // `connect_urg_device()`).
    assert_writes(&rig.feed(b"QT\nE\n\n"), &["SCIP2.0\n"]);
    let out = rig.feed(b"SCIP2.0\n0\n\n");
    assert_eq!(out[0], DriverOutput::State(DeviceState::Configuring));
    assert_writes(&out, &["VV\n"]);
    assert_eq!(rig.driver.stats().total_errors(), 0);
}

#[test]
fn sensor_left_in_time_mode_gets_tm2() {
    let mut rig = Rig::new(ScipConfig::default());
    rig.connect();
    assert_writes(&rig.feed(b"QT\n0Ee\n\n"), &["TM2\n"]);
    assert_writes(&rig.feed(b"TM2\n00P\n\n"), &["VV\n"]);
}

#[test]
fn mid_stream_sensor_is_stopped_and_drained() {
    let mut rig = Rig::new(ScipConfig::default());
    assert_writes(&rig.connect(), &["QT\n"]);
    // The port opened in the middle of an MD scan: the rest of its data
    // lines and its closing empty line arrive first.
    let tail = format!("{}{}\n", summed("0Dh0Dh0Dh0Dh"), summed("1Dh1Dh"));
    let out = rig.feed(tail.as_bytes());
    assert_eq!(
        out,
        vec![
            DriverOutput::Write(b"QT\n".to_vec()),
            DriverOutput::FlushInput
        ]
    );
    assert_eq!(rig.driver.stats().errors("unexpected_echo"), 1);
    // More of the stream (already in flight) is ignored while draining.
    assert!(writes(&rig.feed(&rig.md_scan(100))).is_empty());
    assert_eq!(rig.driver.stats().scans, 0);
    // The sensor stops and answers QT: the driver probes again.
    assert_writes(&rig.feed(b"QT\n00P\n\n"), &["QT\n"]);
    let out = rig.feed(b"QT\n00P\n\n");
    assert_eq!(out[0], DriverOutput::State(DeviceState::Configuring));
    assert_writes(&out, &["VV\n"]);
    // A late answer to the other QT is ignored, not counted.
    assert!(rig.feed(b"QT\n00P\n\n").is_empty());
    assert_writes(&rig.feed(&vv_reply()), &["PP\n"]);
    assert_eq!(rig.driver.stats().errors("unexpected_echo"), 1);
}

#[test]
fn drain_times_out_then_probes_again() {
    let mut rig = Rig::new(ScipConfig::default());
    rig.connect();
    rig.feed(&rig.md_scan(100));
    assert_writes(&rig.advance_ms(1_000), &["QT\n"]);
    assert_eq!(rig.driver.stats().errors("timeout"), 1);
}

#[test]
fn sensor_that_never_stops_streaming_is_given_up() {
    let mut rig = Rig::new(ScipConfig::default());
    rig.connect();
    let mut out = Vec::new();
    for _ in 0..4 {
        out = rig.feed(&rig.md_scan(100));
        rig.advance_ms(1_000);
    }
    let reason = reconnect_reason(&out).expect("gives up");
    assert!(reason.contains("kept streaming"), "{reason}");
}

#[test]
fn rs232_probing_finds_the_third_baud() {
    let config = ScipConfig {
        link: Link::rs232(),
        ..ScipConfig::default()
    };
    let mut rig = Rig::new(config);
    let out = rig.connect();
    assert_eq!(
        out,
        vec![
            DriverOutput::State(DeviceState::Connecting),
            DriverOutput::FlushInput,
            DriverOutput::SetBaud(19_200),
            DriverOutput::Write(b"QT\n".to_vec()),
        ]
    );
    // Nothing at 19200.
    assert!(rig.advance_ms(999).is_empty());
    assert_eq!(
        rig.advance_ms(1),
        vec![
            DriverOutput::SetBaud(38_400),
            DriverOutput::Write(b"QT\n".to_vec())
        ]
    );
    // Line noise at 38400: bytes that are not SCIP text.
    assert!(rig.feed(&[0xF0, 0x0A, 0x83, 0x9C, 0x0A, 0x0A]).is_empty());
    assert_eq!(rig.driver.stats().errors("garbage"), 1);
    assert_eq!(
        rig.advance_ms(1_000),
        vec![
            DriverOutput::SetBaud(115_200),
            DriverOutput::Write(b"QT\n".to_vec())
        ]
    );
    let out = rig.feed(b"QT\n00P\n\n");
    assert_eq!(out[0], DriverOutput::State(DeviceState::Configuring));
    assert_writes(&out, &["VV\n"]);
    rig.feed(&vv_reply());
    rig.feed(URG04LX_PP.as_bytes());
    rig.feed(&ii_reply("Sensor works well."));
    rig.feed(b"TM0\n00P\n\n");
    rig.answer_tm1(5);
    rig.feed(b"TM2\n00P\n\n");
    let pairs = identity(&rig.feed(b"MD0044072501000\n00P\n\n")).unwrap();
    assert_eq!(identity_value(&pairs, "baud").as_deref(), Some("115200"));
    assert_eq!(rig.driver.stats().errors("timeout"), 2);
}

#[test]
fn rs232_silent_at_every_baud_reconnects() {
    let config = ScipConfig {
        link: Link::rs232(),
        ..ScipConfig::default()
    };
    let mut rig = Rig::new(config);
    rig.connect();
    rig.advance_ms(1_000);
    rig.advance_ms(1_000);
    let out = rig.advance_ms(1_000);
    assert_eq!(
        reconnect_reason(&out).as_deref(),
        Some("no reply to QT at 19200, 38400, 115200 baud")
    );
    assert_eq!(rig.driver.state(), &DeviceState::Disconnected);
    assert_eq!(rig.driver.stats().reconnects, 1);
}

#[test]
fn rs232_target_baud_is_set_with_ss() {
    let config = ScipConfig {
        link: Link::rs232(),
        target_baud: Some(115_200),
        ..ScipConfig::default()
    };
    let mut rig = Rig::new(config);
    rig.connect();
    assert_writes(&rig.feed(b"QT\n00P\n\n"), &["SS115200\n"]);
    let out = rig.feed(b"SS115200\n00P\n\n");
    assert_eq!(
        out,
        vec![DriverOutput::SetBaud(115_200), DriverOutput::FlushInput]
    );
    assert!(
        rig.advance_ms(100).is_empty(),
        "the sensor gets time to switch"
    );
    assert_writes(&rig.advance_ms(50), &["QT\n"]);
    assert_writes(&rig.feed(b"QT\n00P\n\n"), &["VV\n"]);
}

#[test]
fn usb_silence_reconnects_naming_the_command() {
    let mut rig = Rig::new(ScipConfig::default());
    rig.connect();
    rig.feed(b"QT\n00P\n\n");
    let out = rig.advance_ms(1_000);
    assert_eq!(
        reconnect_reason(&out).as_deref(),
        Some("no reply to VV within 1000 ms")
    );
    let out = {
        let mut rig = Rig::new(ScipConfig::default());
        rig.connect();
        rig.advance_ms(1_000)
    };
    assert_eq!(
        reconnect_reason(&out).as_deref(),
        Some("no reply to QT over USB")
    );
}

#[test]
fn every_connect_probes_everything_again() {
    let mut rig = Rig::streaming();
    rig.feed(&rig.md_scan(120));
    let out = rig.bring_up();
    assert_eq!(
        writes(&out),
        [
            "QT\n",
            "VV\n",
            "PP\n",
            "II\n",
            "TM0\n",
            "TM1\n",
            "TM1\n",
            "TM1\n",
            "TM1\n",
            "TM1\n",
            "TM2\n",
            "MD0044072501000\n"
        ]
    );
    rig.feed(b"MD0044072501000\n00P\n\n");
    assert_eq!(rig.driver.stats().handshakes, 2);
    let writes_total = 2 * 12;
    assert_eq!(rig.driver.stats().commands, writes_total);
}

#[test]
fn shutdown_writes_qt() {
    let mut rig = Rig::streaming();
    let before = rig.driver.stats().commands;
    let mut out = Vec::new();
    rig.driver.shutdown(&mut out);
    assert_writes(&out, &["QT\n"]);
    assert_eq!(rig.driver.stats().commands, before + 1);
    assert_eq!(rig.driver.state(), &DeviceState::Disconnected);
    assert!(scans(&rig.feed(&rig.md_scan(120))).is_empty());
}

#[test]
fn unhealthy_stat_is_reported_and_streaming_goes_on() {
    let mut rig = Rig::new(ScipConfig::default());
    rig.connect();
    rig.feed(b"QT\n00P\n\n");
    rig.feed(&vv_reply());
    rig.feed(URG04LX_PP.as_bytes());
    let out = rig.feed(&ii_reply("Motor rotation error"));
    assert!(out.contains(&DriverOutput::Health {
        ok: false,
        detail: "STAT: Motor rotation error".into()
    }));
    assert_writes(&out, &["TM0\n"]);
}

#[test]
fn bad_pp_reply_reconnects() {
    let mut rig = Rig::new(ScipConfig::default());
    rig.connect();
    rig.feed(b"QT\n00P\n\n");
    rig.feed(&vv_reply());
    let broken = URG04LX_PP.replace("DMIN:20;4", "DMIN:20;5");
    let reason = reconnect_reason(&rig.feed(broken.as_bytes())).unwrap();
    assert_eq!(reason, "bad reply to PP: a parameter line has a wrong sum");
    assert_eq!(rig.driver.stats().errors("bad_checksum"), 1);
}

#[test]
fn laser_malfunction_on_bm_reboots() {
    let mut rig = Rig::new(ScipConfig {
        scan: ScanCommand::Gd,
        ..ScipConfig::default()
    });
    rig.bring_up();
    let out = rig.feed(b"BM\n01Q\n\n");
    assert_writes(&out, &["RB\n"]);
    assert!(matches!(rig.driver.state(), DeviceState::Recovering(_)));
}
