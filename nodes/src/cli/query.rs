//! `shroud query`: ask a stored surrogate where a point is, where a ray first
//! hits, or how high a region can reach.

use crate::{files, parse};
use anyhow::{bail, Result};
use clap::Args;
use glam::DVec3;
use shroud_surrogate::query::{
    BoundOptions, BoundQuery, Classify, PointClass, Ray, RayCast, SurrogateView, UvRect,
};
use std::path::PathBuf;

#[derive(Debug, Args)]
pub struct QueryArgs {
    /// A surrogate written by `shroud fit` (.json or binary).
    pub surrogate: PathBuf,
    /// Classify the world point x,y,z.
    #[arg(long, allow_hyphen_values = true)]
    pub point: Option<String>,
    /// First hit of the ray ox,oy,oz,dx,dy,dz.
    #[arg(long, allow_hyphen_values = true)]
    pub ray: Option<String>,
    /// Longest ray distance considered.
    #[arg(long, default_value_t = 1e9)]
    pub max_distance: f64,
    /// Conservative height range over the frame rectangle u0,v0,u1,v1.
    #[arg(long, allow_hyphen_values = true)]
    pub bound: Option<String>,
    /// Subdivision depth of the bound (tighter, still conservative).
    #[arg(long, default_value_t = 0)]
    pub refine: u32,
}

pub fn run(args: QueryArgs) -> Result<()> {
    if args.point.is_none() && args.ray.is_none() && args.bound.is_none() {
        bail!("nothing to ask: give --point, --ray or --bound");
    }
    let surrogate = files::read_surrogate(&args.surrogate)?;
    let view = SurrogateView::new(&surrogate)?;
    if let Some(text) = &args.point {
        let p = DVec3::from_array(parse::numbers::<3>(text, "point")?);
        println!("point {text}: {}", describe(view.classify(p)));
    }
    if let Some(text) = &args.ray {
        let [ox, oy, oz, dx, dy, dz] = parse::numbers::<6>(text, "ray")?;
        let ray = Ray {
            origin: DVec3::new(ox, oy, oz),
            direction: DVec3::new(dx, dy, dz),
        };
        match view.first_hit(&ray, args.max_distance)? {
            Some(hit) => println!(
                "ray {text}: hit the {:?} surface at distance {:.6} point ({:.6}, {:.6}, {:.6}) normal ({:.4}, {:.4}, {:.4})",
                hit.side, hit.distance, hit.point.x, hit.point.y, hit.point.z, hit.normal.x, hit.normal.y, hit.normal.z
            ),
            None => println!("ray {text}: no hit within {}", args.max_distance),
        }
    }
    if let Some(text) = &args.bound {
        let [u0, v0, u1, v1] = parse::numbers::<4>(text, "bound rectangle")?;
        let options = BoundOptions {
            refine: args.refine,
            ..Default::default()
        };
        for side in view.sides() {
            match side.range_over_uv(
                UvRect {
                    u: [u0, u1],
                    v: [v0, v1],
                },
                options,
            )? {
                Some(r) => println!(
                    "bound {text}: {:?} surface within [{:.6}, {:.6}]",
                    side.side(),
                    r.min,
                    r.max
                ),
                None => println!("bound {text}: {:?} surface absent there", side.side()),
            }
        }
    }
    Ok(())
}

fn describe(class: PointClass) -> String {
    match class {
        PointClass::OutsideDomain => "outside the surrogate's domain".into(),
        PointClass::Trimmed => "over a trimmed-out part of the domain (no data there)".into(),
        PointClass::Above { gap } => format!("above the surrogate by {gap:.6}"),
        PointClass::Below { gap } => format!("below the surrogate by {gap:.6}"),
        PointClass::Between {
            above_lower,
            below_upper,
        } => {
            format!("between the surfaces ({above_lower:.6} above the lower, {below_upper:.6} below the upper)")
        }
    }
}
