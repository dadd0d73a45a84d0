//! One enum over all scenes, so a CLI or config file can pick a scene by name.

use crate::error::{check_finite, check_points, SceneError};
use crate::moving_spheres::MovingSpheres;
use crate::table_top::TableTop;
use crate::terrain::Terrain;
use serde::{Deserialize, Serialize};
use std::str::FromStr;

/// Any scene. Serialized with a `"kind"` tag holding the scene's name, e.g.
/// `{"kind": "terrain", "points": 50000}` (missing fields take their defaults).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum Scene {
    /// The paper's two moving spherical scatter clouds (animated).
    MovingSpheres(MovingSpheres),
    /// Hills and cliffs height field (static).
    Terrain(Terrain),
    /// Boxes and a cylinder on a table (static).
    TableTop(TableTop),
}

impl Default for Scene {
    /// The paper's benchmark scene.
    fn default() -> Self {
        Self::MovingSpheres(MovingSpheres::default())
    }
}

impl Scene {
    /// Names accepted by [`Scene::by_name`], in declaration order.
    pub const NAMES: [&'static str; 3] = ["moving-spheres", "terrain", "table-top"];

    /// The scene's name, as accepted by [`Scene::by_name`] and used as serde tag.
    pub fn name(&self) -> &'static str {
        match self {
            Self::MovingSpheres(_) => Self::NAMES[0],
            Self::Terrain(_) => Self::NAMES[1],
            Self::TableTop(_) => Self::NAMES[2],
        }
    }

    /// The default configuration of the named scene with the given point count
    /// and seed: the one-liner a CLI needs.
    pub fn by_name(name: &str, points: usize, seed: u64) -> Result<Self, SceneError> {
        check_points("points", points)?;
        let scene = match name {
            "moving-spheres" => Self::MovingSpheres(MovingSpheres {
                points,
                seed,
                ..MovingSpheres::default()
            }),
            "terrain" => Self::Terrain(Terrain {
                points,
                seed,
                ..Terrain::default()
            }),
            "table-top" => Self::TableTop(TableTop {
                points,
                seed,
                ..TableTop::default()
            }),
            _ => {
                return Err(SceneError::UnknownScene {
                    name: name.to_owned(),
                })
            }
        };
        Ok(scene)
    }

    /// Number of points every generated cloud has.
    pub fn points(&self) -> usize {
        match self {
            Self::MovingSpheres(s) => s.points,
            Self::Terrain(t) => t.points,
            Self::TableTop(t) => t.points,
        }
    }

    /// Whether the cloud changes with time (only the moving spheres do).
    pub fn is_animated(&self) -> bool {
        matches!(self, Self::MovingSpheres(_))
    }

    /// Checks every parameter of the wrapped scene.
    pub fn validate(&self) -> Result<(), SceneError> {
        match self {
            Self::MovingSpheres(s) => s.validate(),
            Self::Terrain(t) => t.validate(),
            Self::TableTop(t) => t.validate(),
        }
    }

    /// The cloud at `time` seconds; static scenes return the same cloud at every
    /// (finite) time, so a frame loop can treat all scenes alike.
    pub fn generate(&self, time: f64) -> Result<Vec<[f32; 3]>, SceneError> {
        check_finite("time", time)?;
        match self {
            Self::MovingSpheres(s) => s.generate(time),
            Self::Terrain(t) => t.generate(),
            Self::TableTop(t) => t.generate(),
        }
    }
}

impl FromStr for Scene {
    type Err = SceneError;

    /// The named scene with its full default configuration.
    fn from_str(name: &str) -> Result<Self, SceneError> {
        let default = match name {
            "moving-spheres" => Self::MovingSpheres(MovingSpheres::default()),
            "terrain" => Self::Terrain(Terrain::default()),
            "table-top" => Self::TableTop(TableTop::default()),
            _ => {
                return Err(SceneError::UnknownScene {
                    name: name.to_owned(),
                })
            }
        };
        Ok(default)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip() {
        for name in Scene::NAMES {
            let scene = Scene::by_name(name, 123, 4).unwrap();
            assert_eq!(scene.name(), name);
            assert_eq!(scene.points(), 123);
            assert_eq!(name.parse::<Scene>().unwrap().name(), name);
        }
    }

    #[test]
    fn every_scene_generates_exactly_and_deterministically() {
        for name in Scene::NAMES {
            let scene = Scene::by_name(name, 1_000, 7).unwrap();
            let cloud = scene.generate(0.5).unwrap();
            assert_eq!(cloud.len(), 1_000);
            assert_eq!(cloud, scene.generate(0.5).unwrap());
            assert!(cloud.iter().flatten().all(|c| c.is_finite()));
            assert_eq!(scene.is_animated(), cloud != scene.generate(1.5).unwrap());
        }
    }

    #[test]
    fn seed_reaches_the_scene() {
        for name in Scene::NAMES {
            let a = Scene::by_name(name, 100, 1).unwrap().generate(0.0).unwrap();
            let b = Scene::by_name(name, 100, 2).unwrap().generate(0.0).unwrap();
            assert_ne!(a, b, "{name}");
        }
    }

    #[test]
    fn bad_requests_are_errors() {
        let err = Scene::by_name("teapot", 10, 0).unwrap_err();
        assert!(err.to_string().contains("teapot"), "{err}");
        assert!("teapot".parse::<Scene>().is_err());
        let err = Scene::by_name("terrain", 0, 0).unwrap_err();
        assert!(err.to_string().contains("points"), "{err}");
        assert!(Scene::default().generate(f64::INFINITY).is_err());
    }

    #[test]
    fn serde_tag_is_the_name_and_fields_default() {
        let json = serde_json::to_string(&Scene::by_name("table-top", 50, 3).unwrap()).unwrap();
        assert!(json.contains(r#""kind":"table-top""#), "{json}");
        let parsed: Scene = serde_json::from_str(r#"{"kind": "terrain", "points": 77}"#).unwrap();
        assert_eq!(parsed, Scene::by_name("terrain", 77, 0).unwrap());
        assert_eq!(serde_json::from_str::<Scene>(&json).unwrap().points(), 50);
    }
}
