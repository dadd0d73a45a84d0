//! A smooth fit (paper 004) from its message to a triangle mesh: the patches
//! sampled on a grid each and placed as their parametrisation places values.

use super::error::SceneError;
use shroud_msg::SmoothPatchesMessage;
use shroud_shapes::format::TriangleMesh;
use shroud_shapes::mesh::QuadMesh;
use shroud_shapes::smooth::SmoothSurface;

/// The fit in `msg` as triangles, `per_patch * per_patch` quads per patch (two
/// triangles each). `msg` must have passed [`SmoothPatchesMessage::from_bytes`].
pub fn smooth_mesh(
    msg: &SmoothPatchesMessage,
    per_patch: usize,
) -> Result<TriangleMesh, SceneError> {
    let vertices: Vec<[f64; 3]> = f64s(&msg.vertices)
        .chunks_exact(3)
        .map(|c| [c[0], c[1], c[2]])
        .collect();
    let quads: Vec<[u32; 4]> = msg
        .quads
        .as_chunks::<16>()
        .0
        .iter()
        .map(|q| {
            std::array::from_fn(|k| {
                u32::from_le_bytes([q[4 * k], q[4 * k + 1], q[4 * k + 2], q[4 * k + 3]])
            })
        })
        .collect();
    let domain = QuadMesh::new(vertices, quads)?;
    let surface = SmoothSurface {
        dim: msg.dim as usize,
        coefficients: f64s(&msg.coefficients),
        weights: Vec::new(),
    };
    let n = per_patch.max(1);
    let quads = match msg.kind.as_str() {
        "graph" => surface.tessellate_graph(&domain, n),
        "radial" => surface.tessellate_radial(&domain, n),
        "parametric" => surface.tessellate_parametric(&domain, n),
        other => return Err(SceneError::SmoothMesh(format!("unknown kind {other:?}"))),
    }?;
    let (vertices, faces) = quads.into_parts();
    Ok(TriangleMesh::from_quads(vertices, &faces))
}

fn f64s(bytes: &[u8]) -> Vec<f64> {
    bytes
        .as_chunks::<8>()
        .0
        .iter()
        .map(|c| f64::from_le_bytes(*c))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use shroud_shapes::smooth::sample_patches_message as sample_smooth_message;

    #[test]
    fn a_graph_fit_becomes_a_mesh_of_its_patches() {
        let msg = sample_smooth_message();
        let faces = msg.quads.len() / 16;
        let mesh = smooth_mesh(&msg, 4).unwrap();
        assert_eq!(mesh.triangles.len(), faces * 4 * 4 * 2);
        assert!(mesh.vertices.iter().flatten().all(|x| x.is_finite()));
        let mut bad = msg.clone();
        bad.kind = "torus".into();
        assert!(matches!(
            smooth_mesh(&bad, 2),
            Err(SceneError::SmoothMesh(_))
        ));
    }
}
