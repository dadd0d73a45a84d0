//! The error type for invalid scene parameters, and the checks that produce it.

/// Upper bound on the number of points one call may generate (1.2 GB of `[f32; 3]`),
/// so that an absurd request is reported instead of aborting on allocation.
pub const MAX_POINTS: usize = 100_000_000;

/// Why a scene could not be generated. Every variant names the offending parameter
/// (e.g. `radii[1]`, `cliffs[0].normal`) so a config file can be fixed directly.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SceneError {
    /// A parameter (or the requested time) is NaN or infinite.
    #[error("scene parameter `{parameter}` must be finite, got {value}")]
    NonFinite { parameter: String, value: f64 },
    /// A length that must be strictly positive (radius, width, height) is not.
    #[error("scene parameter `{parameter}` must be positive, got {value}")]
    NotPositive { parameter: String, value: f64 },
    /// An amplitude or fraction that must be zero or more is negative.
    #[error("scene parameter `{parameter}` must be non-negative, got {value}")]
    Negative { parameter: String, value: f64 },
    /// A parameter lies outside its closed admissible interval.
    #[error("scene parameter `{parameter}` must lie in [{min}, {max}], got {value}")]
    OutOfRange {
        parameter: String,
        value: f64,
        min: f64,
        max: f64,
    },
    /// Zero points were requested; an empty cloud has no surrogate.
    #[error("scene parameter `{parameter}` must be at least 1, got 0")]
    ZeroPoints { parameter: String },
    /// More than [`MAX_POINTS`] points were requested.
    #[error("scene parameter `{parameter}` must be at most {max}, got {value}")]
    TooManyPoints {
        parameter: String,
        value: usize,
        max: usize,
    },
    /// A shape is degenerate (empty rectangle, zero normal, ...).
    #[error("scene parameter `{parameter}` is degenerate: {reason}")]
    Degenerate {
        parameter: String,
        reason: &'static str,
    },
    /// `Scene::by_name` got a name it does not know.
    #[error("unknown scene `{name}`; expected one of: moving-spheres, terrain, table-top, scan-table-top, scan-terrain, crossing (scan-mesh is built from a mesh with Scene::scan_mesh)")]
    UnknownScene { name: String },
    /// `part_by_name` got a name it does not know.
    #[error("unknown part `{name}`; expected hemisphere or half-cylinder")]
    UnknownPart { name: String },
    /// A parameter lies outside an open or half-open interval (a field of view in
    /// (0, π), a dropout probability in [0, 1)).
    #[error("scene parameter `{parameter}` must lie in {interval}, got {value}")]
    OutOfInterval {
        parameter: String,
        value: f64,
        interval: &'static str,
    },
    /// A scan's empty rays need a cone too wide to state (a grid too coarse
    /// for its field of view).
    #[error("the scan's rays without return cannot be stated: {reason}")]
    NoReturn { reason: String },
    /// A scanner resolution (columns, rows or point budget) is zero.
    #[error("scene parameter `{parameter}` must be at least 1 (a scan needs rays), got 0")]
    ZeroResolution { parameter: String },
    /// A mesh to scan has nothing to hit.
    #[error("the mesh cannot be scanned: {reason}")]
    EmptyMesh { reason: &'static str },
    /// A mesh vertex is NaN or infinite (also once narrowed to f32).
    #[error("mesh vertex {vertex} coordinate {axis} is {value}, must be finite (in f32)")]
    MeshVertexNotFinite {
        vertex: usize,
        axis: usize,
        value: f64,
    },
    /// A mesh triangle refers to a vertex that does not exist.
    #[error(
        "mesh triangle {triangle} refers to vertex {index}, but the mesh has {vertices} vertices"
    )]
    MeshIndexOutOfRange {
        triangle: usize,
        index: u32,
        vertices: usize,
    },
    /// A `scan-mesh` scene was used before its mesh was attached.
    #[error("the scan-mesh scene has no mesh yet: read `{path}` (e.g. with shroud_shapes::format::parse_triangle_mesh) and attach it with Scene::attach_mesh")]
    MeshNotLoaded { path: String },
    /// `Scene::by_name` was asked for a scene that needs a mesh.
    #[error("scene `{name}` is built from a triangle mesh: use Scene::scan_mesh, or deserialize it and attach the mesh")]
    MeshRequired { name: String },
    /// A mesh was attached to a scene that does not scan a user mesh.
    #[error("scene `{name}` takes no mesh: only scan-mesh does")]
    NotAMeshScene { name: &'static str },
}

/// Rejects NaN and infinities.
pub(crate) fn check_finite(parameter: &str, value: f64) -> Result<(), SceneError> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(SceneError::NonFinite {
            parameter: parameter.to_owned(),
            value,
        })
    }
}

/// Rejects non-finite coordinates, naming the component (`centre[2]`).
pub(crate) fn check_finite_all(parameter: &str, values: &[f64]) -> Result<(), SceneError> {
    values
        .iter()
        .enumerate()
        .try_for_each(|(i, &v)| check_finite(&format!("{parameter}[{i}]"), v))
}

/// Rejects values that are not finite and strictly positive.
pub(crate) fn check_positive(parameter: &str, value: f64) -> Result<(), SceneError> {
    check_finite(parameter, value)?;
    if value > 0.0 {
        Ok(())
    } else {
        Err(SceneError::NotPositive {
            parameter: parameter.to_owned(),
            value,
        })
    }
}

/// Rejects values that are not finite or are below zero.
pub(crate) fn check_non_negative(parameter: &str, value: f64) -> Result<(), SceneError> {
    check_finite(parameter, value)?;
    if value >= 0.0 {
        Ok(())
    } else {
        Err(SceneError::Negative {
            parameter: parameter.to_owned(),
            value,
        })
    }
}

/// Rejects values outside `[min, max]` (and non-finite ones).
pub(crate) fn check_range(
    parameter: &str,
    value: f64,
    min: f64,
    max: f64,
) -> Result<(), SceneError> {
    check_finite(parameter, value)?;
    if (min..=max).contains(&value) {
        Ok(())
    } else {
        Err(SceneError::OutOfRange {
            parameter: parameter.to_owned(),
            value,
            min,
            max,
        })
    }
}

/// Rejects zero and absurdly large point counts.
pub(crate) fn check_points(parameter: &str, points: usize) -> Result<(), SceneError> {
    if points == 0 {
        return Err(SceneError::ZeroPoints {
            parameter: parameter.to_owned(),
        });
    }
    if points > MAX_POINTS {
        return Err(SceneError::TooManyPoints {
            parameter: parameter.to_owned(),
            value: points,
            max: MAX_POINTS,
        });
    }
    Ok(())
}

/// Rejects a rectangle whose `max` corner is not strictly beyond its `min` corner.
pub(crate) fn check_rectangle(
    parameter: &str,
    min: [f64; 2],
    max: [f64; 2],
) -> Result<(), SceneError> {
    check_finite_all(&format!("{parameter}.min"), &min)?;
    check_finite_all(&format!("{parameter}.max"), &max)?;
    if max[0] > min[0] && max[1] > min[1] {
        Ok(())
    } else {
        Err(SceneError::Degenerate {
            parameter: parameter.to_owned(),
            reason: "max must exceed min in both x and y",
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn messages_name_the_parameter() {
        let err = check_positive("radii[1]", -0.5).unwrap_err();
        assert!(err.to_string().contains("radii[1]"), "{err}");
        let err = check_points("points", 0).unwrap_err();
        assert!(err.to_string().contains("points"), "{err}");
        let err = check_finite_all("centre", &[0.0, f64::NAN]).unwrap_err();
        assert!(err.to_string().contains("centre[1]"), "{err}");
    }

    #[test]
    fn checks_accept_valid_values() {
        assert!(check_positive("r", 1.0).is_ok());
        assert!(check_range("split", 0.0, 0.0, 1.0).is_ok());
        assert!(check_non_negative("noise", 0.0).is_ok());
        assert!(check_points("points", MAX_POINTS).is_ok());
        assert!(check_rectangle("rect", [0.0, 0.0], [1.0, 1.0]).is_ok());
    }

    #[test]
    fn checks_reject_invalid_values() {
        assert!(check_positive("r", 0.0).is_err());
        assert!(check_positive("r", f64::INFINITY).is_err());
        assert!(check_range("split", 1.5, 0.0, 1.0).is_err());
        assert!(check_non_negative("noise", -1e-9).is_err());
        assert!(check_range("split", f64::NAN, 0.0, 1.0).is_err());
        assert!(check_points("points", MAX_POINTS + 1).is_err());
        assert!(check_rectangle("rect", [0.0, 0.0], [1.0, 0.0]).is_err());
    }
}
