//! The catalog and robustness: every model by name, and no panic on any
//! frame or time.

use crate::can_device::{can_emulator, CanEmulatorOptions, CanWorld, CAN_MODELS};
use proptest::prelude::*;
use shroud_drivers::can::CanFrame;

#[test]
fn every_listed_model_is_made_and_reports_its_name() {
    for model in CAN_MODELS {
        let device =
            can_emulator(model, &CanEmulatorOptions::default(), CanWorld::default()).unwrap();
        assert_eq!(device.model(), model);
    }
    let err = can_emulator(
        "ars409",
        &CanEmulatorOptions::default(),
        CanWorld::default(),
    )
    .err()
    .unwrap();
    assert!(err.contains("ars409") && err.contains("tf03-can"), "{err}");
    let bad_sensor = CanEmulatorOptions {
        sensor_id: 8,
        ..CanEmulatorOptions::default()
    };
    assert!(can_emulator("ars408", &bad_sensor, CanWorld::default()).is_err());
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]
    #[test]
    fn no_frame_or_time_makes_a_device_panic(
        frames in proptest::collection::vec(
            (0u32..0x4000, any::<bool>(), proptest::collection::vec(any::<u8>(), 0..=8), 0.0f64..2.0),
            0..40,
        ),
        model in 0usize..CAN_MODELS.len(),
    ) {
        let mut device = can_emulator(CAN_MODELS[model], &CanEmulatorOptions::default(), CanWorld::default()).unwrap();
        let mut out = Vec::new();
        let mut now = 0.0;
        for (id, extended, data, step) in frames {
            now += step * 0.01;
            if let Ok(frame) = CanFrame::new(if extended { id } else { id & 0x7FF }, extended, &data) {
                device.receive(&frame, now);
            }
            device.poll(now, &mut out);
        }
        device.poll(f64::NAN, &mut out);
        device.poll(f64::INFINITY, &mut out);
        device.poll(1e15, &mut out);
        device.poll(1e300, &mut out);
        if let Ok(frame) = CanFrame::new(0x200, false, &[0xFF; 8]) {
            device.receive(&frame, 1e300);
        }
        device.poll(f64::MAX, &mut out);
        prop_assert!(out.windows(2).all(|w| w[0].0 <= w[1].0));
    }
}

#[test]
fn the_emulators_encode_every_frame_without_dbc_errors() {
    use crate::can_device::ars408::{Ars408Emulator, RadarConfig};
    use crate::can_device::benewake::{BenewakeCanEmulator, BenewakeCanModel, UnitSpec};
    use crate::can_device::CanDeviceEmulator;
    use shroud_drivers::assembly::MountPose;
    use shroud_sim::MovingSpheres;

    let mount = CanEmulatorOptions::default().radar_mount;
    let mut radar = Ars408Emulator::new(
        MovingSpheres::default(),
        mount,
        RadarConfig::default(),
        0,
        1,
    )
    .unwrap();
    let mut out = Vec::new();
    radar.poll(0.5, &mut out);
    // Objects with quality and extended information.
    let objects = CanFrame::new(0x200, false, &[0x38, 0, 0, 0, 0x08, 0x0C, 0, 0]).unwrap();
    radar.receive(&objects, 0.5);
    radar.poll(1.0, &mut out);
    let counts = radar.counts();
    assert_eq!(counts.encode_errors, 0);
    assert!(counts.cycles >= 13, "{counts:?}");
    assert!(out.iter().any(|(_, f)| f.id == 0x60D));
    for model in BenewakeCanModel::ALL {
        let unit = UnitSpec {
            id: model.default_id(),
            extended: model.default_extended(),
            mount: MountPose::default(),
        };
        let mut device = BenewakeCanEmulator::new(model, &[unit], None, 0, 0).unwrap();
        device.poll(0.5, &mut out);
        assert_eq!(device.counts().encode_errors, 0, "{}", model.name());
        assert!(device.counts().readings >= 49);
    }
}
