//! Smooth-surface messages (`SmoothPatchesMessage::from_bytes`): domain
//! quads and patch coefficients, validated on read.

use crate::check::named;
use crate::round_trip;
use shroud_msg::SmoothPatchesMessage;

pub fn run(data: &[u8]) {
    match SmoothPatchesMessage::from_bytes(data) {
        Ok(message) => {
            round_trip::message(
                &message,
                SmoothPatchesMessage::to_bytes,
                SmoothPatchesMessage::from_bytes,
            );
        }
        Err(e) => named(&e),
    }
}

pub fn seeds() -> Vec<Vec<u8>> {
    let f64s = |values: &[f64]| {
        values
            .iter()
            .flat_map(|v| v.to_le_bytes())
            .collect::<Vec<u8>>()
    };
    let vertices = f64s(&[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 1.0, 0.0]);
    let quads: Vec<u8> = [0u32, 1, 2, 3]
        .iter()
        .flat_map(|i| i.to_le_bytes())
        .collect();
    let coefficients = f64s(&(0..36).map(|i| f64::from(i) * 0.01).collect::<Vec<_>>());
    let message = SmoothPatchesMessage {
        version: shroud_msg::SCHEMA_VERSION,
        source_stamp_ns: 1,
        source_sequence: 2,
        source: "fit".into(),
        kind: "height".into(),
        dim: 1,
        vertices,
        quads,
        coefficients,
        functions: 16,
        lambda: 1e-3,
        points: 100,
        outside: 3,
        error_min: -0.01,
        error_max: 0.02,
        error_rmse: 0.005,
        fit_ns: 12345,
    };
    vec![message.to_bytes().expect("the seed message encodes")]
}
