//! The supervisor: one task per node that starts it, waits for it, and restarts
//! it by policy; the graph stops on a signal, after `--duration`, when a
//! critical node is done, or when every node is done.

use super::child::{self, Wiring};
use super::monitor;
use super::output;
use super::plan::PlannedNode;
use super::roster::{self, Roster};
use crate::transport::{shutdown_signal, OnOff, ZenohArgs};
use anyhow::Result;
use shroud_graph::launch::{Backoff, LaunchFile, RestartDecision, LAUNCHER_NAME};
use std::time::{Duration, Instant};
use tokio::sync::watch;
use tokio::task::JoinSet;

/// How a node's supervision ended.
#[derive(Debug)]
struct Outcome {
    name: String,
    critical: bool,
    kind: OutcomeKind,
}

#[derive(Debug, PartialEq)]
enum OutcomeKind {
    /// Stopped by the launcher.
    Stopped,
    /// Exited and the policy said not to restart.
    Finished { success: bool },
    /// Failed more often in a row than allowed.
    GaveUp,
}

pub async fn run_graph(
    file: LaunchFile,
    host: Option<String>,
    planned: Vec<PlannedNode>,
    log: String,
    duration: Option<Duration>,
) -> Result<()> {
    let z = &file.zenoh;
    let mut hub = ZenohArgs {
        namespace: file.namespace.clone(),
        mode: z.mode.clone(),
        connect: z.connect.clone(),
        listen: z.listen.clone(),
        multicast: Some(if z.multicast { OnOff::On } else { OnOff::Off }),
        shm: if z.shm { OnOff::On } else { OnOff::Off },
        zenoh_config: None,
        tls_root_ca: None,
        tls_certificate: None,
        tls_private_key: None,
        access_control: None,
    };
    if let Some(host) = &host {
        hub.serve_host(&file, host)?;
    }
    let session = hub.open().await?;
    let locators: Vec<String> = (session.info().locators().await.iter())
        .map(|l| l.to_string())
        .collect();
    let connect = node_endpoints(&file, host.as_deref(), locators);
    anyhow::ensure!(
        !connect.is_empty(),
        "the launcher's router has no loopback endpoint for its nodes (zenoh.listen: {:?})",
        file.zenoh.listen
    );
    output::out(format!(
        "[launch] namespace {:?}{}, nodes connect to {}",
        file.namespace,
        host.as_deref()
            .map(|h| format!(", host {h} (a router)"))
            .unwrap_or_default(),
        connect.join(", ")
    ));
    let wiring = Wiring {
        namespace: file.namespace.clone(),
        // A host's nodes are its router's clients: they link to nothing
        // else, so every sample from another host passes that router's
        // access control.
        mode: if host.is_some() {
            "client".into()
        } else {
            z.mode.clone()
        },
        connect,
        // A host's nodes find their router by its endpoint, never by scouting.
        multicast: z.multicast && host.is_none(),
        shm: z.shm,
        log,
    };
    let grace = Duration::from_secs_f64(file.shutdown_grace_s);
    let (stop_tx, stop_rx) = watch::channel(false);
    let roster = Roster::named(&launcher_name(host.as_deref()));
    let mut nodes = JoinSet::new();
    for node in planned {
        nodes.spawn(supervise(
            node,
            wiring.clone(),
            stop_rx.clone(),
            grace,
            roster.clone(),
        ));
    }
    let roster_status = match hub.topics() {
        Ok(topics) => Some(tokio::spawn(roster::publish(
            session.clone(),
            topics,
            roster.clone(),
            Duration::from_secs(1),
        ))),
        Err(e) => {
            output::err(format!("[launch] no launcher status: {e:#}"));
            None
        }
    };
    let monitor = file.summary.enabled.then(|| {
        tokio::spawn(monitor::run(
            session.clone(),
            hub.topics(),
            file.summary.period_s,
            roster.clone(),
        ))
    });
    let deadline = async {
        match duration {
            Some(d) => tokio::time::sleep(d).await,
            None => std::future::pending().await,
        }
    };
    tokio::pin!(deadline);
    // One signal wait for the whole loop: a new one per turn would miss a
    // signal that lands while a turn handles a node's exit.
    let stop_signal = shutdown_signal();
    tokio::pin!(stop_signal);
    let mut failed = Vec::new();
    loop {
        tokio::select! {
            signal = &mut stop_signal => {
                output::out(format!("[launch] {signal}: stopping every node"));
                break;
            }
            _ = &mut deadline => {
                output::out("[launch] --duration reached: stopping every node");
                break;
            }
            joined = nodes.join_next() => {
                let Some(joined) = joined else {
                    output::out("[launch] every node has stopped");
                    break;
                };
                let outcome = joined?;
                if matches!(outcome.kind, OutcomeKind::GaveUp | OutcomeKind::Finished { success: false }) {
                    failed.push(outcome.name.clone());
                }
                if outcome.critical {
                    output::out(format!("[launch] critical node {} is done: stopping the graph", outcome.name));
                    break;
                }
            }
        }
    }
    let _ = stop_tx.send(true);
    while let Some(joined) = nodes.join_next().await {
        let outcome = joined?;
        if matches!(
            outcome.kind,
            OutcomeKind::GaveUp | OutcomeKind::Finished { success: false }
        ) {
            failed.push(outcome.name);
        }
    }
    if let Some(m) = monitor {
        m.abort();
    }
    if let Some(r) = roster_status {
        r.abort();
    }
    let _ = session.close().await;
    anyhow::ensure!(failed.is_empty(), "nodes failed: {}", failed.join(", "));
    output::out("[launch] all nodes stopped cleanly");
    Ok(())
}

/// Where the nodes connect: the launcher's own endpoints and the file's
/// `zenoh.connect`; on a host, only the launcher's loopback endpoints (the
/// host's router), never the other hosts.
fn node_endpoints(file: &LaunchFile, host: Option<&str>, locators: Vec<String>) -> Vec<String> {
    match host {
        None => locators
            .into_iter()
            .chain(file.zenoh.connect.iter().cloned())
            .collect(),
        Some(_) => (locators.into_iter())
            .filter(|l| l.starts_with("tcp/127.0.0.1:") || l.starts_with("tcp/[::1]:"))
            .collect(),
    }
}

/// The launcher's status name: `launcher`, or `launcher.<host>` so that
/// every host's launcher has its own.
fn launcher_name(host: Option<&str>) -> String {
    match host {
        None => LAUNCHER_NAME.to_owned(),
        Some(host) => format!("{LAUNCHER_NAME}.{host}"),
    }
}

/// Reports how a child ended; true if it succeeded.
fn exited(name: &str, status: std::io::Result<std::process::ExitStatus>) -> bool {
    match status {
        Ok(status) => {
            output::out(format!("[launch] {name} exited: {status}"));
            status.success()
        }
        Err(e) => {
            output::out(format!("[launch] {name} exited: {e}"));
            false
        }
    }
}

async fn supervise(
    node: PlannedNode,
    wiring: Wiring,
    mut stop: watch::Receiver<bool>,
    grace: Duration,
    roster: Roster,
) -> Outcome {
    let spec = &node.spec;
    let mut backoff = Backoff::new(spec);
    let outcome = |kind| Outcome {
        name: spec.name.clone(),
        critical: spec.critical,
        kind,
    };
    loop {
        if *stop.borrow() {
            return outcome(OutcomeKind::Stopped);
        }
        let started = Instant::now();
        let success = match child::spawn(&node, &wiring) {
            Ok(mut process) => {
                let pid = process.id().unwrap_or(0);
                output::out(format!("[launch] started {} (pid {pid})", spec.name));
                roster.started(&spec.name, pid);
                tokio::select! {
                    status = process.wait() => exited(&spec.name, status),
                    _ = stop.changed() => {
                        child::stop(&mut process, &spec.name, grace).await;
                        roster.set_state(&spec.name, "stopped");
                        return outcome(OutcomeKind::Stopped);
                    }
                }
            }
            Err(e) => {
                output::err(format!("[launch] {e:#}"));
                false
            }
        };
        match backoff.on_exit(success, started.elapsed()) {
            RestartDecision::RestartAfter(delay) => {
                roster.set_state(&spec.name, "restarting");
                output::out(format!(
                    "[launch] restarting {} in {:.2} s",
                    spec.name,
                    delay.as_secs_f64()
                ));
                tokio::select! {
                    _ = tokio::time::sleep(delay) => {}
                    _ = stop.changed() => return outcome(OutcomeKind::Stopped),
                }
            }
            RestartDecision::Stop => {
                roster.set_state(&spec.name, "finished");
                return outcome(OutcomeKind::Finished { success });
            }
            RestartDecision::GiveUp { failures } => {
                roster.set_state(&spec.name, "gave-up");
                output::err(format!(
                    "[launch] giving up on {} after {failures} failures in a row",
                    spec.name
                ));
                return outcome(OutcomeKind::GaveUp);
            }
        }
    }
}
