//! Scan scenes: a [`RangeScanner`] over the table-top mesh, the terrain mesh or a
//! user's mesh. Each keeps its [`Bvh`] behind an `Arc`, built once and reused by
//! every scan (and shared by clones); the table-top and terrain caches remember the
//! geometry they were built from and rebuild only when it is changed.

use super::{Bvh, RangeScanner, ScanFrame};
use crate::error::SceneError;
use crate::mesh_scene::{check_terrain_cells, DEFAULT_CYLINDER_SEGMENTS, DEFAULT_TERRAIN_CELLS};
use crate::table_top::TableTop;
use crate::terrain::Terrain;
use serde::{Deserialize, Serialize};
use shroud_shapes::format::TriangleMesh;
use std::fmt;
use std::sync::{Arc, Mutex, PoisonError};

/// A lazily built BVH with the key (geometry) it was built from. Not part of a
/// scene's value: every cache compares equal, and `Debug` shows only whether it
/// is built.
pub(crate) struct BvhCache<K> {
    slot: Mutex<Option<(K, Arc<Bvh>)>>,
}

impl<K> Default for BvhCache<K> {
    fn default() -> Self {
        Self {
            slot: Mutex::new(None),
        }
    }
}

impl<K: Clone> Clone for BvhCache<K> {
    fn clone(&self) -> Self {
        let slot = self.slot.lock().unwrap_or_else(PoisonError::into_inner);
        Self {
            slot: Mutex::new(slot.clone()),
        }
    }
}

impl<K> fmt::Debug for BvhCache<K> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let slot = self.slot.lock().unwrap_or_else(PoisonError::into_inner);
        f.debug_struct("BvhCache")
            .field("built", &slot.is_some())
            .finish()
    }
}

impl<K> PartialEq for BvhCache<K> {
    fn eq(&self, _: &Self) -> bool {
        true
    }
}

impl<K: Clone + PartialEq> BvhCache<K> {
    /// The BVH for `key`, built by `build` unless the cached one has that key.
    fn get_or_build(
        &self,
        key: &K,
        build: impl FnOnce() -> Result<TriangleMesh, SceneError>,
    ) -> Result<Arc<Bvh>, SceneError> {
        let mut slot = self.slot.lock().unwrap_or_else(PoisonError::into_inner);
        if let Some((cached, bvh)) = &*slot {
            if cached == key {
                return Ok(Arc::clone(bvh));
            }
        }
        let bvh = Arc::new(Bvh::build(&build()?)?);
        *slot = Some((key.clone(), Arc::clone(&bvh)));
        Ok(bvh)
    }
}

/// A range scanner over the table-top mesh ([`TableTop::mesh`]): only the table's
/// geometry is used, not its sampling fields (`points`, `noise`, ...).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct TableTopScan {
    /// The table and the objects on it.
    pub table: TableTop,
    /// Side segments of each cylinder's mesh, in 3 ..= 65536.
    pub segments: usize,
    /// The scanner.
    pub scanner: RangeScanner,
    #[serde(skip)]
    cache: BvhCache<(TableTop, usize)>,
}

impl Default for TableTopScan {
    /// The default table, 48 segments per cylinder, the default scanner.
    fn default() -> Self {
        Self::new(TableTop::default(), RangeScanner::default())
    }
}

impl TableTopScan {
    /// `scanner` over `table`, cylinders with the default 48 segments.
    pub fn new(table: TableTop, scanner: RangeScanner) -> Self {
        Self {
            table,
            segments: DEFAULT_CYLINDER_SEGMENTS,
            scanner,
            cache: BvhCache::default(),
        }
    }

    /// Checks the table, the segment count and the scanner.
    pub fn validate(&self) -> Result<(), SceneError> {
        self.scanner.validate()?;
        self.mesh().map(drop)
    }

    /// The scanned mesh.
    pub fn mesh(&self) -> Result<TriangleMesh, SceneError> {
        self.table.mesh(self.segments)
    }

    /// The BVH of the mesh, built on the first call (or after the geometry
    /// changed) and shared afterwards.
    pub fn bvh(&self) -> Result<Arc<Bvh>, SceneError> {
        let key = (self.table.clone(), self.segments);
        self.cache.get_or_build(&key, || self.mesh())
    }

    /// The scan at `time` seconds.
    pub fn scan(&self, time: f64) -> Result<ScanFrame, SceneError> {
        self.scanner.validate()?;
        self.scanner.scan(&*self.bvh()?, time)
    }
}

/// A range scanner over the terrain mesh ([`Terrain::mesh`]); the terrain's
/// sampling fields (`points`, `noise`, `seed`) are not used.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct TerrainScan {
    /// The height field.
    pub terrain: Terrain,
    /// Grid cells of the mesh along x and y, each >= 1.
    pub cells: [usize; 2],
    /// The scanner.
    pub scanner: RangeScanner,
    #[serde(skip)]
    cache: BvhCache<(Terrain, [usize; 2])>,
}

impl Default for TerrainScan {
    /// The default terrain on a 160 x 120 cell mesh, the default scanner.
    fn default() -> Self {
        Self::new(Terrain::default(), RangeScanner::default())
    }
}

impl TerrainScan {
    /// `scanner` over `terrain`, meshed with the default 160 x 120 cells.
    pub fn new(terrain: Terrain, scanner: RangeScanner) -> Self {
        Self {
            terrain,
            cells: DEFAULT_TERRAIN_CELLS,
            scanner,
            cache: BvhCache::default(),
        }
    }

    /// Checks the terrain, the cell counts and the scanner (without meshing).
    pub fn validate(&self) -> Result<(), SceneError> {
        self.scanner.validate()?;
        self.terrain.validate()?;
        check_terrain_cells(self.cells).map(drop)
    }

    /// The scanned mesh.
    pub fn mesh(&self) -> Result<TriangleMesh, SceneError> {
        self.terrain.mesh(self.cells)
    }

    /// The BVH of the mesh, built on the first call (or after the geometry
    /// changed) and shared afterwards.
    pub fn bvh(&self) -> Result<Arc<Bvh>, SceneError> {
        let key = (self.terrain.clone(), self.cells);
        self.cache.get_or_build(&key, || self.mesh())
    }

    /// The scan at `time` seconds.
    pub fn scan(&self, time: f64) -> Result<ScanFrame, SceneError> {
        self.scanner.validate()?;
        self.scanner.scan(&*self.bvh()?, time)
    }
}

/// A user's mesh and its BVH, attached by the caller.
#[derive(Clone)]
struct LoadedMesh {
    mesh: Arc<TriangleMesh>,
    bvh: Arc<Bvh>,
}

impl PartialEq for LoadedMesh {
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.mesh, &other.mesh) || self.mesh == other.mesh
    }
}

impl fmt::Debug for LoadedMesh {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("LoadedMesh")
            .field("vertices", &self.mesh.vertices.len())
            .field("triangles", &self.mesh.triangles.len())
            .finish()
    }
}

/// A range scanner over a user's triangle mesh. The serialized form names the
/// mesh by `mesh_path` only: this crate does no file I/O, so whoever deserializes
/// the scene reads that file (e.g. with
/// `shroud_shapes::format::parse_triangle_mesh`) and attaches the mesh with
/// [`MeshScan::attach_mesh`]. Until then scanning fails with
/// [`SceneError::MeshNotLoaded`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct MeshScan {
    /// Where the mesh is stored, for the caller to resolve (may be empty when the
    /// mesh was given directly).
    pub mesh_path: String,
    /// The scanner.
    pub scanner: RangeScanner,
    #[serde(skip)]
    loaded: Option<LoadedMesh>,
}

impl Default for MeshScan {
    /// No mesh yet, no path, the default scanner.
    fn default() -> Self {
        Self {
            mesh_path: String::new(),
            scanner: RangeScanner::default(),
            loaded: None,
        }
    }
}

impl MeshScan {
    /// `scanner` over `mesh`; builds the BVH now (failing on an empty or invalid
    /// mesh).
    pub fn new(mesh: TriangleMesh, scanner: RangeScanner) -> Result<Self, SceneError> {
        let mut scan = Self {
            scanner,
            ..Self::default()
        };
        scan.attach_mesh(mesh)?;
        Ok(scan)
    }

    /// Attaches (or replaces) the mesh and builds its BVH; on error the scene
    /// keeps its previous mesh.
    pub fn attach_mesh(&mut self, mesh: TriangleMesh) -> Result<(), SceneError> {
        let bvh = Arc::new(Bvh::build(&mesh)?);
        self.loaded = Some(LoadedMesh {
            mesh: Arc::new(mesh),
            bvh,
        });
        Ok(())
    }

    /// The attached mesh, if any.
    pub fn mesh(&self) -> Option<&TriangleMesh> {
        self.loaded.as_ref().map(|l| &*l.mesh)
    }

    /// The BVH of the attached mesh.
    pub fn bvh(&self) -> Result<Arc<Bvh>, SceneError> {
        self.loaded
            .as_ref()
            .map(|l| Arc::clone(&l.bvh))
            .ok_or_else(|| SceneError::MeshNotLoaded {
                path: self.mesh_path.clone(),
            })
    }

    /// Checks the scanner and that a mesh is attached.
    pub fn validate(&self) -> Result<(), SceneError> {
        self.scanner.validate()?;
        self.bvh().map(drop)
    }

    /// The scan at `time` seconds.
    pub fn scan(&self, time: f64) -> Result<ScanFrame, SceneError> {
        self.scanner.validate()?;
        self.scanner.scan(&*self.bvh()?, time)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_bvh_is_built_once_and_shared_by_clones() {
        let scan = TableTopScan::default();
        let first = scan.bvh().unwrap();
        assert!(Arc::ptr_eq(&first, &scan.bvh().unwrap()));
        let copy = scan.clone();
        assert!(Arc::ptr_eq(&first, &copy.bvh().unwrap()));
        assert_eq!(copy, TableTopScan::default());
        assert!(format!("{scan:?}").contains("built: true"));
    }

    #[test]
    fn changed_geometry_rebuilds_the_bvh() {
        let mut scan = TerrainScan {
            cells: [8, 6],
            ..TerrainScan::default()
        };
        let coarse = scan.bvh().unwrap();
        scan.cells = [16, 12];
        let fine = scan.bvh().unwrap();
        assert!(!Arc::ptr_eq(&coarse, &fine));
        assert_eq!(fine.triangle_count(), 2 * 16 * 12);
        scan.scanner.seed = 5; // not geometry
        assert!(Arc::ptr_eq(&fine, &scan.bvh().unwrap()));
        let mut table = TableTopScan::default();
        let before = table.bvh().unwrap();
        table.table.boxes.pop();
        assert_eq!(
            table.bvh().unwrap().triangle_count(),
            before.triangle_count() - 12
        );
    }

    #[test]
    fn mesh_scans_compare_by_mesh() {
        let mesh = TableTop::default().mesh(8).unwrap();
        let a = MeshScan::new(mesh.clone(), RangeScanner::default()).unwrap();
        let b = MeshScan::new(mesh, RangeScanner::default()).unwrap();
        assert_eq!(a, b);
        let c = MeshScan::new(
            TableTop::default().mesh(9).unwrap(),
            RangeScanner::default(),
        );
        assert_ne!(a, c.unwrap());
        assert_ne!(a, MeshScan::default());
        let mut failed = a.clone();
        assert!(failed.attach_mesh(TriangleMesh::default()).is_err());
        assert_eq!(failed, a);
    }
}
