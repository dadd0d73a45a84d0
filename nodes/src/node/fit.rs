//! The `fit` node: certified surrogates from the clouds of one stream. Its
//! input keeps the newest `--queue` clouds; one worker fits each with warm
//! start and publishes it, aged by the cloud's time upstream, its transit
//! and its time here; with `--sectors`, then each sector of the cloud's
//! field of view on its own stream.

use crate::args::SurrogateShapeArgs;
use crate::runtime::{run_node, Arrival, NodeCommon, NodeContext, Output};
use crate::transport::monotonic_ns;
use anyhow::{Context, Result};
use clap::Args;
use shroud_graph::metrics::names as metric;
use shroud_graph::metrics::{Percentiles, SequenceGaps};
use shroud_msg::{
    counted_transit, sector_stream, CloudMessage, CloudView, MessageError, SurrogateMessage,
};
use shroud_surrogate::SurrogateWire;
use shroud_surrogate::{FitError, SectorFitter, Sides, SurrogateFitter};
use std::sync::Arc;

#[derive(Debug, Clone, Args)]
pub struct FitNodeArgs {
    #[command(flatten)]
    pub common: NodeCommon,
    /// Cloud stream to fit (`shroud/<ns>/cloud/<input>`).
    #[arg(long, default_value = "sim")]
    pub input: String,
    /// Surrogate stream to publish (`shroud/<ns>/surrogate/<output>`); default: the input's name.
    #[arg(long)]
    pub output: Option<String>,
    /// upper, lower, or sandwich (the guard needs the sandwich).
    #[arg(long, default_value = "sandwich")]
    pub side: Sides,
    #[command(flatten)]
    pub shape: SurrogateShapeArgs,
    /// Clouds waiting for the fitter at most; older ones are dropped and counted.
    #[arg(long, default_value_t = 1)]
    pub queue: usize,
    /// Bound (seconds) on how far the cloud publishers' wall clocks and this
    /// node's may disagree: added to every cloud's measured transit; a cloud
    /// that seems to come from further in the future is dropped
    /// (`clock_offset`). One host: the default; across hosts: the clock
    /// synchronisation's bound.
    #[arg(long, default_value_t = 0.001)]
    pub max_clock_offset: f64,
    /// Also fit each cloud in N x N overlapping sectors of the field of view
    /// it states, each along its own axis, published on `<output>.s<k>`
    /// (k = row * N + column) for a guard with the same `sectors`: tighter
    /// than one view of a wide perspective sensor (0: the whole view only).
    #[arg(long, default_value_t = 0, value_parser = clap::builder::RangedU64ValueParser::<usize>::new().range(0..=8))]
    pub sectors: usize,
    /// How far each sector reaches, in its grid cell's angular
    /// half-diagonals (>= 1: overlapping sectors; never past the field of view).
    #[arg(long, default_value_t = 1.5)]
    pub sector_reach: f64,
}

/// The cloud's transit to this node as counted (see [`counted_transit`]);
/// `None`, counted and logged, when it cannot be known.
fn cloud_transit(ctx: &NodeContext, arrival: &Arrival, max_offset_ns: u64) -> Option<u64> {
    let Some(published_ns) = arrival.published_ns else {
        ctx.metrics.add(metric::NO_PUBLISH_STAMP, 1);
        tracing::warn!(key = %arrival.key, "cloud without a zenoh timestamp: its transit is unknown");
        return None;
    };
    match counted_transit(published_ns, arrival.received_wall_ns, max_offset_ns) {
        Ok(transit) => Some(transit),
        Err(e) => {
            ctx.metrics.add(metric::CLOCK_OFFSET, 1);
            tracing::warn!(key = %arrival.key, "cloud dropped: {e}");
            None
        }
    }
}

pub fn run(args: FitNodeArgs) -> Result<()> {
    let options = args.shape.options(args.side)?;
    let fitter = SurrogateFitter::new(options.clone())?;
    let sectors = (args.sectors > 0)
        .then(|| SectorFitter::new(args.sectors, args.sector_reach, options))
        .transpose()
        .context("--sectors and --sector-reach")?;
    anyhow::ensure!((1..=64).contains(&args.queue), "--queue must be 1 to 64");
    anyhow::ensure!(
        args.max_clock_offset.is_finite() && (0.0..=10.0).contains(&args.max_clock_offset),
        "--max-clock-offset must be in [0, 10] seconds"
    );
    let common = args.common.clone();
    run_node(&common, "fit", move |ctx| serve(ctx, args, fitter, sectors))
}

fn serve(
    ctx: Arc<NodeContext>,
    args: FitNodeArgs,
    mut fitter: SurrogateFitter,
    sectors: Option<SectorFitter>,
) -> Result<()> {
    let input = ctx.subscribe::<CloudMessage>(&args.input, args.queue)?;
    let output_name = args.output.as_deref().unwrap_or(&args.input);
    let output = ctx.output::<SurrogateMessage>(output_name)?;
    let mut sectors = sectors
        .map(|fitter| SectorOutputs::new(&ctx, output_name, fitter))
        .transpose()?;
    let sector_count = sectors.as_ref().map_or(0, |s| s.outputs.len());
    tracing::info!(
        input = input.key(),
        output = output.key(),
        sectors = sector_count,
        "fitting"
    );
    let max_offset_ns = (args.max_clock_offset * 1e9) as u64;
    let (mut times, mut copied) = (FrameTimes::default(), Vec::new());
    input.for_each(|arrival, cloud| {
        // Clouds this node never decoded: dropped by its backlog policy
        // (`dropped_backlog`) or lost before it; the difference is the loss
        // on the way.
        times.gaps.observe(&cloud.source, cloud.sequence);
        ctx.metrics
            .set_counter(metric::SEQUENCE_GAPS, times.gaps.missing());
        let points = match points_of(&cloud, &mut copied) {
            Ok(points) => points,
            Err(e) => return ctx.drop_malformed(&arrival.key, &e),
        };
        let decoded_ns = monotonic_ns();
        let surrogate = match fitter.fit(points) {
            Ok(s) => s,
            // A NaN or an empty cloud is bad input, like a corrupted message.
            Err(e @ FitError::Cloud(_)) => return ctx.drop_malformed(&arrival.key, &e),
            Err(e) => {
                ctx.metrics.add(metric::FIT_ERRORS, 1);
                return tracing::warn!(sequence = cloud.sequence, "cloud not fitted: {e}");
            }
        };
        let fit_ns = monotonic_ns().saturating_sub(decoded_ns);
        let Some(transit_ns) = cloud_transit(&ctx, arrival, max_offset_ns) else {
            return;
        };
        // The publication's timestamp is taken before the time here is
        // measured and the message encoded: the encoding, and any pause
        // before the put, then count as transit at the guard. The age is the
        // cloud's upstream, its transit (wall clocks, within the offset
        // bound) and its time here on our clock (queue, decode, fit).
        let published = ctx.session.new_timestamp();
        let since_ns = transit_ns.saturating_add(arrival.held_ns());
        let out = SurrogateMessage::of_cloud(&surrogate, &cloud, fit_ns, since_ns);
        let publish_start = monotonic_ns();
        output.put_stamped(&out, published);
        times.record(
            &ctx,
            arrival,
            &cloud,
            [decoded_ns, fit_ns, publish_start],
            &out,
        );
        ctx.metrics.set(metric::POINTS, points.len() as f64);
        if let Some(sectors) = sectors.as_mut() {
            sectors.publish(&ctx, arrival, &cloud, points, transit_ns);
        }
    });
    Ok(())
}

/// The sectors of each cloud, fitted and published after its whole view.
struct SectorOutputs {
    fitter: SectorFitter,
    outputs: Vec<Output<SurrogateMessage>>,
    /// Whether a cloud without a field of view was logged already.
    warned: bool,
    /// Per sector, whether an error was logged already: a sector with no
    /// room in the field of view fails on every cloud.
    failed: Vec<bool>,
}

impl SectorOutputs {
    fn new(ctx: &NodeContext, output: &str, fitter: SectorFitter) -> Result<Self> {
        let outputs: Vec<_> = (0..fitter.count())
            .map(|k| {
                let name = sector_stream(output, k);
                ctx.output::<SurrogateMessage>(&name)
                    .with_context(|| format!("--sectors: sector stream {name:?}"))
            })
            .collect::<Result<_>>()?;
        Ok(Self {
            failed: vec![false; outputs.len()],
            fitter,
            outputs,
            warned: false,
        })
    }

    /// Fits and publishes every sector of `cloud` that holds points, each
    /// aged like the whole view: upstream, transit, and its time here until
    /// its own publication.
    fn publish(
        &mut self,
        ctx: &NodeContext,
        arrival: &Arrival,
        cloud: &CloudView<'_>,
        points: &[[f32; 3]],
        transit_ns: u64,
    ) {
        let Some(fov) = cloud.field_of_view else {
            ctx.metrics.add(metric::SECTORS_UNSTATED, 1);
            if !std::mem::replace(&mut self.warned, true) {
                tracing::warn!(key = %arrival.key, "the cloud states no field of view: its sectors cannot be fitted (the whole view still is)");
            }
            return;
        };
        for (index, output) in self.outputs.iter().enumerate() {
            let start = monotonic_ns();
            let fit = match self
                .fitter
                .fit(index, &fov, cloud.no_return.as_ref(), points)
            {
                Ok(Some(fit)) => fit,
                Ok(None) => continue,
                Err(e) => {
                    ctx.metrics.add(metric::SECTOR_ERRORS, 1);
                    if !std::mem::replace(&mut self.failed[index], true) {
                        tracing::warn!(sequence = cloud.sequence, "{e} (logged once a sector)");
                    }
                    continue;
                }
            };
            let fit_ns = monotonic_ns().saturating_sub(start);
            let published = ctx.session.new_timestamp();
            let since_ns = transit_ns.saturating_add(arrival.held_ns());
            let mut out = SurrogateMessage::of_cloud(&fit.surrogate, cloud, fit_ns, since_ns);
            out.field_of_view = Some(fit.field_of_view);
            out.no_return = fit.no_return;
            output.put_stamped(&out, published);
            ctx.metrics.add(metric::SECTORS_PUBLISHED, 1);
        }
    }
}

/// Where a frame's time goes, for the node's status and `shroud topic echo`.
struct FrameTimes {
    fit_ms: Percentiles,
    latency_ms: Percentiles,
    gaps: SequenceGaps,
}

impl Default for FrameTimes {
    fn default() -> Self {
        Self {
            fit_ms: Percentiles::new(256),
            latency_ms: Percentiles::new(256),
            gaps: SequenceGaps::default(),
        }
    }
}

impl FrameTimes {
    /// `[decoded, fit duration, publish start]` on the monotonic clock.
    fn record(
        &mut self,
        ctx: &NodeContext,
        arrival: &Arrival,
        cloud: &CloudView<'_>,
        [decoded_ns, fit_ns, publish_start]: [u64; 3],
        out: &SurrogateMessage,
    ) {
        let ms = |ns: u64| ns as f64 / 1e6;
        let transit_ms = ms(arrival.received_wall_ns.saturating_sub(cloud.stamp_ns));
        let wait_ms = ms(arrival.queued_ns());
        let decode_ms = ms(decoded_ns.saturating_sub(arrival.taken_ns));
        let publish_ms = ms(monotonic_ns().saturating_sub(publish_start));
        let fit_ms = ms(fit_ns);
        tracing::debug!(
            sequence = cloud.sequence,
            transit_ms,
            wait_ms,
            decode_ms,
            fit_ms,
            publish_ms,
            "frame"
        );
        self.fit_ms.push(fit_ms);
        self.latency_ms.push(ms(out.pipeline_ns));
        let m = &ctx.metrics;
        m.set(metric::TRANSIT_MS, transit_ms);
        m.set(metric::QUEUE_WAIT_MS, wait_ms);
        m.set(metric::DECODE_MS, decode_ms);
        m.set(metric::PUBLISH_MS, publish_ms);
        if let (Some(f), Some(l)) = (self.fit_ms.summary(), self.latency_ms.summary()) {
            m.set(metric::FIT_P50_MS, f.p50);
            m.set(metric::FIT_P99_MS, f.p99);
            m.set(metric::LATENCY_P50_MS, l.p50);
            m.set(metric::LATENCY_P99_MS, l.p99);
        }
    }
}

/// The cloud's points: in place when the payload allows it, else copied into
/// `copied` (which keeps its allocation between frames). In place, the values
/// are checked by the fitter's first pass rather than here (see `serve`).
fn points_of<'a>(
    msg: &'a CloudView<'_>,
    copied: &'a mut Vec<[f32; 3]>,
) -> Result<&'a [[f32; 3]], MessageError> {
    if let Some(in_place) = msg.raw_points_in_place() {
        return Ok(in_place);
    }
    msg.read_points(copied)?;
    Ok(copied)
}
