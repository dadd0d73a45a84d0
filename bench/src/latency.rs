//! `shroud-bench latency`: end-to-end latency of the fit node, from a cloud
//! published to its surrogate received, through a real `shroud node fit` process
//! and real zenoh sessions, at several cloud sizes and rates.

use super::graph::BenchGraph;
use super::BenchArgs;
use anyhow::Result;
use shroud_graph::metrics::Percentiles;
use shroud_msg::{CloudView, TopicKind};
use shroud_nodes::transport::{topic_publisher, unix_ns, PayloadWriter};
use shroud_sim::MovingSpheres;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// One row of the table.
struct Row {
    points: usize,
    rate: f64,
    published: u64,
    received: u64,
    latency: Option<shroud_graph::metrics::LatencySummary>,
    fit_p50: f64,
    overhead_p50: f64,
}

/// What the subscriber collects.
#[derive(Default)]
struct Received {
    latency_ms: Vec<f64>,
    fit_ms: Vec<f64>,
}

pub fn run(args: &BenchArgs) -> Result<()> {
    let sizes: &[usize] = if args.quick {
        &[30_000]
    } else {
        &[30_000, 300_000]
    };
    let rates: &[f64] = if args.quick { &[10.0] } else { &[10.0, 30.0] };
    let seconds = if args.quick { 3.0 } else { args.seconds };
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(1)
        .enable_all()
        .build()?;
    let mut rows = Vec::new();
    for &points in sizes {
        for &rate in rates {
            let row = runtime.block_on(measure(points, rate, seconds))?;
            eprintln!("measured {} points at {} Hz", row.points, row.rate);
            rows.push(row);
        }
    }
    print_table(&rows, seconds);
    Ok(())
}

async fn measure(points: usize, rate: f64, seconds: f64) -> Result<Row> {
    let mut graph = BenchGraph::start("latency").await?;
    graph.spawn("fit", "fit", &["--input", "bench"], None)?;
    let received = Arc::new(Mutex::new(Received::default()));
    let sink = received.clone();
    let _sub = graph
        .on_surrogates("bench", move |m| {
            let now = unix_ns();
            let mut r = sink.lock().unwrap_or_else(|p| p.into_inner());
            r.latency_ms
                .push(now.saturating_sub(m.source_stamp_ns) as f64 / 1e6);
            r.fit_ms.push(m.fit_ns as f64 / 1e6);
        })
        .await?;
    let namespace = graph.namespace.clone();
    let session = graph.session.clone();
    let key = format!("shroud/{namespace}/cloud/bench");
    let publisher = topic_publisher(&session, key, TopicKind::Cloud)?;
    let writer = PayloadWriter::new(true, 4 * (points * 12 + 4096));
    // Frames are generated ahead so that the publisher's clock measures transport
    // and fitting only, not the simulator.
    let scene = MovingSpheres {
        points,
        ..MovingSpheres::default()
    };
    let frames: Vec<Vec<[f32; 3]>> = (0..20)
        .map(|i| scene.generate(i as f64 * 0.1))
        .collect::<Result<_, _>>()?;
    wait_until_fitting(&publisher, &writer, &frames[0], &received).await?;
    *received.lock().unwrap_or_else(|p| p.into_inner()) = Received::default();
    let period = Duration::from_secs_f64(1.0 / rate);
    let start = Instant::now();
    let mut published = 0u64;
    while start.elapsed().as_secs_f64() < seconds {
        let frame = &frames[published as usize % frames.len()];
        let msg =
            CloudView::new(unix_ns(), published, "bench", Default::default(), frame).aligned()?;
        publisher
            .put(writer.encode(&msg)?)
            .await
            .map_err(|e| anyhow::anyhow!("put: {e}"))?;
        published += 1;
        let next = start + period * published as u32;
        tokio::time::sleep_until(next.into()).await;
    }
    tokio::time::sleep(Duration::from_millis(500)).await;
    graph.stop("fit");
    let r = std::mem::take(&mut *received.lock().unwrap_or_else(|p| p.into_inner()));
    let _ = session.close().await;
    let mut lat = Percentiles::new(r.latency_ms.len().max(1));
    let mut fit_p = Percentiles::new(r.fit_ms.len().max(1));
    let mut over = Percentiles::new(r.fit_ms.len().max(1));
    for (l, f) in r.latency_ms.iter().zip(&r.fit_ms) {
        lat.push(*l);
        fit_p.push(*f);
        over.push(l - f);
    }
    Ok(Row {
        points,
        rate,
        published,
        received: r.latency_ms.len() as u64,
        latency: lat.summary(),
        fit_p50: fit_p.quantile(0.5).unwrap_or(f64::NAN),
        overhead_p50: over.quantile(0.5).unwrap_or(f64::NAN),
    })
}

/// Publishes a warm-up cloud every 100 ms until the fitter answers (it may
/// still be connecting), for at most 30 s.
async fn wait_until_fitting(
    publisher: &zenoh::pubsub::Publisher<'_>,
    writer: &PayloadWriter,
    frame: &[[f32; 3]],
    received: &Arc<Mutex<Received>>,
) -> Result<()> {
    let start = Instant::now();
    while received
        .lock()
        .unwrap_or_else(|p| p.into_inner())
        .latency_ms
        .len()
        < 3
    {
        anyhow::ensure!(
            start.elapsed() < Duration::from_secs(30),
            "the fit node never answered"
        );
        let msg =
            CloudView::new(unix_ns(), u64::MAX, "warmup", Default::default(), frame).aligned()?;
        publisher
            .put(writer.encode(&msg)?)
            .await
            .map_err(|e| anyhow::anyhow!("put: {e}"))?;
        tokio::time::sleep(Duration::from_millis(100)).await;
    }
    Ok(())
}

fn print_table(rows: &[Row], seconds: f64) {
    println!("End-to-end latency, cloud published -> surrogate received ({seconds} s per row, separate fit process, zenoh peer on loopback, shared memory)\n");
    println!("| points | rate | published | received | dropped | latency p50 | latency p99 | fit p50 | p50 latency - fit |");
    println!("|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for r in rows {
        let (p50, p99) = r
            .latency
            .map(|l| (l.p50, l.p99))
            .unwrap_or((f64::NAN, f64::NAN));
        let dropped = r.published.saturating_sub(r.received);
        println!(
            "| {}K | {} Hz | {} | {} | {} ({:.1}%) | {:.2} ms | {:.2} ms | {:.2} ms | {:.2} ms |",
            r.points / 1000,
            r.rate,
            r.published,
            r.received,
            dropped,
            100.0 * dropped as f64 / r.published.max(1) as f64,
            p50,
            p99,
            r.fit_p50,
            r.overhead_p50
        );
    }
}
