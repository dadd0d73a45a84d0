//! Real serial range sensors, end to end with real processes: an emulated
//! device (`shroud sensor-sim --device ...`) on a real pseudo-terminal, the
//! `serial` node reading it with the device's driver and assembling clouds
//! from a (tilting) mount, and the test listening over a real zenoh session.
//! Handshakes, streams, unplug and replug, a device left streaming by a
//! crashed driver, RS-232 baud probing, and injected faults.

mod common;

use common::device_rig::{
    clouds, expect_certified_surrogate, fit_from_above, label, path, status_until, CpuLoad, Rig,
    LONG, TILTING,
};
use common::Proc;
use shroud_msg::CloudMessage;
use std::path::Path;
use std::time::Duration;

#[test]
fn devices_a_tilting_urg_becomes_clouds_and_certified_surrogates() {
    let rig = Rig::new("dev-urg");
    let mut emulator_args = TILTING.to_vec();
    emulator_args.extend(["--corrupt-every", "7", "--garbage-every", "5"]);
    let _emulator = rig.emulator("urg-04lx", &emulator_args);
    let cloud_inbox = rig.inbox("cloud", "dev");
    let status_inbox = rig.inbox("status", "dev");
    let surrogate_inbox = rig.inbox("surrogate", "dev");
    let node = rig.serial("hokuyo", &TILTING);
    let _fit = fit_from_above(&rig);
    // Sweeps of one second: each cloud spans ~10 scans of 682 rays.
    let got = clouds(&cloud_inbox, 4, &node);
    // The first sweep began before the node did: skip it.
    for cloud in &got[1..] {
        let points = cloud.point_array().unwrap();
        // Rays beyond ~63° from straight down leave the 5.6 m range: about
        // 40 % of 682 rays of each of the ~10 scans hit the table.
        assert!(
            points.len() > 1000,
            "a sweep holds ~10 scans: {}",
            points.len()
        );
        // The table top (z = 0) and its objects (up to 1 m) under a sensor at 2.5 m.
        let below = points.iter().filter(|p| p[2] > -0.05 && p[2] < 1.3).count();
        assert!(
            below * 10 > points.len() * 9,
            "points lie on the table and its objects"
        );
        // Nodding ±35° from 2.5 m sweeps x over about ±1.75 m.
        let max_x = points.iter().map(|p| p[0].abs()).fold(0.0, f32::max);
        assert!(max_x > 1.2 && max_x < 2.2, "sweep reach {max_x}");
        // Aged from its first scan's arrival, a sweep's beginning: close to
        // a second before its end, not from its last scan.
        assert!(
            cloud.pipeline_ns > 600_000_000,
            "age {} ns",
            cloud.pipeline_ns
        );
    }
    let status = status_until(&status_inbox, &node, "streaming and counted faults", |s| {
        label(s, "device.state") == "streaming"
            && s.counter("bad_checksum") > 0
            && s.counter("clouds") >= 3
    });
    assert_eq!(label(&status, "device.kind"), "hokuyo");
    assert!(
        label(&status, "device.MODL").contains("URG-04LX"),
        "{status:?}"
    );
    assert!(
        label(&status, "device.health").starts_with("ok"),
        "{status:?}"
    );
    expect_certified_surrogate(&cloud_inbox, &surrogate_inbox, got, &node);
}

#[test]
fn devices_an_unplugged_urg_is_reconnected_and_streams_again() {
    let rig = Rig::new("dev-unplug");
    let emulator = rig.emulator("urg-04lx", &["--unplug-after", "3", "--unplug-for", "1.5"]);
    let cloud_inbox = rig.inbox("cloud", "dev");
    let status_inbox = rig.inbox("status", "dev");
    let node = rig.serial("hokuyo", &[]);
    clouds(&cloud_inbox, 5, &node);
    // The device comes back (powered up afresh) behind the same link.
    emulator.expect_line("sensor-sim: urg-04lx on", LONG);
    let status = status_until(
        &status_inbox,
        &node,
        "a disconnect and a second handshake",
        |s| s.counter("disconnects") >= 1 && s.counter("handshakes") >= 2,
    );
    assert_eq!(label(&status, "device.state"), "streaming", "{status:?}");
    let _ = cloud_inbox.drain().count();
    clouds(&cloud_inbox, 5, &node);
}

#[test]
fn devices_a_urg_left_streaming_by_a_killed_driver_is_recovered() {
    let rig = Rig::new("dev-crash");
    let _emulator = rig.emulator("urg-04lx", &[]);
    let cloud_inbox = rig.inbox("cloud", "dev");
    let status_inbox = rig.inbox("status", "dev");
    let first = rig.serial("hokuyo", &[]);
    clouds(&cloud_inbox, 3, &first);
    // SIGKILL: no QT is sent, the sensor keeps streaming into the pty.
    first.signal(libc::SIGKILL);
    drop(first);
    std::thread::sleep(Duration::from_millis(500));
    let _ = cloud_inbox.drain().count();
    let second = rig.serial("hokuyo", &[]);
    clouds(&cloud_inbox, 3, &second);
    let status = status_until(&status_inbox, &second, "a stream found running", |s| {
        s.counter("unexpected_echo") + s.counter("malformed_reply") > 0
            && label(s, "device.state") == "streaming"
    });
    assert_eq!(status.counter("handshakes"), 1, "{status:?}");
}

#[test]
fn devices_an_rs232_urg_is_found_by_baud_probing_in_scip_1_1_and_rebooted_when_abnormal() {
    let rig = Rig::new("dev-rs232");
    // The sensor's UART runs at 115200, the probe starts at 19200; it answers
    // in SCIP 1.1 until switched, and turns abnormal after 40 scans.
    let _emulator = rig.emulator(
        "urg-04lx",
        &["--rs232", "115200", "--scip1", "--abnormal-after", "40"],
    );
    let cloud_inbox = rig.inbox("cloud", "dev");
    let status_inbox = rig.inbox("status", "dev");
    let node = rig.serial("hokuyo", &["--rs232"]);
    clouds(&cloud_inbox, 3, &node);
    let status = status_until(&status_inbox, &node, "a reboot and a new stream", |s| {
        s.counter("device_error_abnormal") >= 1
            && s.counter("handshakes") >= 2
            && label(s, "device.state") == "streaming"
    });
    assert!(
        status.counter("timeout") >= 1,
        "the wrong rates timed out: {status:?}"
    );
    let _ = cloud_inbox.drain().count();
    clouds(&cloud_inbox, 3, &node);
}

#[test]
fn devices_an_rplidar_a1_streams_revolutions_with_its_motor_on_dtr_and_survives_an_unplug() {
    let rig = Rig::new("dev-a1");
    let emulator = rig.emulator(
        "rplidar-a1",
        &[
            "--mount",
            "0,0,0.3,0,0,0",
            "--unplug-after",
            "5",
            "--unplug-for",
            "1",
        ],
    );
    let cloud_inbox = rig.inbox("cloud", "dev");
    let status_inbox = rig.inbox("status", "dev");
    let surrogate_inbox = rig.inbox("surrogate", "dev");
    let node = rig.serial("rplidar", &["--mount", "0,0,0.3,0,0,0"]);
    let _fit = fit_from_above(&rig);
    // One cloud a revolution (~5.5 Hz), in the table's plane 0.3 m up.
    let got = clouds(&cloud_inbox, 5, &node);
    for cloud in &got {
        let points = cloud.point_array().unwrap();
        assert!(
            points.len() > 100,
            "a revolution of the table's objects: {}",
            points.len()
        );
        assert!(
            points.iter().all(|p| (p[2] - 0.3).abs() < 1e-3),
            "a planar scan"
        );
    }
    let status = status_until(&status_inbox, &node, "streaming", |s| {
        label(s, "device.state") == "streaming"
    });
    assert_eq!(label(&status, "device.model"), "A1M8", "{status:?}");
    assert_eq!(label(&status, "device.motor_control"), "dtr", "{status:?}");
    // A pty has no modem lines: the DTR writes fail, counted, not fatal.
    assert!(status.counter("line_setting_failures") >= 1, "{status:?}");
    expect_certified_surrogate(&cloud_inbox, &surrogate_inbox, got, &node);
    emulator.expect_line("sensor-sim: rplidar-a1 on", LONG);
    status_until(&status_inbox, &node, "a disconnect and a new stream", |s| {
        s.counter("disconnects") >= 1
            && s.counter("handshakes") >= 2
            && label(s, "device.state") == "streaming"
    });
    let _ = cloud_inbox.drain().count();
    clouds(&cloud_inbox, 3, &node);
}

#[test]
fn devices_an_rplidar_a2_left_streaming_dense_capsules_by_a_killed_driver_is_recovered() {
    let rig = Rig::new("dev-a2");
    let _emulator = rig.emulator(
        "rplidar-a2",
        &["--mount", "0,0,0.3,0,0,0", "--corrupt-every", "40"],
    );
    let cloud_inbox = rig.inbox("cloud", "dev");
    let status_inbox = rig.inbox("status", "dev");
    let first = rig.serial("rplidar", &["--mount", "0,0,0.3,0,0,0"]);
    clouds(&cloud_inbox, 3, &first);
    let status = status_until(
        &status_inbox,
        &first,
        "dense capsules, PWM and a bad checksum",
        |s| label(s, "device.state") == "streaming" && s.counter("bad_checksum") >= 1,
    );
    assert!(
        label(&status, "device.scan_mode").contains("dense"),
        "{status:?}"
    );
    assert!(
        label(&status, "device.motor_control").starts_with("pwm"),
        "{status:?}"
    );
    first.signal(libc::SIGKILL);
    drop(first);
    std::thread::sleep(Duration::from_millis(500));
    let _ = cloud_inbox.drain().count();
    let second = rig.serial("rplidar", &["--mount", "0,0,0.3,0,0,0"]);
    clouds(&cloud_inbox, 3, &second);
}

/// A slope `z = x / 2`, 40 m across, as an OBJ file in `dir`.
fn slope_obj(dir: &Path) -> String {
    let file = dir.join("slope.obj");
    let obj = "v -20 -20 -10\nv 20 -20 10\nv 20 20 10\nv -20 20 -10\nf 1 2 3\nf 1 3 4\n";
    std::fs::write(&file, obj).expect("the slope mesh is written");
    path(&file)
}

/// A pan unit 1.5 m up turning once a second, the beam 50° below horizontal.
const PANNING: &str = "rotate:1";
const PAN_MOUNT: [&str; 6] = [
    "--mount",
    "0,0,1.5,0,0,0",
    "--mount-axis",
    "z",
    "--sensor-offset",
    "0,0,0,0,50,0",
];

/// The node options of the panning TFmini tests. The emulator sends, at
/// each of its 2 ms steps, every frame due by then: under load a frame can
/// wait up to a period (10 ms at the factory 100 Hz) and a late step where
/// the host cannot see it, so its link latency is 15 ms.
const TF_TIMING: [&str; 2] = ["--link-latency", "0.015"];

/// A bound on the position error of a sane cloud here: the node's default
/// maximum (a reading less sure of its place is dropped).
const SANE_POSITION_ERROR_M: f64 = 0.25;

/// Every point of `clouds` lies on the slope within the error its cloud
/// states, plus the emulator's range noise: the beam was placed at the pan
/// angle of the best estimate of its time, and the uncertainty of that time
/// through the pan speed bounds how far off (5° off would put points
/// ~0.1 m off it). A point `d` metres off moves `z - x/2` by at most
/// `d·√1.25`.
fn assert_on_slope(clouds: &[CloudMessage]) {
    let mut points = 0;
    for cloud in clouds {
        let error = cloud.position_error_m;
        assert!(
            error.is_finite() && error > 0.0 && error <= SANE_POSITION_ERROR_M,
            "cloud {} states a position error of {error} m",
            cloud.sequence
        );
        let tolerance = 0.06 + error * 1.25f64.sqrt();
        let mut worst = 0.0f64;
        for p in cloud.point_array().unwrap() {
            points += 1;
            let off = (p[2] - p[0] / 2.0).abs() as f64;
            worst = worst.max(off);
            assert!(
                off < tolerance,
                "a point {p:?} off the slope by {off}, more than {tolerance} \
                 (position error {error} m)"
            );
        }
        eprintln!(
            "cloud {}: {} points, position error {error:.4} m, worst z - x/2 {worst:.4}",
            cloud.sequence,
            cloud.point_array().unwrap().len()
        );
    }
    assert!(points > 50, "{points} points on the slope");
}

/// Logs the node's count of readings dropped for their lateness.
fn log_late_readings(status: &shroud_msg::NodeStatusMessage) {
    eprintln!(
        "readings dropped: {} without a time bound, {} beyond the largest error",
        status.counter("readings_late_unbounded"),
        status.counter("readings_late_beyond_bound")
    );
}

#[test]
fn devices_a_panning_tfmini_placed_by_its_sweep_profile_draws_the_slope() {
    // Two busy threads compete with the emulator and the nodes throughout.
    let _load = CpuLoad::start(2);
    let rig = Rig::new("dev-tf");
    let slope = slope_obj(rig.dir.path());
    let mut args = vec![
        "--world",
        slope.as_str(),
        "--sweep",
        PANNING,
        "--corrupt-every",
        "50",
    ];
    // It also goes silent for a second, 3 s after power-up.
    args.extend(["--stall-after", "3", "--stall-for", "1"]);
    args.extend(PAN_MOUNT);
    let _emulator = rig.emulator("tfmini-plus", &args);
    let cloud_inbox = rig.inbox("cloud", "dev");
    let status_inbox = rig.inbox("status", "dev");
    let mut node_args = vec!["--sweep", PANNING];
    node_args.extend(PAN_MOUNT);
    node_args.extend(TF_TIMING);
    let surrogate_inbox = rig.inbox("surrogate", "dev");
    let node = rig.serial("tfmini", &node_args);
    let _fit = fit_from_above(&rig);
    let got = clouds(&cloud_inbox, 3, &node);
    assert_on_slope(&got[1..]);
    expect_certified_surrogate(&cloud_inbox, &surrogate_inbox, got, &node);
    let status = status_until(&status_inbox, &node, "a bad checksum and a stall", |s| {
        s.counter("bad_checksum") >= 1
            && s.counter("reconnects") >= 1
            && label(s, "device.state") == "streaming"
    });
    assert_eq!(label(&status, "device.model"), "tfmini-plus", "{status:?}");
    log_late_readings(&status);
    // Streaming again after the stall.
    let _ = cloud_inbox.drain().count();
    assert_on_slope(&clouds(&cloud_inbox, 2, &node)[1..]);
}

#[test]
fn devices_a_panning_tfmini_placed_by_joint_states_draws_the_slope() {
    // Two busy threads compete with the emulator, the node and the joint
    // states' publisher throughout.
    let _load = CpuLoad::start(2);
    let rig = Rig::new("dev-tf-joint");
    let slope = slope_obj(rig.dir.path());
    let mut args = vec!["--world", slope.as_str(), "--sweep", PANNING];
    args.extend(PAN_MOUNT);
    let _emulator = rig.emulator("tfmini-plus", &args);
    // The unit's controller: its angle as joint states, 200 Hz.
    let profile: shroud_drivers::assembly::SweepProfile = PANNING.parse().unwrap();
    let stop = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
    let publisher = {
        let key = format!("shroud/{}/joints/mount", rig.namespace);
        let session = rig.hub.clone();
        let stop = stop.clone();
        std::thread::spawn(move || {
            let mut sequence = 0;
            while !stop.load(std::sync::atomic::Ordering::Relaxed) {
                let now = common::unix_ns();
                let msg = shroud_msg::JointStateMessage::new(
                    now,
                    sequence,
                    "pan-unit",
                    vec!["pan".into()],
                    vec![profile.angle_at(now)],
                );
                use zenoh::Wait;
                session.put(&key, msg.to_bytes().unwrap()).wait().unwrap();
                sequence += 1;
                std::thread::sleep(Duration::from_millis(5));
            }
        })
    };
    let cloud_inbox = rig.inbox("cloud", "dev");
    let status_inbox = rig.inbox("status", "dev");
    let mut node_args = vec!["--mount-joint", "pan", "--cloud", "time:1"];
    node_args.extend(PAN_MOUNT);
    node_args.extend(TF_TIMING);
    let mut node = rig.serial("tfmini", &node_args);
    let got = clouds(&cloud_inbox, 3, &node);
    assert_on_slope(&got[1..]);
    log_late_readings(&status_until(&status_inbox, &node, "clouds", |s| {
        s.counter("clouds") >= 3
    }));
    // A SIGTERM stops it cleanly while joint states still come.
    node.signal(libc::SIGTERM);
    let status = node.wait_exit(Duration::from_secs(8));
    assert!(status.success(), "{status:?}: {}", node.output());
    stop.store(true, std::sync::atomic::Ordering::Relaxed);
    publisher.join().unwrap();
}

#[test]
fn devices_a_utm_30lx_streams_multi_echo_ranges_with_intensity() {
    let rig = Rig::new("dev-utm");
    let _emulator = rig.emulator("utm-30lx", &["--mount", "0,0,0.5,0,0,0"]);
    let cloud_inbox = rig.inbox("cloud", "dev");
    let status_inbox = rig.inbox("status", "dev");
    let node = rig.serial(
        "hokuyo",
        &[
            "--scip-scan",
            "nd",
            "--intensity",
            "--mount",
            "0,0,0.5,0,0,0",
        ],
    );
    // 40 scans a second of 1081 steps, some with a second or third echo.
    let got = clouds(&cloud_inbox, 20, &node);
    for cloud in &got {
        let intensity = cloud
            .intensity_array()
            .unwrap()
            .expect("NE carries intensity");
        assert_eq!(intensity.len(), cloud.point_array().unwrap().len());
    }
    let status = status_until(&status_inbox, &node, "NE streaming", |s| {
        label(s, "device.state") == "streaming"
    });
    assert_eq!(label(&status, "device.multiecho"), "yes", "{status:?}");
    assert_eq!(label(&status, "device.scan_command"), "NE", "{status:?}");
}

#[test]
fn devices_the_lidar_launch_file_runs_an_emulated_urg_to_the_guard() {
    let file = concat!(env!("CARGO_MANIFEST_DIR"), "/launch/lidar.toml");
    let mut launcher = Proc::start(&["launch", file, "--duration", "20"]);
    // A summary line once a certified surrogate of an assembled sweep came
    // through the fit node and the guard is answering the arm.
    let line = launcher.expect_line("certified", LONG);
    assert!(line.contains("0 violations"), "{line}");
    launcher.expect_line("demo_arm: ", LONG);
    // With the default policy (space no sensor saw is occupied), the arm
    // still moves where the table was seen.
    launcher.expect_line("arm: ", LONG);
    let moving = launcher.expect_line(", moving, ", LONG);
    assert!(moving.contains("certified"), "{moving}");
    assert!(launcher.wait_exit(LONG).success(), "{}", launcher.output());
    let output = launcher.output();
    assert!(output.contains("all nodes stopped cleanly"), "{output}");
}

#[test]
fn devices_bad_device_settings_are_named_errors_before_anything_opens() {
    // `shroud node serial --device DEVICE --port /x OPTION VALUE`.
    let serial = |device, option, value| {
        vec![
            "node", "serial", "--device", device, "--port", "/x", option, value,
        ]
    };
    let late_tf = serial("tfmini", "--link-latency", "11");
    let late_urg = serial("hokuyo", "--link-latency", "0.01");
    let exact_tf = serial("tfmini", "--max-position-error", "0");
    let cases: [(&[&str], &str); 10] = [
        (
            &[
                "node",
                "serial",
                "--device",
                "rplidar",
                "--port",
                "/x",
                "--cluster",
                "3",
            ],
            "--cluster applies to --device hokuyo only",
        ),
        (
            &["sensor-sim", "--device", "lidar-9000"],
            "unknown device model",
        ),
        (
            &[
                "node", "serial", "--device", "hokuyo", "--port", "/x", "--sweep", "wobble:1",
            ],
            "invalid sweep profile",
        ),
        (
            &["node", "serial", "--port", "/x", "--sweep", "rotate:1"],
            "apply to range devices only",
        ),
        (
            &[
                "sensor-sim",
                "--device",
                "urg-04lx",
                "--world",
                "/nonexistent.obj",
            ],
            "cannot read the world mesh",
        ),
        (
            &[
                "node", "serial", "--device", "tfmini", "--port", "/x", "--cloud", "sweep",
            ],
            "needs a moving mount",
        ),
        (
            &[
                "node", "serial", "--device", "hokuyo", "--port", "/x", "--mount", "1,2,3",
            ],
            "expected 6 comma-separated numbers",
        ),
        (&late_tf, "--link-latency must be between 0 and 10 seconds"),
        (&late_urg, "--link-latency applies to --device tfmini only"),
        (&exact_tf, "the largest position error 0 m must be positive"),
    ];
    for (args, message) in cases {
        let mut proc = Proc::start(args);
        let status = proc.wait_exit(LONG);
        assert!(!status.success(), "{args:?} must fail");
        assert!(
            proc.output().contains(message),
            "{args:?}: {}",
            proc.output()
        );
    }
}
