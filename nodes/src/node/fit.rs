//! The `fit` node: certified surrogates from the clouds of one stream. The
//! subscriber hands payloads to a bounded drop-oldest mailbox; one worker thread
//! decodes, fits with warm start, and publishes.

use crate::args::SurrogateShapeArgs;
use crate::runtime::{run_node, NodeCommon, NodeContext};
use crate::transport::{sample_published_ns, unix_ns, Mailbox};
use anyhow::Result;
use clap::Args;
use shroud_graph::metrics::names as metric;
use shroud_graph::metrics::{Percentiles, SequenceGaps};
use shroud_msg::{counted_transit, CloudView, MessageError, SurrogateMessage, TopicKind};
use shroud_surrogate::SurrogateWire;
use shroud_surrogate::{FitError, Sides, SurrogateFitter};
use std::sync::Arc;
use std::time::{Duration, Instant};
use zenoh::bytes::ZBytes;
use zenoh::Wait;

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

/// A received cloud payload with its arrival time and its publication's.
struct Arrival {
    payload: ZBytes,
    key: String,
    /// The sample's zenoh timestamp (the publisher's wall clock).
    published_ns: Option<u64>,
    received_ns: u64,
    received: Instant,
}

/// The cloud's transit to this node as counted (see [`counted_transit`]);
/// `None`, counted and logged, when it cannot be known.
fn cloud_transit(ctx: &NodeContext, arrival: &Arrival, max_offset_ns: u64) -> Option<u64> {
    let Some(published_ns) = arrival.published_ns else {
        ctx.metrics.add(metric::NO_PUBLISH_STAMP, 1);
        tracing::warn!(key = %arrival.key, "cloud without a zenoh timestamp: its transit is unknown");
        return None;
    };
    match counted_transit(published_ns, arrival.received_ns, max_offset_ns) {
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
    let input = ctx.key(TopicKind::Cloud, &args.input)?;
    let publisher = ctx.publisher(
        TopicKind::Surrogate,
        args.output.as_deref().unwrap_or(&args.input),
    )?;
    let output = publisher.key_expr().to_string();
    let mailbox = Arc::new(Mailbox::new(args.queue));
    let inbox = mailbox.clone();
    let _subscriber = ctx
        .session
        .declare_subscriber(&input)
        .callback(move |sample| {
            inbox.push(Arrival {
                payload: sample.payload().clone(),
                key: sample.key_expr().to_string(),
                published_ns: sample_published_ns(&sample),
                received_ns: unix_ns(),
                received: Instant::now(),
            });
        })
        .wait()
        .map_err(|e| anyhow::anyhow!("subscribe {input}: {e}"))?;
    tracing::info!(%input, %output, "fitting");
    let mut fit_ms = Percentiles::new(256);
    let mut latency_ms = Percentiles::new(256);
    let mut copied = Vec::new();
    let mut gaps = SequenceGaps::default();
    let max_offset_ns = (args.max_clock_offset * 1e9) as u64;
    while !ctx.stopping() {
        ctx.metrics
            .set_counter(metric::DROPPED_BACKLOG, mailbox.dropped());
        let Some(arrival) = mailbox.pop(Duration::from_millis(100)) else {
            continue;
        };
        ctx.metrics.add(metric::RECEIVED, 1);
        let decode_start = Instant::now();
        // Shared-memory payloads are one contiguous slice: the view borrows it,
        // and an aligned cloud's floats are fitted where they lie.
        let bytes = arrival.payload.to_bytes();
        let msg = match CloudView::from_bytes(&bytes) {
            Ok(msg) => msg,
            Err(e) => {
                ctx.drop_malformed(&arrival.key, &e);
                continue;
            }
        };
        // Clouds this node never decoded: dropped by its backlog policy
        // (`dropped_backlog`) or lost before it; the difference is the loss
        // on the way.
        gaps.observe(&msg.source, msg.sequence);
        ctx.metrics
            .set_counter(metric::SEQUENCE_GAPS, gaps.missing());
        let points = match points_of(&msg, &mut copied) {
            Ok(points) => points,
            Err(e) => {
                ctx.drop_malformed(&arrival.key, &e);
                continue;
            }
        };
        let decode_ms = decode_start.elapsed().as_secs_f64() * 1e3;
        let start = Instant::now();
        let surrogate = match fitter.fit(points) {
            Ok(s) => s,
            // A NaN or an empty cloud is bad input, like a corrupted message.
            Err(e @ FitError::Cloud(_)) => {
                ctx.drop_malformed(&arrival.key, &e);
                continue;
            }
            Err(e) => {
                ctx.metrics.add(metric::FIT_ERRORS, 1);
                tracing::warn!(sequence = msg.sequence, "cloud not fitted: {e}");
                continue;
            }
        };
        let fit_ns = start.elapsed().as_nanos() as u64;
        let mut out = SurrogateMessage::from_surrogate(
            &surrogate,
            msg.stamp_ns,
            msg.sequence,
            &msg.source,
            fit_ns,
        );
        // The cloud's age so far, on the upstream nodes' clocks, its transit
        // to this node (wall clocks, within the offset bound), and its time
        // here on ours (queue, decode, fit): what the guard ages it by.
        let Some(transit_ns) = cloud_transit(&ctx, &arrival, max_offset_ns) else {
            continue;
        };
        // The publication's timestamp is taken before the time here is
        // measured and the message encoded: the encoding, and any pause
        // before the put, then count as transit at the guard.
        let published = ctx.session.new_timestamp();
        let here_ns = arrival.received.elapsed().as_nanos() as u64;
        // The certificate is about the points as placed; how far the sensor
        // may have misplaced them travels on, for the guard to subtract.
        out.position_error_m = msg.position_error_m;
        // So is where the sensor looked: outside it the surface was not
        // measured, whatever the interpolation says.
        out.field_of_view = msg.field_of_view;
        out.no_return = msg.no_return.clone();
        out.pipeline_ns = msg
            .pipeline_ns
            .saturating_add(transit_ns)
            .saturating_add(here_ns);
        let publish_start = Instant::now();
        match out.to_bytes() {
            Ok(bytes) => match publisher.put(bytes).timestamp(published).wait() {
                Ok(()) => ctx.metrics.add(metric::PUBLISHED, 1),
                Err(e) => {
                    ctx.metrics.add(metric::PUBLISH_ERRORS, 1);
                    tracing::warn!("publish {output}: {e}");
                }
            },
            Err(e) => tracing::error!("encode surrogate: {e}"),
        }
        let publish_ms = publish_start.elapsed().as_secs_f64() * 1e3;
        let transit_ms = arrival.received_ns.saturating_sub(msg.stamp_ns) as f64 / 1e6;
        let wait_ms = (decode_start - arrival.received).as_secs_f64() * 1e3;
        tracing::debug!(
            sequence = msg.sequence,
            transit_ms,
            wait_ms,
            decode_ms,
            fit_ms = fit_ns as f64 / 1e6,
            publish_ms,
            "frame"
        );
        fit_ms.push(fit_ns as f64 / 1e6);
        latency_ms.push(out.pipeline_ns as f64 / 1e6);
        ctx.metrics.set(metric::POINTS, points.len() as f64);
        // Where a frame's time goes besides the fit, for `shroud topic echo`.
        ctx.metrics.set(metric::TRANSIT_MS, transit_ms);
        ctx.metrics.set(metric::QUEUE_WAIT_MS, wait_ms);
        ctx.metrics.set(metric::DECODE_MS, decode_ms);
        ctx.metrics.set(metric::PUBLISH_MS, publish_ms);
        if let (Some(f), Some(l)) = (fit_ms.summary(), latency_ms.summary()) {
            ctx.metrics.set(metric::FIT_P50_MS, f.p50);
            ctx.metrics.set(metric::FIT_P99_MS, f.p99);
            ctx.metrics.set(metric::LATENCY_P50_MS, l.p50);
            ctx.metrics.set(metric::LATENCY_P99_MS, l.p99);
        }
    }
    mailbox.close();
    Ok(())
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
