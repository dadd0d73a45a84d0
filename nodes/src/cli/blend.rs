//! `shroud blend`: drop a child point cloud onto a parent and blend them (Zou et
//! al., paper 001): by position (`--at`) or by a 2D cursor drag over a camera view
//! (`--drag`), then write the merged cloud with normals as PLY.

use crate::args::{points3, BlendShapeArgs};
use crate::{files, parse};
use anyhow::{bail, Context, Result};
use glam::{DVec2, DVec3};
use shroud_shapes::blend::AdjustTransform;
use shroud_shapes::blend::{
    blend, write_ply_with_normals, Camera, Child, DragSession, LocalAdjust, PolygonOfInterest,
    Prepared,
};
use std::path::PathBuf;
use std::time::Instant;

#[derive(clap::Args, Debug)]
pub struct BlendArgs {
    /// The parent cloud M_p (.ply, .pcd, .xyz, .csv).
    pub parent: PathBuf,
    /// The child cloud M_c, with an open boundary (its polygon of interest).
    pub child: PathBuf,
    /// Drop point x,y,z near the parent's surface (projected onto it).
    #[arg(long, allow_hyphen_values = true, required_unless_present = "drag")]
    pub at: Option<String>,
    /// Surface normal x,y,z at the drop point (default: estimated from the parent).
    #[arg(long, allow_hyphen_values = true)]
    pub normal: Option<String>,
    /// Spin about the normal, degrees.
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub spin: f64,
    /// Slide along the normal (cloud units; negative sinks the child).
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub lift: f64,
    /// Tilt about the centroid, degrees about the two tangent axes: a,b.
    #[arg(long, default_value = "0,0", allow_hyphen_values = true)]
    pub tilt: String,
    /// Place by dragging: paste at the first point of --path, then drag along it.
    #[arg(long, requires = "path", conflicts_with = "at")]
    pub drag: bool,
    /// Camera eye,target[,up]: ex,ey,ez,tx,ty,tz[,ux,uy,uz] (up defaults to z).
    #[arg(long, allow_hyphen_values = true, default_value = "0,-4,6,0,0,0")]
    pub camera: String,
    /// Vertical field of view, degrees.
    #[arg(long, default_value_t = 45.0)]
    pub fov: f64,
    /// Image size WxH in pixels.
    #[arg(long, default_value = "800x600")]
    pub size: String,
    /// Cursor path in pixels: "x,y;x,y;..." (the first point is where the child is pasted).
    #[arg(long, allow_hyphen_values = true)]
    pub path: Option<String>,
    /// Depth-buffer block size n (the paper's discretisation, 10).
    #[arg(long, default_value_t = 10)]
    pub block: usize,
    /// Polygon of interest in the child's coordinates: "x,y,z;x,y,z;..."
    /// (default: the child's longest open boundary loop).
    #[arg(long, allow_hyphen_values = true)]
    pub polygon: Option<String>,
    #[command(flatten)]
    pub shape: BlendShapeArgs,
    /// Where to write the blended cloud (binary PLY with normals and a source
    /// property: 0 parent, 1 child, 2 transition).
    #[arg(short, long)]
    pub output: PathBuf,
}

pub fn run(args: &BlendArgs) -> Result<()> {
    if args
        .output
        .extension()
        .is_none_or(|e| !e.eq_ignore_ascii_case("ply"))
    {
        bail!(
            "{}: the output must be a .ply file (it carries normals)",
            args.output.display()
        );
    }
    let params = args.shape.params()?;
    let start = Instant::now();
    let parent_points = files::read_cloud(&args.parent)?;
    let child_points = files::read_cloud(&args.child)?;
    let parent = Prepared::new(&parent_points, "parent", params.normal_k)
        .with_context(|| format!("parent {}", args.parent.display()))?;
    let child_cloud = Prepared::new(&child_points, "child", params.normal_k)
        .with_context(|| format!("child {}", args.child.display()))?;
    let polygon = match &args.polygon {
        Some(text) => Some(PolygonOfInterest::from_polyline(points3(text, "polygon")?)?),
        None => None,
    };
    let child = Child::new(child_cloud, polygon, &params.boundary)
        .with_context(|| format!("child {}", args.child.display()))?;
    let prepare_ms = start.elapsed().as_secs_f64() * 1e3;
    let [a, b] = parse::numbers::<2>(&args.tilt, "tilt")?;
    let adjust = LocalAdjust {
        lift: args.lift,
        spin: args.spin.to_radians(),
        tilt: [a.to_radians(), b.to_radians()],
    };
    let placement = if args.drag {
        let session = drag(args, &parent, &child)?;
        let (p_t, v_t) = session.placement();
        adjust.transform(p_t, v_t).after(&session.transform())
    } else {
        let at = DVec3::from(parse::numbers::<3>(
            args.at.as_deref().unwrap_or_default(),
            "at",
        )?);
        let (p_t, mut v_t) = parent
            .surface_pair(at, 16)
            .context("cannot find the parent's surface at --at")?;
        if let Some(text) = &args.normal {
            v_t = DVec3::from(parse::numbers::<3>(text, "normal")?).normalize_or_zero();
            if v_t == DVec3::ZERO {
                bail!("--normal must not be the zero vector");
            }
        }
        child.placement(p_t, v_t, &adjust)
    };
    let result = blend(&parent, &child, &placement, &params).context("blend failed")?;
    files::write(&args.output, &write_ply_with_normals(&result.merged))?;
    let r = &result.report;
    println!(
        "blended {} + {} points into {} ({} transition points kept of {}), prepared in {prepare_ms:.1} ms",
        parent_points.len(),
        child_points.len(),
        result.merged.len(),
        r.kept_transition,
        r.transition_points
    );
    println!(
        "regions: F_p {} points, F_c {} points; RBF {} centres of {} constraints in {} rounds, max residual {:.3e}",
        r.parent_region, r.child_region, r.greedy.centres, r.constraints, r.greedy.rounds, r.greedy.max_residual
    );
    let t = r.times;
    println!(
        "blend {:.1} ms: regions {:.1}, normals {:.1}, rbf {:.1}, sampling {:.1}, merge {:.1}",
        t.total, t.regions, t.normals, t.rbf, t.sampling, t.merge
    );
    Ok(())
}

fn drag(args: &BlendArgs, parent: &Prepared, child: &Child) -> Result<DragSession> {
    let values: Vec<f64> = args
        .camera
        .split(',')
        .map(|s| {
            s.trim()
                .parse::<f64>()
                .with_context(|| format!("camera '{}': '{s}' is not a number", args.camera))
        })
        .collect::<Result<_>>()?;
    let up = match values.len() {
        6 => DVec3::Z,
        9 => DVec3::new(values[6], values[7], values[8]),
        n => bail!(
            "camera '{}' needs 6 or 9 numbers (eye, target[, up]), got {n}",
            args.camera
        ),
    };
    let (width, height) = parse::grid(&args.size).context("--size")?;
    let eye = DVec3::new(values[0], values[1], values[2]);
    let target = DVec3::new(values[3], values[4], values[5]);
    let distance = eye.distance(target);
    let extent = parent
        .points()
        .iter()
        .map(|p| p.distance(eye))
        .fold(0.0, f64::max);
    let camera = Camera {
        eye,
        target,
        up,
        fov_y: args.fov.to_radians(),
        width,
        height,
        near: 1e-3 * distance.max(1e-9),
        far: 2.0 * extent.max(distance) + 1.0,
    };
    let path: Vec<DVec2> = points2(args.path.as_deref().unwrap_or_default())?;
    let Some((&first, rest)) = path.split_first() else {
        bail!("--path needs at least one cursor position");
    };
    let mut session = DragSession::paste(
        parent.points(),
        camera,
        args.block,
        child.p_i,
        child.v_i,
        first,
    )
    .with_context(|| format!("cannot paste at cursor {first}"))?;
    for &cursor in rest {
        session
            .drag_to(cursor)
            .with_context(|| format!("cannot drag to cursor {cursor}"))?;
    }
    Ok(session)
}

/// `"x,y;x,y;..."`.
fn points2(text: &str) -> Result<Vec<DVec2>> {
    text.split(';')
        .filter(|s| !s.trim().is_empty())
        .map(|s| parse::numbers::<2>(s, "path").map(DVec2::from))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_point_lists() {
        assert_eq!(
            points2("1,2; 3,4;").unwrap(),
            vec![DVec2::new(1.0, 2.0), DVec2::new(3.0, 4.0)]
        );
        assert!(points2("1,2,3").is_err());
        assert_eq!(points3("0,0,1;1,0,1;0,1,1", "polygon").unwrap().len(), 3);
        assert!(points3("0,0;1", "polygon").is_err());
    }
}
