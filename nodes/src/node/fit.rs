//! The `fit` node: certified surrogates from the clouds of one stream. Its
//! input keeps the newest `--queue` clouds; one worker fits each with warm
//! start and publishes it, aged by the cloud's time upstream, its transit
//! and its time here.

use crate::args::SurrogateShapeArgs;
use crate::runtime::{run_node, Arrival, NodeCommon, NodeContext};
use crate::transport::monotonic_ns;
use anyhow::Result;
use clap::Args;
use shroud_graph::metrics::names as metric;
use shroud_graph::metrics::{Percentiles, SequenceGaps};
use shroud_msg::{counted_transit, CloudMessage, CloudView, MessageError, SurrogateMessage};
use shroud_surrogate::SurrogateWire;
use shroud_surrogate::{FitError, Sides, SurrogateFitter};
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
    let fitter = SurrogateFitter::new(options)?;
    anyhow::ensure!((1..=64).contains(&args.queue), "--queue must be 1 to 64");
    anyhow::ensure!(
        args.max_clock_offset.is_finite() && (0.0..=10.0).contains(&args.max_clock_offset),
        "--max-clock-offset must be in [0, 10] seconds"
    );
    let common = args.common.clone();
    run_node(&common, "fit", move |ctx| serve(ctx, args, fitter))
}

fn serve(ctx: Arc<NodeContext>, args: FitNodeArgs, mut fitter: SurrogateFitter) -> Result<()> {
    let input = ctx.subscribe::<CloudMessage>(&args.input, args.queue)?;
    let output_name = args.output.as_deref().unwrap_or(&args.input);
    let output = ctx.output::<SurrogateMessage>(output_name)?;
    tracing::info!(input = input.key(), output = output.key(), "fitting");
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
    });
    Ok(())
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
