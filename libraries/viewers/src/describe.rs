//! Human- and machine-readable summaries of any shroud message, for `shroud topic
//! echo`: every field except bulk blobs, which are summarised (count, bounds).

use serde_json::{json, Value};
use shroud_msg::{
    BlendCommandMessage, CloudMessage, CollisionMessage, JointStateMessage, MessageError, NoReturn,
    NodeStatusMessage, SmoothPatchesMessage, SurrogateMessage, TopicKind,
};
use shroud_surrogate::SurrogateWire;

/// Decodes `bytes` as the message a topic of `kind` carries and summarises it.
pub fn describe(kind: TopicKind, bytes: &[u8]) -> Result<Value, MessageError> {
    let value = match kind {
        TopicKind::Cloud => describe_cloud(&CloudMessage::from_bytes(bytes)?)?,
        TopicKind::Surrogate => describe_surrogate(&SurrogateMessage::from_bytes(bytes)?.0),
        TopicKind::Joints => to_value(&JointStateMessage::from_bytes(bytes)?)?,
        TopicKind::Collision => to_value(&CollisionMessage::from_bytes(bytes)?)?,
        TopicKind::Status => to_value(&NodeStatusMessage::from_bytes(bytes)?)?,
        TopicKind::Alive => json!({ "alive": true }),
        TopicKind::Blend => to_value(&BlendCommandMessage::from_bytes(bytes)?)?,
        TopicKind::Smooth => describe_smooth(&SmoothPatchesMessage::from_bytes(bytes)?),
    };
    Ok(value)
}

fn to_value<T: serde::Serialize>(msg: &T) -> Result<Value, MessageError> {
    serde_json::to_value(msg).map_err(|e| MessageError::Malformed(e.to_string()))
}

fn describe_cloud(msg: &CloudMessage) -> Result<Value, MessageError> {
    let points = msg.point_array()?;
    let mut lo = [f32::INFINITY; 3];
    let mut hi = [f32::NEG_INFINITY; 3];
    for p in &points {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let bounds = if points.is_empty() {
        Value::Null
    } else {
        json!({ "min": lo, "max": hi })
    };
    Ok(json!({
        "version": msg.version,
        "stamp_ns": msg.stamp_ns,
        "sequence": msg.sequence,
        "source": msg.source,
        "pose": msg.pose,
        "position_error_m": msg.position_error_m,
        "field_of_view": msg.field_of_view,
        "no_return": summarise_no_return(msg.no_return.as_ref()),
        "points": points.len(),
        "bounds": bounds,
        "intensity": msg.intensity.is_some(),
    }))
}

fn describe_smooth(msg: &SmoothPatchesMessage) -> Value {
    json!({
        "version": msg.version,
        "source_stamp_ns": msg.source_stamp_ns,
        "source_sequence": msg.source_sequence,
        "source": msg.source,
        "kind": msg.kind,
        "faces": msg.quads.len() / 16,
        "functions": msg.functions,
        "lambda": msg.lambda,
        "points": msg.points,
        "outside": msg.outside,
        "errors": { "min": msg.error_min, "max": msg.error_max, "rmse": msg.error_rmse },
        "fit_ns": msg.fit_ns,
    })
}

fn describe_surrogate(msg: &SurrogateMessage) -> Value {
    let surfaces: Vec<Value> = msg
        .surfaces
        .iter()
        .map(|s| json!({ "side": s.side, "coefficients": s.coefficients.len() / 8, "certificate": s.certificate }))
        .collect();
    json!({
        "version": msg.version,
        "source_stamp_ns": msg.source_stamp_ns,
        "source_sequence": msg.source_sequence,
        "source": msg.source,
        "direction": msg.direction,
        "domain": msg.domain,
        "grid": [msg.domain.cols, msg.domain.rows],
        "kept_cells": msg.trim.iter().filter(|&&b| b != 0).count(),
        "cells": msg.trim.len(),
        "surfaces": surfaces,
        "fit_ms": msg.fit_ns as f64 / 1e6,
        "position_error_m": msg.position_error_m,
        "field_of_view": msg.field_of_view,
        "no_return": summarise_no_return(msg.no_return.as_ref()),
    })
}

/// The apex, the number of cones and the widest one (degrees), not every cone.
fn summarise_no_return(no_return: Option<&NoReturn>) -> Value {
    no_return.map_or(Value::Null, |n| {
        let widest = n.cones.iter().map(|c| c.half_angle).fold(0.0, f64::max);
        json!({ "apex": n.apex, "cones": n.cones.len(), "widest_half_angle_deg": widest.to_degrees() })
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use shroud_msg::SensorPose;

    #[test]
    fn clouds_are_summarised_not_dumped() {
        let msg = CloudMessage::new(
            1,
            2,
            "s",
            SensorPose::default(),
            &[[0.0, 1.0, 2.0], [3.0, -1.0, 0.5]],
        );
        let v = describe(TopicKind::Cloud, &msg.to_bytes().unwrap()).unwrap();
        assert_eq!(v["points"], 2);
        assert_eq!(v["bounds"]["max"][0], 3.0);
        assert!(v["field_of_view"].is_null(), "{v}");
        let mut msg = msg;
        msg.field_of_view = Some(shroud_msg::sample_field_of_view());
        let v = describe(TopicKind::Cloud, &msg.to_bytes().unwrap()).unwrap();
        assert_eq!(v["field_of_view"]["max_range"], 4.0, "{v}");
        assert!(v["no_return"].is_null(), "{v}");
        msg.no_return = Some(shroud_msg::sample_no_return());
        let v = describe(TopicKind::Cloud, &msg.to_bytes().unwrap()).unwrap();
        assert_eq!(v["no_return"]["cones"], 2, "{v}");
        assert!(describe(TopicKind::Surrogate, &msg.to_bytes().unwrap()).is_err());
        assert!(describe(TopicKind::Status, b"\x00garbage").is_err());
    }
}
