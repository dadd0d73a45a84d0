//! `shroud-bench soak`: the demo graph (scanner, fit, guard, arm, dashboard)
//! at `--points`/`--rate` for `--minutes`, reported per window: every node's
//! resident memory and CPU share, the fit latency (p50, p99 of the surrogates'
//! `pipeline_ns`), drops by cause, and shared-memory use; then each node's
//! memory slope and the accounting of clouds between the scanner and the fit
//! node. With `--check` it fails (non-zero exit) when a cloud is unaccounted
//! for or a node's memory grew between the first and the last window beyond
//! `--max-growth-mb`.

use super::graph::{rss_bytes, tree_cpu_seconds, BenchGraph};
use super::BenchArgs;
use anyhow::{bail, Result};
use shroud_graph::metrics::Percentiles;
use shroud_msg::NodeStatusMessage;
use std::collections::BTreeMap;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

const NODES: [&str; 5] = ["scanner", "fit", "guard", "arm", "dashboard"];
/// Seconds the graph runs before the first window (start-up allocations).
const SETTLE: Duration = Duration::from_secs(5);
/// How long the fit node gets to take the clouds still in flight when the
/// scanner stops.
const DRAIN: Duration = Duration::from_secs(2);

/// What the bench hears: latencies of the current window, the latest status
/// of every node.
#[derive(Default)]
struct Heard {
    latency_ms: Vec<f64>,
    status: BTreeMap<String, NodeStatusMessage>,
}

/// One window's line.
struct Window {
    end_s: f64,
    rss_mb: BTreeMap<&'static str, f64>,
    cpu_pct: BTreeMap<&'static str, f64>,
    latency: (f64, f64),
    surrogates: usize,
    drops: Drops,
    shm_mb: f64,
}

/// Drops by cause, cumulative.
#[derive(Debug, Clone, Copy, Default)]
struct Drops {
    /// Ticks the scanner could not produce in time.
    missed_ticks: u64,
    /// Clouds the fit node's queue dropped (a newer one waited).
    fit_backlog: u64,
    /// Clouds missing from the fit node's sequence beyond its backlog drops.
    lost_on_the_way: u64,
    /// Samples the dashboard's inbox replaced before drawing them.
    dashboard_superseded: u64,
}

pub fn run(args: &BenchArgs) -> Result<()> {
    anyhow::ensure!(
        args.minutes.is_finite() && args.minutes > 0.0 && args.window > 0.0,
        "--minutes and --window must be positive"
    );
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(1)
        .enable_all()
        .build()?;
    runtime.block_on(soak(args))
}

async fn soak(args: &BenchArgs) -> Result<()> {
    let mut graph = BenchGraph::start("soak").await?;
    let heard = Arc::new(Mutex::new(Heard::default()));
    let _subscribers = listen(&graph, &heard).await?;
    let (points, rate) = (args.points.to_string(), args.rate.to_string());
    let arm = "launch/arms/demo_arm.toml";
    anyhow::ensure!(
        std::path::Path::new(arm).exists(),
        "run from the repository root ({arm} is read)"
    );
    graph.spawn(
        "scanner",
        "scanner",
        &["--points", &points, "--rate", &rate, "--stream", "soak"],
        None,
    )?;
    graph.spawn(
        "fit",
        "fit",
        &["--input", "soak", "--grid", "20x20", "--side", "sandwich"],
        None,
    )?;
    graph.spawn(
        "guard",
        "guard",
        &[
            "--arm-file",
            arm,
            "--surrogate",
            "soak",
            "--unobserved",
            "ignore",
            "--max-age",
            "1",
        ],
        None,
    )?;
    graph.spawn("arm", "arm", &["--arm-file", arm, "--rate", "50"], None)?;
    graph.spawn(
        "dashboard",
        "dashboard",
        &["--listen", "127.0.0.1:0", "--arm-file", arm],
        None,
    )?;
    tokio::time::sleep(SETTLE).await;
    let windows = run_windows(&graph, &heard, args).await?;
    graph.stop("scanner");
    tokio::time::sleep(DRAIN).await;
    for node in NODES.iter().skip(1) {
        graph.stop(node);
    }
    // The final statuses (published as each node stops) have landed.
    tokio::time::sleep(Duration::from_millis(500)).await;
    let status = heard
        .lock()
        .unwrap_or_else(|p| p.into_inner())
        .status
        .clone();
    print_windows(&windows, args);
    let growth = print_memory(&windows);
    let accounted = print_accounting(&status);
    if args.check {
        let worst = growth.iter().map(|(_, g)| *g).fold(0.0, f64::max);
        if let Some((node, g)) = growth.iter().find(|(_, g)| *g > args.max_growth_mb) {
            bail!("{node}'s memory grew by {g:.1} MB between the first and the last window (bound {} MB)", args.max_growth_mb);
        }
        accounted?;
        println!("\ncheck passed: every cloud accounted for, largest memory growth {worst:.1} MB (bound {} MB)", args.max_growth_mb);
    }
    Ok(())
}

async fn listen(
    graph: &BenchGraph,
    heard: &Arc<Mutex<Heard>>,
) -> Result<Vec<zenoh::pubsub::Subscriber<()>>> {
    let sink = heard.clone();
    let surrogates = graph
        .on_surrogates("soak", move |m| {
            let mut h = sink.lock().unwrap_or_else(|p| p.into_inner());
            h.latency_ms.push(m.pipeline_ns as f64 / 1e6);
        })
        .await?;
    let sink = heard.clone();
    let status = graph
        .on_status("*", move |s| {
            let mut h = sink.lock().unwrap_or_else(|p| p.into_inner());
            h.status.insert(s.node.clone(), s);
        })
        .await?;
    Ok(vec![surrogates, status])
}

async fn run_windows(
    graph: &BenchGraph,
    heard: &Arc<Mutex<Heard>>,
    args: &BenchArgs,
) -> Result<Vec<Window>> {
    let pids: Vec<(&'static str, u32)> = NODES
        .iter()
        .filter_map(|&n| graph.pid(n).map(|p| (n, p)))
        .collect();
    let total = Duration::from_secs_f64(args.minutes * 60.0);
    let step = Duration::from_secs_f64(args.window);
    let start = Instant::now();
    heard
        .lock()
        .unwrap_or_else(|p| p.into_inner())
        .latency_ms
        .clear();
    let mut cpu_before: BTreeMap<&str, f64> = pids
        .iter()
        .map(|&(n, p)| (n, tree_cpu_seconds(p)))
        .collect();
    let mut windows = Vec::new();
    while start.elapsed() < total {
        let left = total.saturating_sub(start.elapsed());
        tokio::time::sleep(step.min(left)).await;
        let elapsed = start.elapsed().as_secs_f64();
        let span = elapsed - windows.last().map_or(0.0, |w: &Window| w.end_s);
        let mut rss_mb = BTreeMap::new();
        let mut cpu_pct = BTreeMap::new();
        for &(name, pid) in &pids {
            let Some(rss) = rss_bytes(pid) else {
                bail!("node {name} (pid {pid}) is gone during the soak");
            };
            rss_mb.insert(name, rss as f64 / 1e6);
            let cpu = tree_cpu_seconds(pid);
            cpu_pct.insert(name, 100.0 * (cpu - cpu_before[name]) / span.max(1e-9));
            cpu_before.insert(name, cpu);
        }
        let mut h = heard.lock().unwrap_or_else(|p| p.into_inner());
        let latencies = std::mem::take(&mut h.latency_ms);
        windows.push(Window {
            end_s: elapsed,
            rss_mb,
            cpu_pct,
            latency: (quantile(&latencies, 0.5), quantile(&latencies, 0.99)),
            surrogates: latencies.len(),
            drops: drops(&h.status),
            shm_mb: shm_used_bytes() as f64 / 1e6,
        });
        eprintln!("soak: {elapsed:.0} s");
    }
    Ok(windows)
}

fn quantile(values: &[f64], q: f64) -> f64 {
    let mut p = Percentiles::new(values.len().max(1));
    values.iter().for_each(|&v| p.push(v));
    p.quantile(q).unwrap_or(f64::NAN)
}

fn counter(status: &BTreeMap<String, NodeStatusMessage>, node: &str, name: &str) -> u64 {
    status.get(node).map_or(0, |s| s.counter(name))
}

fn drops(status: &BTreeMap<String, NodeStatusMessage>) -> Drops {
    let backlog = counter(status, "fit", "dropped_backlog");
    Drops {
        missed_ticks: counter(status, "scanner", "missed_ticks"),
        fit_backlog: backlog,
        lost_on_the_way: counter(status, "fit", "sequence_gaps").saturating_sub(backlog),
        dashboard_superseded: counter(status, "dashboard", "samples_superseded"),
    }
}

/// Bytes in use on `/dev/shm` (zenoh's shared-memory segments live there).
fn shm_used_bytes() -> u64 {
    let Ok(path) = std::ffi::CString::new("/dev/shm") else {
        return 0;
    };
    // SAFETY: statvfs fills the struct we own from a valid C string.
    let mut stat: libc::statvfs = unsafe { std::mem::zeroed() };
    if unsafe { libc::statvfs(path.as_ptr(), &mut stat) } != 0 {
        return 0;
    }
    (stat.f_blocks - stat.f_bfree) * stat.f_frsize
}

fn print_windows(windows: &[Window], args: &BenchArgs) {
    println!(
        "Soak: scanner, fit, guard, arm, dashboard at {}K points and {} Hz for {} min, one line per {} s\n",
        args.points / 1000,
        args.rate,
        args.minutes,
        args.window
    );
    let names = NODES.join(" / ");
    println!("| t (s) | RSS MB ({names}) | CPU % ({names}) | surrogates | latency p50 | p99 | drops: missed ticks, fit backlog, lost on the way, dashboard superseded | /dev/shm MB |");
    println!("|---:|---|---|---:|---:|---:|---|---:|");
    for w in windows {
        let join = |m: &BTreeMap<&str, f64>, digits: usize| {
            NODES
                .iter()
                .map(|n| format!("{:.*}", digits, m.get(n).copied().unwrap_or(f64::NAN)))
                .collect::<Vec<_>>()
                .join(" / ")
        };
        let d = w.drops;
        println!(
            "| {:.0} | {} | {} | {} | {:.2} ms | {:.2} ms | {}, {}, {}, {} | {:.1} |",
            w.end_s,
            join(&w.rss_mb, 1),
            join(&w.cpu_pct, 0),
            w.surrogates,
            w.latency.0,
            w.latency.1,
            d.missed_ticks,
            d.fit_backlog,
            d.lost_on_the_way,
            d.dashboard_superseded,
            w.shm_mb
        );
    }
}

/// Prints each node's memory slope (least squares over the windows, MB per
/// minute) and growth (last window minus first); returns the growths.
fn print_memory(windows: &[Window]) -> Vec<(&'static str, f64)> {
    println!("\n| node | RSS first window | RSS last window | growth | slope |");
    println!("|---|---:|---:|---:|---:|");
    let mut growth = Vec::new();
    for node in NODES {
        let series: Vec<(f64, f64)> = windows
            .iter()
            .filter_map(|w| Some((w.end_s / 60.0, *w.rss_mb.get(node)?)))
            .collect();
        let (Some(first), Some(last)) = (series.first(), series.last()) else {
            continue;
        };
        let g = last.1 - first.1;
        println!(
            "| {node} | {:.1} MB | {:.1} MB | {g:+.1} MB | {:+.2} MB/min |",
            first.1,
            last.1,
            slope(&series)
        );
        growth.push((node, g));
    }
    growth
}

fn slope(series: &[(f64, f64)]) -> f64 {
    let n = series.len() as f64;
    if series.len() < 2 {
        return 0.0;
    }
    let (mx, my) = (
        series.iter().map(|p| p.0).sum::<f64>() / n,
        series.iter().map(|p| p.1).sum::<f64>() / n,
    );
    let sxy: f64 = series.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = series.iter().map(|p| (p.0 - mx).powi(2)).sum();
    if sxx > 0.0 {
        sxy / sxx
    } else {
        0.0
    }
}

/// The clouds between the scanner and the fit node, from their final
/// statuses: every published cloud was taken, dropped by the backlog policy,
/// or is missing from the sequence the fit node saw; the two ways of counting
/// the missing ones (published minus seen, and the sequence gaps) must agree
/// up to the clouds after the last one the fit node saw.
fn print_accounting(status: &BTreeMap<String, NodeStatusMessage>) -> Result<()> {
    let published = counter(status, "scanner", "published");
    let received = counter(status, "fit", "received");
    let backlog = counter(status, "fit", "dropped_backlog");
    let malformed = counter(status, "fit", "dropped_malformed");
    let gaps = counter(status, "fit", "sequence_gaps");
    let lost_gaps = gaps.saturating_sub(backlog);
    let unseen = published.saturating_sub(received + backlog);
    println!("\nclouds: scanner published {published}; fit node received {received}, dropped by its backlog {backlog}, malformed {malformed}, sequence gaps {gaps} (so {lost_gaps} lost on the way); published - received - backlog = {unseen}");
    // Gaps count the clouds missing between two seen ones; `unseen` also
    // counts those after the last seen one, of which at most the queue can
    // still be in flight when the scanner stopped (one: the fit node's queue).
    let tail = unseen.saturating_sub(lost_gaps);
    if published == 0 || received == 0 {
        bail!("no clouds went through the graph (published {published}, received {received})");
    }
    if received + backlog > published || lost_gaps > unseen || tail > 1 {
        bail!("clouds unaccounted for: published {published}, received {received}, backlog {backlog}, lost on the way by gaps {lost_gaps}, unseen {unseen}");
    }
    Ok(())
}
