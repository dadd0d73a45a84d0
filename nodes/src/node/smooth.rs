//! The `smooth` node: the accurate counterpart of the safe surrogate (paper
//! 004). It fits every incoming cloud by G1 smooth spline functions over a
//! configured domain (a planar quad mesh for graphs, the cube-sphere for
//! radial functions, a quad mesh in space for parametric surfaces with
//! parameter correction) and publishes the patches with their error measures.
//! Points outside the domain are skipped and counted.

use crate::args::SmoothDomainArgs;
use crate::runtime::{run_node, NodeCommon, NodeContext};
use crate::transport::unix_ns;
use anyhow::Result;
use clap::Args;
use shroud_graph::metrics::names as metric;
use shroud_msg::{CloudMessage, CloudView, SmoothPatchesMessage};
use shroud_shapes::smooth::{patches_message, SmoothFitReport};
use shroud_shapes::smooth::{Parametrisation, SmoothFitter, SmoothSurface};
use std::sync::Arc;
use std::time::Instant;

#[derive(Debug, Clone, Args)]
pub struct SmoothNodeArgs {
    #[command(flatten)]
    pub common: NodeCommon,
    /// Cloud stream to fit (`shroud/<ns>/cloud/<input>`).
    #[arg(long, default_value = "sim")]
    pub input: String,
    /// Patch stream (`shroud/<ns>/smooth/<output>`); default: the input's name.
    #[arg(long)]
    pub output: Option<String>,
    #[command(flatten)]
    pub domain: SmoothDomainArgs,
    /// Thin-plate smoothing weight lambda of eq. (26).
    #[arg(long, default_value_t = 1e-6)]
    pub lambda: f64,
    /// Rounds of parameter correction for a parametric fit (default 3).
    #[arg(long)]
    pub corrections: Option<usize>,
}

pub fn run(args: SmoothNodeArgs) -> Result<()> {
    anyhow::ensure!(
        args.lambda.is_finite() && args.lambda >= 0.0,
        "--lambda must be finite and >= 0"
    );
    let (domain, parametrisation) = args.domain.load()?;
    let corrections = parametrisation.corrections(args.corrections)?;
    let fitter = SmoothFitter::new(domain)?;
    let common = args.common.clone();
    run_node(&common, "smooth", move |ctx| {
        serve(ctx, args, fitter, parametrisation, corrections)
    })
}

fn serve(
    ctx: Arc<NodeContext>,
    args: SmoothNodeArgs,
    fitter: SmoothFitter,
    parametrisation: Parametrisation,
    corrections: usize,
) -> Result<()> {
    let input = ctx.subscribe::<CloudMessage>(&args.input, 1)?;
    let output =
        ctx.output::<SmoothPatchesMessage>(args.output.as_deref().unwrap_or(&args.input))?;
    tracing::info!(
        input = input.key(),
        output = output.key(),
        functions = fitter.basis.len(),
        kind = parametrisation.kind(),
        "fitting"
    );
    ctx.metrics
        .set(metric::FUNCTIONS, fitter.basis.len() as f64);
    let setup = FitSetup {
        fitter: &fitter,
        parametrisation: &parametrisation,
        lambda: args.lambda,
        corrections,
    };
    // The last surface published: a parametric fit of the next cloud starts
    // from it (fewer corrections for the same error on a steady object).
    let mut previous: Option<SmoothSurface> = None;
    input.for_each(
        |arrival, cloud| match fit_one(&ctx, &setup, previous.as_ref(), &cloud) {
            Ok(Some((message, surface))) => {
                previous = Some(surface);
                output.put(&message);
            }
            Ok(None) => {}
            Err(e) => ctx.drop_malformed(&arrival.key, &e),
        },
    );
    Ok(())
}

/// What every cloud is fitted with.
struct FitSetup<'a> {
    fitter: &'a SmoothFitter,
    parametrisation: &'a Parametrisation,
    lambda: f64,
    corrections: usize,
}

/// Fits one cloud, warm-started on `previous`. A cloud whose points are
/// not finite is an error (the caller counts it); a cloud that cannot be
/// fitted is logged and counted here, and gives `None`.
fn fit_one(
    ctx: &NodeContext,
    setup: &FitSetup<'_>,
    previous: Option<&SmoothSurface>,
    msg: &CloudView<'_>,
) -> Result<Option<(SmoothPatchesMessage, SmoothSurface)>, shroud_msg::MessageError> {
    let FitSetup {
        fitter,
        parametrisation,
        lambda,
        corrections,
    } = *setup;
    let mut points = Vec::new();
    msg.read_points(&mut points)?;
    let start = Instant::now();
    let xyz: Vec<[f64; 3]> = points.iter().map(|p| p.map(f64::from)).collect();
    let (samples, values, outside) = parametrisation.sample_inside(&xyz);
    ctx.metrics.add(metric::POINTS_OUTSIDE, outside as u64);
    let fit = fitter.fit_as(
        parametrisation,
        &samples,
        &values,
        (lambda, corrections),
        previous,
    );
    let (surface, errors) = match fit {
        Ok(fit) => {
            let errors = fit.errors();
            (fit.surface, errors)
        }
        Err(e) => {
            ctx.metrics.add(metric::FIT_ERRORS, 1);
            tracing::warn!(sequence = msg.sequence, "cloud not fitted: {e}");
            return Ok(None);
        }
    };
    let fit_ns = start.elapsed().as_nanos() as u64;
    ctx.metrics.set(metric::FIT_MS, fit_ns as f64 / 1e6);
    ctx.metrics.set(metric::RMSE, errors.rmse);
    ctx.metrics.set(
        metric::LATENCY_MS,
        unix_ns().saturating_sub(msg.stamp_ns) as f64 / 1e6,
    );
    let report = SmoothFitReport {
        source_stamp_ns: msg.stamp_ns,
        source_sequence: msg.sequence,
        source: &msg.source,
        kind: parametrisation.kind(),
        functions: fitter.basis.len(),
        lambda,
        points: samples.len(),
        outside,
        errors,
        fit_ns,
    };
    let message = patches_message(&fitter.domain.mesh, &surface, &report);
    Ok(Some((message, surface)))
}
