//! A surrogate as a `foxglove.SceneUpdate`: one entity per stream and side,
//! `surrogate/<stream>/upper` and `.../lower`, each an indexed triangle list of
//! the trimmed surface. Stable ids make each update replace the last; a side
//! the surrogate no longer has is deleted.

use super::geometry::{color, identity, point, timestamp, WORLD_FRAME};
use foxglove::messages::scene_entity_deletion::Type as DeletionType;
use foxglove::messages::{
    KeyValuePair, SceneEntity, SceneEntityDeletion, SceneUpdate, TriangleListPrimitive,
};
use shroud_msg::SurrogateMessage;
use shroud_surrogate::{Side, Surrogate};
use shroud_viewers::scene::{surface_rgba, surrogate_meshes, SurfaceMesh};

fn entity_id(stream: &str, side: Side) -> String {
    format!("surrogate/{stream}/{}", side.name())
}

/// Subdivisions of each trim triangle of a surrogate's mesh, in the bridge
/// and in recordings alike.
pub const SURFACE_PER_CELL: usize = 2;

/// The surfaces of `surrogate` (decoded from `msg`, published on `stream`),
/// each kept trim triangle split into `per_cell * per_cell` triangles.
pub fn surrogate_scene(
    stream: &str,
    msg: &SurrogateMessage,
    surrogate: &Surrogate,
    per_cell: usize,
) -> SceneUpdate {
    let meshes = surrogate_meshes(surrogate, per_cell);
    let deletions = [Side::Upper, Side::Lower]
        .into_iter()
        .filter(|side| meshes.iter().all(|m| m.side != *side))
        .map(|side| SceneEntityDeletion {
            timestamp: Some(timestamp(msg.source_stamp_ns)),
            r#type: DeletionType::MatchingId as i32,
            id: entity_id(stream, side),
        })
        .collect();
    let entities = meshes
        .iter()
        .map(|mesh| surface_entity(stream, msg, mesh))
        .collect();
    SceneUpdate {
        deletions,
        entities,
    }
}

fn surface_entity(stream: &str, msg: &SurrogateMessage, mesh: &SurfaceMesh) -> SceneEntity {
    let c = &mesh.certificate;
    let metadata = [
        ("side", mesh.side.name().to_string()),
        ("source_sequence", msg.source_sequence.to_string()),
        ("points_checked", c.points_checked.to_string()),
        ("violations", c.violations.to_string()),
        ("min_gap", c.min_gap.to_string()),
    ]
    .into_iter()
    .map(|(key, value)| KeyValuePair {
        key: key.into(),
        value,
    })
    .collect();
    SceneEntity {
        timestamp: Some(timestamp(msg.source_stamp_ns)),
        frame_id: WORLD_FRAME.into(),
        id: entity_id(stream, mesh.side),
        metadata,
        triangles: vec![TriangleListPrimitive {
            pose: Some(identity()),
            points: mesh.positions.iter().copied().map(point).collect(),
            color: Some(color(surface_rgba(mesh.side))),
            colors: Vec::new(),
            indices: mesh.indices.clone(),
        }],
        ..Default::default()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use shroud_surrogate::SurrogateWire;
    use shroud_surrogate::{fit_surrogate, FitOptions, Sides};

    fn fitted(sides: Sides) -> (SurrogateMessage, Surrogate) {
        let points: Vec<[f32; 3]> = (0..900)
            .map(|i| {
                let (x, y) = ((i % 30) as f32 * 0.1, (i / 30) as f32 * 0.1);
                [x, y, (x * 2.0).sin() * 0.3 + y * 0.1]
            })
            .collect();
        let options = FitOptions {
            cols: 6,
            rows: 6,
            sides,
            ..Default::default()
        };
        let s = fit_surrogate(&points, &options).unwrap();
        (
            SurrogateMessage::from_surrogate(&s, 2_000_000_000, 5, "sim", 1),
            s,
        )
    }

    #[test]
    fn a_sandwich_is_two_indexed_triangle_lists_with_stable_ids() {
        let (msg, s) = fitted(Sides::Sandwich);
        let update = surrogate_scene("spheres", &msg, &s, 2);
        assert!(update.deletions.is_empty());
        let ids: Vec<&str> = update.entities.iter().map(|e| e.id.as_str()).collect();
        assert_eq!(ids, ["surrogate/spheres/upper", "surrogate/spheres/lower"]);
        for (entity, mesh) in update.entities.iter().zip(surrogate_meshes(&s, 2)) {
            let list = &entity.triangles[0];
            assert_eq!(list.points.len(), mesh.positions.len());
            assert_eq!(list.indices, mesh.indices);
            assert_eq!(list.indices.len() % 3, 0);
            assert!(list
                .indices
                .iter()
                .all(|&i| (i as usize) < list.points.len()));
            let c = list.color.unwrap();
            assert_eq!([c.r, c.g, c.b, c.a], surface_rgba(mesh.side));
            assert_eq!(entity.frame_id, WORLD_FRAME);
        }
        // More subdivisions, four times the triangles.
        let finer = surrogate_scene("spheres", &msg, &s, 4);
        assert_eq!(
            finer.entities[0].triangles[0].indices.len(),
            4 * update.entities[0].triangles[0].indices.len()
        );
    }

    #[test]
    fn a_missing_side_is_deleted() {
        let (msg, s) = fitted(Sides::Upper);
        let update = surrogate_scene("s", &msg, &s, 1);
        assert_eq!(update.entities.len(), 1);
        assert_eq!(update.deletions.len(), 1);
        assert_eq!(update.deletions[0].id, "surrogate/s/lower");
        assert_eq!(update.deletions[0].r#type, DeletionType::MatchingId as i32);
    }
}
