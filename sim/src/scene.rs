//! One enum over all scenes, so a CLI or config file can pick a scene by name.

use crate::crossing::Crossing;
use crate::error::{check_finite, check_points, SceneError};
use crate::moving_spheres::MovingSpheres;
use crate::scanner::{
    MeshScan, RangeScanner, ScanFrame, ScanResolution, TableTopScan, TerrainScan,
};
use crate::table_top::TableTop;
use crate::terrain::Terrain;
use serde::{Deserialize, Serialize};
use shroud_msg::{FieldOfView, NoReturn};
use shroud_shapes::format::TriangleMesh;
use std::str::FromStr;

/// Any scene. Serialized with a `"kind"` tag holding the scene's name, e.g.
/// `{"kind": "terrain", "points": 50000}` (missing fields take their defaults).
///
/// The scan scenes (`scan-*`) cast a [`RangeScanner`]'s rays at a triangle mesh;
/// their clouds have at most [`Scene::points`] points (rays that miss or drop
/// out return none). Their BVH is built once, on the first scan or by
/// [`Scene::prepare`], and shared by clones.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum Scene {
    /// The paper's two moving spherical scatter clouds (animated).
    MovingSpheres(MovingSpheres),
    /// Hills and cliffs height field (static).
    Terrain(Terrain),
    /// Boxes and a cylinder on a table (static).
    TableTop(TableTop),
    /// A range scanner orbiting the table-top mesh (animated).
    ScanTableTop(TableTopScan),
    /// A range scanner orbiting the terrain mesh (animated).
    ScanTerrain(TerrainScan),
    /// A range scanner around a user's mesh: `{"kind": "scan-mesh", "mesh_path":
    /// "part.obj", "scanner": {...}}`; the caller loads the mesh and attaches it
    /// ([`Scene::mesh_to_load`], [`Scene::attach_mesh`]).
    ScanMesh(MeshScan),
    /// A person (a capsule) walking across a cell and back (animated).
    Crossing(Crossing),
}

impl Default for Scene {
    /// The paper's benchmark scene.
    fn default() -> Self {
        Self::MovingSpheres(MovingSpheres::default())
    }
}

impl Scene {
    /// Names accepted by [`Scene::by_name`], in declaration order.
    pub const NAMES: [&'static str; 6] = [
        "moving-spheres",
        "terrain",
        "table-top",
        "scan-table-top",
        "scan-terrain",
        "crossing",
    ];

    /// Name (and serde tag) of the scene that scans a user's mesh; it needs the
    /// mesh, so [`Scene::by_name`] does not make it (use [`Scene::scan_mesh`]).
    pub const MESH_SCENE: &'static str = "scan-mesh";

    /// The scene's name, as accepted by [`Scene::by_name`] (except
    /// [`Scene::MESH_SCENE`]) and used as serde tag.
    pub fn name(&self) -> &'static str {
        match self {
            Self::MovingSpheres(_) => Self::NAMES[0],
            Self::Terrain(_) => Self::NAMES[1],
            Self::TableTop(_) => Self::NAMES[2],
            Self::ScanTableTop(_) => Self::NAMES[3],
            Self::ScanTerrain(_) => Self::NAMES[4],
            Self::ScanMesh(_) => Self::MESH_SCENE,
            Self::Crossing(_) => Self::NAMES[5],
        }
    }

    /// The default configuration of the named scene with the given point count
    /// and seed: the one-liner a CLI needs. For scan scenes `points` is the ray
    /// budget ([`ScanResolution::Points`]) and `seed` the scanner's; their BVH is
    /// built here.
    pub fn by_name(name: &str, points: usize, seed: u64) -> Result<Self, SceneError> {
        check_points("points", points)?;
        let scanner = RangeScanner {
            resolution: ScanResolution::Points(points),
            seed,
            ..RangeScanner::default()
        };
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
            "scan-table-top" => Self::ScanTableTop(TableTopScan::new(TableTop::default(), scanner)),
            "scan-terrain" => Self::ScanTerrain(TerrainScan::new(Terrain::default(), scanner)),
            "crossing" => Self::Crossing(Crossing {
                points,
                seed,
                floor: None,
                ..Crossing::default()
            }),
            Self::MESH_SCENE => {
                return Err(SceneError::MeshRequired {
                    name: name.to_owned(),
                })
            }
            _ => {
                return Err(SceneError::UnknownScene {
                    name: name.to_owned(),
                })
            }
        };
        scene.prepare()?;
        Ok(scene)
    }

    /// A scene scanning `mesh` with `scanner` (its BVH is built here).
    pub fn scan_mesh(mesh: TriangleMesh, scanner: RangeScanner) -> Result<Self, SceneError> {
        Ok(Self::ScanMesh(MeshScan::new(mesh, scanner)?))
    }

    /// The path of a user mesh the scene names but does not hold yet (a
    /// deserialized `scan-mesh` scene): the caller reads it and calls
    /// [`Scene::attach_mesh`]. `None` for every other scene.
    pub fn mesh_to_load(&self) -> Option<&str> {
        match self {
            Self::ScanMesh(scan) if scan.mesh().is_none() => Some(&scan.mesh_path),
            _ => None,
        }
    }

    /// Attaches the user mesh of a `scan-mesh` scene and builds its BVH.
    pub fn attach_mesh(&mut self, mesh: TriangleMesh) -> Result<(), SceneError> {
        match self {
            Self::ScanMesh(scan) => scan.attach_mesh(mesh),
            other => Err(SceneError::NotAMeshScene { name: other.name() }),
        }
    }

    /// Builds whatever the scene computes once (the BVH of a scan scene) and
    /// checks its parameters; [`Scene::generate`] would do it on first use.
    pub fn prepare(&self) -> Result<(), SceneError> {
        match self {
            Self::ScanTableTop(s) => s.validate().and_then(|()| s.bvh().map(drop)),
            Self::ScanTerrain(s) => s.validate().and_then(|()| s.bvh().map(drop)),
            other => other.validate(),
        }
    }

    /// Whether the scene is a range scan (whose clouds have at most
    /// [`Scene::points`] points, and which has intensities).
    pub fn is_scan(&self) -> bool {
        matches!(
            self,
            Self::ScanTableTop(_) | Self::ScanTerrain(_) | Self::ScanMesh(_)
        )
    }

    /// The scanner of a scan scene.
    pub fn scanner(&self) -> Option<&RangeScanner> {
        match self {
            Self::ScanTableTop(s) => Some(&s.scanner),
            Self::ScanTerrain(s) => Some(&s.scanner),
            Self::ScanMesh(s) => Some(&s.scanner),
            _ => None,
        }
    }

    /// The full scan (points, intensities, sensor pose) at `time` seconds, or
    /// `Ok(None)` for a scene that is not a scan.
    pub fn scan_frame(&self, time: f64) -> Result<Option<ScanFrame>, SceneError> {
        check_finite("time", time)?;
        match self {
            Self::ScanTableTop(s) => s.scan(time).map(Some),
            Self::ScanTerrain(s) => s.scan(time).map(Some),
            Self::ScanMesh(s) => s.scan(time).map(Some),
            _ => Ok(None),
        }
    }

    /// The region a scan scene's scanner covers at `time` seconds (see
    /// [`RangeScanner::field_of_view`]), or `Ok(None)` for a scene that is
    /// not a scan.
    pub fn field_of_view(&self, time: f64) -> Result<Option<FieldOfView>, SceneError> {
        check_finite("time", time)?;
        self.scanner().map(|s| s.field_of_view(time)).transpose()
    }

    /// Number of points every generated cloud has; for a scan scene the number
    /// of rays, an upper bound on its points.
    pub fn points(&self) -> usize {
        match self {
            Self::MovingSpheres(s) => s.points,
            Self::Terrain(t) => t.points,
            Self::TableTop(t) => t.points,
            Self::Crossing(c) => c.total_points(),
            Self::ScanTableTop(_) | Self::ScanTerrain(_) | Self::ScanMesh(_) => {
                self.scanner().map_or(0, RangeScanner::rays)
            }
        }
    }

    /// Whether the cloud changes with time: the moving spheres, and scans whose
    /// scanner moves or has noise or dropouts (drawn afresh for every time).
    pub fn is_animated(&self) -> bool {
        match self {
            Self::MovingSpheres(_) | Self::Crossing(_) => true,
            Self::Terrain(_) | Self::TableTop(_) => false,
            Self::ScanTableTop(_) | Self::ScanTerrain(_) | Self::ScanMesh(_) => {
                self.scanner().is_some_and(RangeScanner::is_animated)
            }
        }
    }

    /// Checks every parameter of the wrapped scene (and that a `scan-mesh`
    /// scene has its mesh).
    pub fn validate(&self) -> Result<(), SceneError> {
        match self {
            Self::MovingSpheres(s) => s.validate(),
            Self::Terrain(t) => t.validate(),
            Self::TableTop(t) => t.validate(),
            Self::ScanTableTop(s) => s.validate(),
            Self::ScanTerrain(s) => s.validate(),
            Self::ScanMesh(s) => s.validate(),
            Self::Crossing(c) => c.validate(),
        }
    }

    /// The cloud at `time` seconds; static scenes return the same cloud at every
    /// (finite) time, so a frame loop can treat all scenes alike. A scan scene
    /// returns its [`Scene::scan_frame`]'s points.
    pub fn generate(&self, time: f64) -> Result<Vec<[f32; 3]>, SceneError> {
        self.generate_with_no_return(time).map(|(points, _)| points)
    }

    /// [`Self::generate`], and for a scan scene the directions in which its
    /// rays returned nothing ([`ScanFrame::no_return`]).
    pub fn generate_with_no_return(
        &self,
        time: f64,
    ) -> Result<(Vec<[f32; 3]>, Option<NoReturn>), SceneError> {
        check_finite("time", time)?;
        let scanned = |frame: ScanFrame| (frame.points, frame.no_return);
        match self {
            Self::MovingSpheres(s) => s.generate(time).map(|p| (p, None)),
            Self::Terrain(t) => t.generate().map(|p| (p, None)),
            Self::TableTop(t) => t.generate().map(|p| (p, None)),
            Self::Crossing(c) => c.generate(time).map(|p| (p, None)),
            Self::ScanTableTop(s) => s.scan(time).map(scanned),
            Self::ScanTerrain(s) => s.scan(time).map(scanned),
            Self::ScanMesh(s) => s.scan(time).map(scanned),
        }
    }
}

impl FromStr for Scene {
    type Err = SceneError;

    /// The named scene with its full default configuration (its BVH, for a scan
    /// scene, is built on first use).
    fn from_str(name: &str) -> Result<Self, SceneError> {
        let default = match name {
            "moving-spheres" => Self::MovingSpheres(MovingSpheres::default()),
            "terrain" => Self::Terrain(Terrain::default()),
            "table-top" => Self::TableTop(TableTop::default()),
            "scan-table-top" => Self::ScanTableTop(TableTopScan::default()),
            "scan-terrain" => Self::ScanTerrain(TerrainScan::default()),
            "crossing" => Self::Crossing(Crossing {
                floor: None,
                ..Crossing::default()
            }),
            Self::MESH_SCENE => {
                return Err(SceneError::MeshRequired {
                    name: name.to_owned(),
                })
            }
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
            if scene.is_scan() {
                assert!(cloud.len() <= scene.points() && cloud.len() > 600, "{name}");
            } else {
                assert_eq!(cloud.len(), 1_000);
            }
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
        let err = Scene::by_name("scan-mesh", 10, 0).unwrap_err();
        assert!(err.to_string().contains("Scene::scan_mesh"), "{err}");
        assert!("scan-mesh".parse::<Scene>().is_err());
        let mut terrain = Scene::by_name("terrain", 10, 0).unwrap();
        assert!(terrain.attach_mesh(TriangleMesh::default()).is_err());
    }

    #[test]
    fn scan_scenes_prepare_once_and_report_their_scanner() {
        let scene = Scene::by_name("scan-table-top", 2_000, 3).unwrap();
        let Scene::ScanTableTop(scan) = &scene else {
            panic!("wrong variant")
        };
        let bvh = scan.bvh().unwrap();
        scene.generate(0.1).unwrap();
        let copy = scene.clone();
        copy.generate(0.2).unwrap();
        let Scene::ScanTableTop(copied) = &copy else {
            panic!("wrong variant")
        };
        assert!(std::sync::Arc::ptr_eq(&bvh, &copied.bvh().unwrap()));
        assert_eq!(copy, scene);
        assert_eq!(scene.scanner().unwrap().seed, 3);
        assert!(scene.is_animated() && scene.is_scan() && scene.mesh_to_load().is_none());
        let frame = scene.scan_frame(0.1).unwrap().unwrap();
        assert_eq!(frame.points, scene.generate(0.1).unwrap());
        assert_eq!(frame.intensity.len(), frame.points.len());
        assert_eq!(Scene::default().scan_frame(0.1), Ok(None));
    }

    #[test]
    fn a_deserialized_mesh_scene_needs_its_mesh() {
        let json = r#"{"kind": "scan-mesh", "mesh_path": "parts/bracket.obj",
                       "scanner": {"resolution": {"grid": {"columns": 40, "rows": 30}}}}"#;
        let mut scene: Scene = serde_json::from_str(json).unwrap();
        assert_eq!(scene.name(), Scene::MESH_SCENE);
        assert_eq!(scene.mesh_to_load(), Some("parts/bracket.obj"));
        assert_eq!(scene.points(), 1_200);
        let err = scene.generate(0.0).unwrap_err();
        assert!(err.to_string().contains("parts/bracket.obj"), "{err}");
        assert!(scene.validate().is_err());
        scene
            .attach_mesh(TableTop::default().mesh(16).unwrap())
            .unwrap();
        assert_eq!(scene.mesh_to_load(), None);
        assert!(!scene.generate(0.0).unwrap().is_empty());
        let json = serde_json::to_string(&scene).unwrap();
        assert!(
            json.contains(r#""kind":"scan-mesh""#) && !json.contains("vertices"),
            "{json}"
        );
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
