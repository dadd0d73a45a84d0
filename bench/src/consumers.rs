//! `shroud-bench consumers`: what watching the graph costs it. A scanner and a
//! fit node run at `--points`/`--rate`; the fit latency (each surrogate's
//! `pipeline_ns`: the scanner's share, the fit node's wait, decode and fit) is
//! measured with no consumer, then with the dashboard node and 0, 1, 3 real
//! headless Chromium pages on it (`tests/browser/open_pages.mjs`, rendering on
//! this machine's cores), and with 1 and 3 WebSocket readers that take every
//! frame as a browser does but draw nothing (browsers on another machine,
//! the usual case: only the node's work stays on the robot), and with
//! the Foxglove bridge with 0 and 1 clients subscribed to every channel, and
//! with `shroud record` writing the clouds and surrogates to a temporary MCAP
//! file, raw only and with the Foxglove views (MB/s written, its drops), with each
//! consumer's CPU share, all in one run so that the ratios compare like with
//! like on a noisy machine.

use super::foxglove_clients::FoxgloveClients;
use super::graph::{tree_cpu_seconds, BenchGraph};
use super::BenchArgs;
use anyhow::{bail, Context, Result};
use shroud_graph::metrics::Percentiles;
use std::io::{BufRead, BufReader};
use std::process::{Child, Command, Stdio};
use std::sync::{Arc, Mutex};
use std::time::Duration;

/// Seconds a configuration runs before its measurement starts.
const SETTLE: Duration = Duration::from_secs(3);

/// What runs beside the scanner and the fit node.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Consumer {
    Nothing,
    /// The dashboard with headless Chromium pages on this machine.
    Dashboard {
        browsers: usize,
    },
    /// The dashboard with WebSocket readers (browsers elsewhere).
    DashboardReaders {
        readers: usize,
    },
    /// The Foxglove bridge with clients subscribed to every channel.
    Foxglove {
        clients: usize,
    },
    /// `shroud record` of the clouds and surrogates to a temporary file,
    /// with or without the Foxglove views.
    Recorder {
        foxglove: bool,
    },
}

impl Consumer {
    fn label(&self) -> String {
        match self {
            Self::Nothing => "none".into(),
            Self::Dashboard { browsers } => {
                format!("dashboard, {browsers} headless Chromium page(s) on this machine")
            }
            Self::DashboardReaders { readers } => {
                format!("dashboard, {readers} WebSocket reader(s) (browsers elsewhere)")
            }
            Self::Foxglove { clients } => {
                format!("foxglove bridge, {clients} client(s) subscribed to everything")
            }
            Self::Recorder { foxglove: true } => {
                "shroud record, cloud/* and surrogate/* (MCAP, zstd), with Foxglove views".into()
            }
            Self::Recorder { foxglove: false } => {
                "shroud record, cloud/* and surrogate/* (MCAP, zstd), raw only".into()
            }
        }
    }
}

/// One row of the table.
struct Row {
    consumer: Consumer,
    surrogates: usize,
    fit_p50: f64,
    latency_p50: f64,
    latency_p99: f64,
    dropped: u64,
    node_cpu: Option<f64>,
    browser_cpu: Option<f64>,
    /// What the consumer itself reports (the recorder's MB/s and drops).
    note: String,
}

/// What the bench hears from the graph.
#[derive(Default)]
struct Heard {
    latency_ms: Vec<f64>,
    fit_ms: Vec<f64>,
    dropped_backlog: u64,
    /// The recorder's drops, all causes.
    recorder_dropped: u64,
}

pub fn run(args: &BenchArgs) -> Result<()> {
    let browsers = parse_counts(&args.browsers)?;
    let seconds = if args.quick { 3.0 } else { args.seconds };
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(1)
        .enable_all()
        .build()?;
    let rows = runtime.block_on(measure_all(args, &browsers, seconds))?;
    print_table(&rows, args, seconds);
    Ok(())
}

fn parse_counts(text: &str) -> Result<Vec<usize>> {
    text.split(',')
        .filter(|s| !s.trim().is_empty())
        .map(|s| {
            let n: usize = s
                .trim()
                .parse()
                .with_context(|| format!("--browsers: {s:?} is not a count"))?;
            anyhow::ensure!(n <= 16, "--browsers: at most 16 pages at once");
            Ok(n)
        })
        .collect()
}

async fn measure_all(args: &BenchArgs, browsers: &[usize], seconds: f64) -> Result<Vec<Row>> {
    let mut graph = BenchGraph::start("consumers").await?;
    let heard = Arc::new(Mutex::new(Heard::default()));
    let _subscribers = listen(&graph, &heard).await?;
    let (points, rate) = (args.points.to_string(), args.rate.to_string());
    graph.spawn(
        "scanner",
        "scanner",
        &["--points", &points, "--rate", &rate, "--stream", "bench"],
        None,
    )?;
    graph.spawn(
        "fit",
        "fit",
        &["--input", "bench", "--grid", "20x20", "--side", "sandwich"],
        None,
    )?;
    let mut rows = vec![measure(&heard, Consumer::Nothing, seconds, None).await?];
    let port = free_port()?;
    let listen = format!("127.0.0.1:{port}");
    let dashboard = graph.spawn("dashboard", "dashboard", &["--listen", &listen], None)?;
    for &count in browsers {
        let pages = (count > 0)
            .then(|| Pages::open(&format!("http://{listen}/"), count))
            .transpose()?;
        let consumer = Consumer::Dashboard { browsers: count };
        let pids = (dashboard, pages.as_ref().map(Pages::pid));
        rows.push(measure(&heard, consumer, seconds, Some(pids)).await?);
        drop(pages);
    }
    for &count in browsers.iter().filter(|&&n| n > 0) {
        let readers = Readers::connect(&format!("ws://{listen}/ws"), count).await?;
        let consumer = Consumer::DashboardReaders { readers: count };
        rows.push(measure(&heard, consumer, seconds, Some((dashboard, None))).await?);
        let frames = readers.stop().await;
        eprintln!("  {count} reader(s) took {frames} frames");
    }
    graph.stop("dashboard");
    let port = free_port()?;
    let listen = format!("127.0.0.1:{port}");
    let bridge = graph.spawn("foxglove", "foxglove", &["--listen", &listen], None)?;
    for clients in [0, 1] {
        let connected = FoxgloveClients::connect(&format!("ws://{listen}"), clients).await?;
        let consumer = Consumer::Foxglove { clients };
        rows.push(measure(&heard, consumer, seconds, Some((bridge, None))).await?);
        let frames = connected.stop().await;
        eprintln!("  {clients} Foxglove client(s) took {frames} frames");
    }
    graph.stop("foxglove");
    for foxglove in [false, true] {
        rows.push(measure_recorder(&mut graph, &heard, seconds, foxglove).await?);
    }
    rows.push(measure(&heard, Consumer::Nothing, seconds, None).await?);
    graph.stop_all();
    Ok(rows)
}

/// Surrogates (latency, fit time) and the fit node's backlog drops.
async fn listen(
    graph: &BenchGraph,
    heard: &Arc<Mutex<Heard>>,
) -> Result<Vec<zenoh::pubsub::Subscriber<()>>> {
    let sink = heard.clone();
    let surrogates = graph
        .on_surrogates("bench", move |m| {
            let mut h = sink.lock().unwrap_or_else(|p| p.into_inner());
            h.latency_ms.push(m.pipeline_ns as f64 / 1e6);
            h.fit_ms.push(m.fit_ns as f64 / 1e6);
        })
        .await?;
    let sink = heard.clone();
    let status = graph
        .on_status("fit", move |s| {
            sink.lock()
                .unwrap_or_else(|p| p.into_inner())
                .dropped_backlog = s.counter("dropped_backlog");
        })
        .await?;
    let sink = heard.clone();
    let recorder = graph
        .on_status("record", move |s| {
            let dropped: u64 = shroud_record::DropCause::ALL
                .iter()
                .map(|c| s.counter(c.counter()))
                .sum();
            sink.lock()
                .unwrap_or_else(|p| p.into_inner())
                .recorder_dropped = dropped;
        })
        .await?;
    Ok(vec![surrogates, status, recorder])
}

/// The recorder's row: `shroud record` to a temporary file while the graph
/// runs; its MB/s from the file's growth over the row (settling included).
async fn measure_recorder(
    graph: &mut BenchGraph,
    heard: &Arc<Mutex<Heard>>,
    seconds: f64,
    foxglove: bool,
) -> Result<Row> {
    let file = std::env::temp_dir().join(format!("shroud-bench-{}.mcap", std::process::id()));
    let path = file.to_string_lossy().into_owned();
    let topics = "cloud/*,surrogate/*";
    let views = foxglove.to_string();
    let args = [
        "-o",
        path.as_str(),
        "--topics",
        topics,
        "--overwrite",
        "--foxglove",
        views.as_str(),
    ];
    let pid = graph.spawn("record", "record", &args, None)?;
    let started = std::time::Instant::now();
    let consumer = Consumer::Recorder { foxglove };
    let mut row = measure(heard, consumer, seconds, Some((pid, None))).await?;
    let bytes = std::fs::metadata(&file).map(|m| m.len()).unwrap_or(0);
    let mb_per_s = bytes as f64 / 1e6 / started.elapsed().as_secs_f64();
    let dropped = heard
        .lock()
        .unwrap_or_else(|p| p.into_inner())
        .recorder_dropped;
    row.note = format!(": {mb_per_s:.1} MB/s written, {dropped} dropped");
    graph.stop("record");
    let _ = std::fs::remove_file(&file);
    Ok(row)
}

/// Runs one configuration: settles, then measures for `seconds`.
async fn measure(
    heard: &Arc<Mutex<Heard>>,
    consumer: Consumer,
    seconds: f64,
    pids: Option<(u32, Option<u32>)>,
) -> Result<Row> {
    tokio::time::sleep(SETTLE).await;
    let dropped_before = {
        let mut h = heard.lock().unwrap_or_else(|p| p.into_inner());
        h.latency_ms.clear();
        h.fit_ms.clear();
        h.dropped_backlog
    };
    let cpu = |pid: u32| tree_cpu_seconds(pid);
    let before = pids.map(|(node, pages)| (cpu(node), pages.map(cpu)));
    tokio::time::sleep(Duration::from_secs_f64(seconds)).await;
    let after = pids.map(|(node, pages)| (cpu(node), pages.map(cpu)));
    let share = |b: f64, a: f64| 100.0 * (a - b) / seconds;
    let (node_cpu, browser_cpu) = match (before, after) {
        (Some((nb, pb)), Some((na, pa))) => {
            (Some(share(nb, na)), pb.zip(pa).map(|(b, a)| share(b, a)))
        }
        _ => (None, None),
    };
    let h = heard.lock().unwrap_or_else(|p| p.into_inner());
    if h.latency_ms.is_empty() {
        bail!(
            "no surrogate arrived while measuring {}: is the fit node running?",
            consumer.label()
        );
    }
    let quantile = |values: &[f64], q: f64| {
        let mut p = Percentiles::new(values.len());
        values.iter().for_each(|&v| p.push(v));
        p.quantile(q).unwrap_or(f64::NAN)
    };
    eprintln!("measured {}", consumer.label());
    Ok(Row {
        consumer,
        surrogates: h.latency_ms.len(),
        fit_p50: quantile(&h.fit_ms, 0.5),
        latency_p50: quantile(&h.latency_ms, 0.5),
        latency_p99: quantile(&h.latency_ms, 0.99),
        dropped: h.dropped_backlog.saturating_sub(dropped_before),
        node_cpu,
        browser_cpu,
        note: String::new(),
    })
}

fn free_port() -> Result<u16> {
    let listener = std::net::TcpListener::bind("127.0.0.1:0")?;
    Ok(listener.local_addr()?.port())
}

/// Headless Chromium pages on the dashboard, open until dropped.
struct Pages(Child);

impl Pages {
    fn open(url: &str, count: usize) -> Result<Self> {
        let script = "tests/browser/open_pages.mjs";
        anyhow::ensure!(
            std::path::Path::new("tests/browser/node_modules/playwright-core").exists(),
            "browsers need playwright-core and Chromium: run from the repository root after \
             `apt-get install chromium && npm ci --prefix tests/browser` (or --browsers 0)"
        );
        let mut child = Command::new("node")
            .args([script, "--url", url, "--count", &count.to_string()])
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::inherit())
            .spawn()
            .context("cannot run node (Node.js) for the browsers")?;
        let stdout = child.stdout.take().context("no stdout")?;
        let mut line = String::new();
        BufReader::new(stdout).read_line(&mut line)?;
        anyhow::ensure!(
            line.trim() == format!("open {count}"),
            "the browsers did not open: {line:?}"
        );
        Ok(Self(child))
    }

    fn pid(&self) -> u32 {
        self.0.id()
    }
}

impl Drop for Pages {
    fn drop(&mut self) {
        drop(self.0.stdin.take()); // end of input: the script closes the browser
        let _ = self.0.wait();
    }
}

/// WebSocket readers on the dashboard: each takes every frame and checks its
/// layout (as a browser's decoder does) and draws nothing.
struct Readers {
    tasks: Vec<tokio::task::JoinHandle<u64>>,
    stop: Arc<std::sync::atomic::AtomicBool>,
}

impl Readers {
    async fn connect(url: &str, count: usize) -> Result<Self> {
        use futures_util::StreamExt;
        let stop = Arc::new(std::sync::atomic::AtomicBool::new(false));
        let mut tasks = Vec::new();
        for _ in 0..count {
            let (mut socket, _) = tokio_tungstenite::connect_async(url)
                .await
                .with_context(|| format!("cannot connect to {url}"))?;
            let stop = stop.clone();
            tasks.push(tokio::spawn(async move {
                let mut frames = 0u64;
                while !stop.load(std::sync::atomic::Ordering::Relaxed) {
                    let next =
                        tokio::time::timeout(Duration::from_millis(200), socket.next()).await;
                    match next {
                        Ok(Some(Ok(tokio_tungstenite::tungstenite::Message::Binary(bytes)))) => {
                            if shroud_viewers::dashboard::DecodedFrame::decode(&bytes).is_ok() {
                                frames += 1;
                            }
                        }
                        Ok(Some(Ok(_))) | Err(_) => {}
                        Ok(Some(Err(_)) | None) => break,
                    }
                }
                frames
            }));
        }
        Ok(Self { tasks, stop })
    }

    /// Stops every reader; the frames they took.
    async fn stop(self) -> u64 {
        self.stop.store(true, std::sync::atomic::Ordering::Relaxed);
        let mut frames = 0;
        for task in self.tasks {
            frames += task.await.unwrap_or(0);
        }
        frames
    }
}

fn print_table(rows: &[Row], args: &BenchArgs, seconds: f64) {
    let none = rows
        .iter()
        .find(|r| r.consumer == Consumer::Nothing)
        .map(|r| r.latency_p50)
        .unwrap_or(f64::NAN);
    println!(
        "Fit latency with consumers: {}K points at {} Hz, {seconds} s per row, one run (p50 and p99 of the surrogates' pipeline_ns)\n",
        args.points / 1000,
        args.rate
    );
    println!("| consumer | surrogates | fit p50 | latency p50 | latency p99 | p50 / none | fit drops | consumer node CPU | browsers CPU |");
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|");
    let pct = |x: Option<f64>| x.map(|v| format!("{v:.1} %")).unwrap_or_else(|| "-".into());
    for r in rows {
        println!(
            "| {}{} | {} | {:.2} ms | {:.2} ms | {:.2} ms | {:.3} | {} | {} | {} |",
            r.consumer.label(),
            r.note,
            r.surrogates,
            r.fit_p50,
            r.latency_p50,
            r.latency_p99,
            r.latency_p50 / none,
            r.dropped,
            pct(r.node_cpu),
            pct(r.browser_cpu),
        );
    }
    println!("\nCPU shares are of one core over the row's seconds; `none` runs first and last to show the drift of the machine.");
}
