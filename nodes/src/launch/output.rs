//! The launcher's output: its own lines and its children's go through a
//! bounded queue to one writer thread, so a terminal or pipe that stops
//! reading (Ctrl-S, a stalled `| less`) never stalls supervision. Lines that do
//! not fit are dropped and counted; the count is written once output flows
//! again. Write errors (a reader gone) are ignored.

use std::io::Write;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::mpsc::{sync_channel, Sender, SyncSender, TrySendError};
use std::sync::OnceLock;
use std::time::Duration;

/// Lines in flight at most before new ones are dropped.
const QUEUE: usize = 4096;

enum Item {
    Line {
        err: bool,
        text: String,
    },
    /// Answered once every line queued before it is written.
    Flush(Sender<()>),
}

static QUEUE_TX: OnceLock<SyncSender<Item>> = OnceLock::new();
static DROPPED: AtomicU64 = AtomicU64::new(0);

fn queue() -> &'static SyncSender<Item> {
    QUEUE_TX.get_or_init(|| {
        let (tx, rx) = sync_channel::<Item>(QUEUE);
        let writer = move || {
            let mut reported = 0;
            for item in rx {
                match item {
                    Item::Line { err, text } => {
                        let dropped = DROPPED.load(Ordering::Relaxed);
                        if dropped > reported {
                            let note = format!(
                                "[launch] {} lines dropped: output too slow",
                                dropped - reported
                            );
                            let _ = writeln!(std::io::stderr(), "{note}");
                            reported = dropped;
                        }
                        let _ = if err {
                            writeln!(std::io::stderr(), "{text}")
                        } else {
                            writeln!(std::io::stdout(), "{text}")
                        };
                    }
                    Item::Flush(done) => {
                        let _ = std::io::stdout().flush();
                        let _ = done.send(());
                    }
                }
            }
        };
        if let Err(e) = std::thread::Builder::new()
            .name("launch-output".into())
            .spawn(writer)
        {
            eprintln!("[launch] output thread: {e}");
        }
        tx
    })
}

fn send(err: bool, text: String) {
    match queue().try_send(Item::Line { err, text }) {
        Ok(()) => {}
        Err(TrySendError::Full(_) | TrySendError::Disconnected(_)) => {
            DROPPED.fetch_add(1, Ordering::Relaxed);
        }
    }
}

/// A line for stdout.
pub fn out(text: impl Into<String>) {
    send(false, text.into());
}

/// A line for stderr.
pub fn err(text: impl Into<String>) {
    send(true, text.into());
}

/// Waits (at most `timeout`) until every line queued so far is written: before
/// the launcher exits.
pub fn flush(timeout: Duration) {
    let (done, wait) = std::sync::mpsc::channel();
    // Blocking here is fine: the graph is down, only the output is left.
    if queue().send(Item::Flush(done)).is_ok() {
        let _ = wait.recv_timeout(timeout);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_are_queued_and_flushed_without_blocking_the_caller() {
        for i in 0..100 {
            out(format!("line {i}"));
        }
        err("an error line");
        flush(Duration::from_secs(5));
        assert_eq!(DROPPED.load(Ordering::Relaxed), 0);
    }
}
