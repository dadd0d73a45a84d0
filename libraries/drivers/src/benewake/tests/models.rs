//! The per-model invalid readings (sensors.md §1.3) and range limits.

use crate::benewake::{BenewakeModel, DataFrame, DistanceUnit, Reading, Validity};

fn verdict(model: BenewakeModel, distance: u16, strength: u16) -> Validity {
    verdict_in(model, DistanceUnit::Centimetre, distance, strength)
}

fn verdict_in(model: BenewakeModel, unit: DistanceUnit, distance: u16, strength: u16) -> Validity {
    let frame = DataFrame {
        distance,
        strength,
        aux: 2248,
    };
    Reading::classify(frame, model, unit).validity
}

use BenewakeModel::*;
use Validity::*;

#[test]
fn tfmini_s_reports_minus_one_below_strength_100() {
    assert_eq!(verdict(TfminiS, 0xFFFF, 99), WeakReturn);
    assert_eq!(verdict(TfminiS, 0xFFFF, 0), WeakReturn);
    assert_eq!(verdict(TfminiS, 500, 100), Valid);
    // -1 with a good strength is still no distance.
    assert_eq!(verdict(TfminiS, 0xFFFF, 1000), OutOfRange);
    // No saturation rule documented for the TFmini-S.
    assert_eq!(verdict(TfminiS, 500, 65535), Valid);
}

#[test]
fn tfmini_plus_reports_zero_when_weak_or_saturated() {
    assert_eq!(verdict(TfminiPlus, 0, 99), WeakReturn);
    assert_eq!(verdict(TfminiPlus, 0, 65535), Saturated);
    assert_eq!(verdict(TfminiPlus, 0, 100), OutOfRange);
    assert_eq!(verdict(TfminiPlus, 1200, 100), Valid);
    assert_eq!(verdict(TfminiPlus, 1201, 65534), OutOfRange);
}

#[test]
fn tf02_pro_reports_4500_below_strength_60() {
    assert_eq!(verdict(Tf02Pro, 4500, 59), WeakReturn);
    assert_eq!(verdict(Tf02Pro, 3999, 60), Valid);
    assert_eq!(verdict(Tf02Pro, 4000, 60), Valid);
    assert_eq!(verdict(Tf02Pro, 4001, 60), OutOfRange);
    assert_eq!(verdict(Tf02Pro, 4500, 1000), OutOfRange);
    assert_eq!(verdict(Tf02Pro, 500, 65535), Valid);
}

#[test]
fn tf_luna_is_unreliable_when_amp_is_low_or_overexposed() {
    assert_eq!(verdict(TfLuna, 300, 99), WeakReturn);
    assert_eq!(verdict(TfLuna, 300, 65535), Saturated);
    assert_eq!(verdict(TfLuna, 800, 100), Valid);
    assert_eq!(verdict(TfLuna, 801, 100), OutOfRange);
}

#[test]
fn original_tfmini_has_only_the_range_rule() {
    assert_eq!(verdict(Tfmini, 300, 0), Valid);
    assert_eq!(verdict(Tfmini, 0, 1000), OutOfRange);
    assert_eq!(verdict(Tfmini, 1201, 1000), OutOfRange);
    assert_eq!(verdict(Tfmini, 0xFFFF, 1000), OutOfRange);
}

#[test]
fn millimetre_output_scales_the_range_limit_and_the_metres() {
    assert_eq!(
        verdict_in(TfminiPlus, DistanceUnit::Millimetre, 12000, 500),
        Valid
    );
    assert_eq!(
        verdict_in(TfminiPlus, DistanceUnit::Millimetre, 12001, 500),
        OutOfRange
    );
    let frame = DataFrame {
        distance: 1234,
        strength: 500,
        aux: 0,
    };
    let reading = Reading::classify(frame, TfminiPlus, DistanceUnit::Millimetre);
    assert_eq!(reading.range_m, 1.234);
}

#[test]
fn invalid_readings_are_nan_rays_that_are_not_valid() {
    let frame = DataFrame {
        distance: 0,
        strength: 10,
        aux: 0,
    };
    let reading = Reading::classify(frame, TfminiPlus, DistanceUnit::Centimetre);
    let ray = reading.ray();
    assert!(ray.range.is_nan());
    assert!(!ray.is_valid());
    assert_eq!(ray.intensity, Some(10.0));
    assert_eq!((ray.angle, ray.offset_ns), (0.0, 0));
}

#[test]
fn counter_names_are_stable() {
    assert_eq!(Valid.counter(), None);
    assert_eq!(WeakReturn.counter(), Some("weak_return"));
    assert_eq!(Saturated.counter(), Some("saturated"));
    assert_eq!(OutOfRange.counter(), Some("out_of_range"));
}

#[test]
fn model_names_round_trip_and_capabilities() {
    for model in BenewakeModel::ALL {
        assert_eq!(BenewakeModel::from_name(model.name()), Some(model));
    }
    assert_eq!(BenewakeModel::from_name("TF-Luna"), Some(TfLuna));
    assert_eq!(BenewakeModel::from_name("tf03"), None);
    assert_eq!(BenewakeModel::default(), TfminiPlus);
    assert!(!Tfmini.has_commands());
    assert!(TfLuna.has_commands());
    assert!(TfminiS.supports_mm_output() && TfminiPlus.supports_mm_output());
    assert!(!TfLuna.supports_mm_output() && !Tf02Pro.supports_mm_output());
    assert_eq!(TfLuna.max_range_cm(), 800);
    assert_eq!(Tf02Pro.max_range_cm(), 4000);
}
