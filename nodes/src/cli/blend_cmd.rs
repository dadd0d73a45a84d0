//! `shroud blend-cmd`: drives a `blend` node from the command line, one command
//! at a time or a whole straight drag at a fixed rate (what a dashboard's
//! drag-and-drop sends).

use crate::parse;
use crate::transport::{topic_publisher, unix_ns, ZenohArgs};
use anyhow::Result;
use clap::{Args, Subcommand};
use glam::DVec3;
use shroud_msg::{BlendCommandMessage, TopicKind};
use shroud_shapes::blend::{BlendCommand, LocalAdjust};
use std::time::Duration;

#[derive(Debug, Args)]
pub struct BlendCmdArgs {
    #[command(flatten)]
    pub zenoh: ZenohArgs,
    /// The blend node's command stream (`shroud/<ns>/blend/<stream>`).
    #[arg(long, default_value = "blend", global = true)]
    pub stream: String,
    #[command(subcommand)]
    pub action: Action,
}

#[derive(Debug, Subcommand)]
pub enum Action {
    /// Drop the child on the parent's surface near a point.
    Drop {
        /// x,y,z near the parent's surface.
        #[arg(long, allow_hyphen_values = true)]
        at: String,
        /// Surface normal x,y,z to use instead of the estimated one.
        #[arg(long, allow_hyphen_values = true)]
        normal: Option<String>,
        /// Which of the blend node's parts to paste (its `blend.parts`
        /// status label lists them); default: the one it holds.
        #[arg(long)]
        part: Option<String>,
    },
    /// Adjust the dropped child: slide along the normal, spin, tilt.
    Adjust {
        #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
        lift: f64,
        /// Degrees about the normal.
        #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
        spin: f64,
        /// Degrees about the two tangent axes: a,b.
        #[arg(long, default_value = "0,0", allow_hyphen_values = true)]
        tilt: String,
    },
    /// Take the child away.
    Clear,
    /// Make the current blend the parent of the next drop.
    Commit,
    /// Drag the child along a straight line: one drop per step at --rate.
    Drag {
        #[arg(long, allow_hyphen_values = true)]
        from: String,
        #[arg(long, allow_hyphen_values = true)]
        to: String,
        #[arg(long, default_value_t = 20)]
        steps: u32,
        /// Drops per second.
        #[arg(long, default_value_t = 10.0)]
        rate: f64,
        /// Which part to drag (as for drop).
        #[arg(long)]
        part: Option<String>,
    },
}

pub fn run(args: BlendCmdArgs) -> Result<()> {
    let commands = commands(&args.action)?;
    let part = match &args.action {
        Action::Drop { part, .. } | Action::Drag { part, .. } => part.clone(),
        _ => None,
    };
    let period = match &args.action {
        Action::Drag { rate, .. } => {
            anyhow::ensure!(
                rate.is_finite() && *rate > 0.0 && *rate <= 1000.0,
                "--rate must be in (0, 1000]"
            );
            Duration::from_secs_f64(1.0 / rate)
        }
        _ => Duration::ZERO,
    };
    let key = args
        .zenoh
        .topics()?
        .key(TopicKind::Blend, &args.stream)?
        .to_string();
    tokio::runtime::Builder::new_multi_thread()
        .worker_threads(1)
        .enable_all()
        .build()?
        .block_on(async {
            let session = args.zenoh.open().await?;
            // A command must arrive: the blend topic blocks rather than drops.
            let publisher = topic_publisher(&session, key.clone(), TopicKind::Blend)?;
            wait_for_blender(&publisher, &key).await;
            for (sequence, command) in commands.iter().enumerate() {
                let mut msg = BlendCommandMessage::new(unix_ns(), sequence as u64, command);
                if matches!(command, BlendCommand::Drop { .. }) {
                    msg.part = part.clone();
                }
                // Refuses NaN, infinities and bad part names before anything is sent.
                msg.command()?;
                msg.check_part()?;
                publisher
                    .put(msg.to_bytes()?)
                    .await
                    .map_err(|e| anyhow::anyhow!("publish {key}: {e}"))?;
                tokio::time::sleep(period).await;
            }
            // Let the last command leave before the session closes.
            tokio::time::sleep(Duration::from_millis(200)).await;
            let _ = session.close().await;
            println!("sent {} command(s) to {key}", commands.len());
            Ok(())
        })
}

/// Gives zenoh up to 2 s to find a subscriber of `key` (a fresh session may
/// not know its peers yet, and a command published before would be lost).
async fn wait_for_blender(publisher: &zenoh::pubsub::Publisher<'_>, key: &str) {
    let deadline = tokio::time::Instant::now() + Duration::from_secs(2);
    while tokio::time::Instant::now() < deadline {
        if let Ok(status) = publisher.matching_status().await {
            if status.matching() {
                return;
            }
        }
        tokio::time::sleep(Duration::from_millis(50)).await;
    }
    tracing::warn!("no blend node subscribes to {key} yet; sending anyway");
}

fn commands(action: &Action) -> Result<Vec<BlendCommand>> {
    Ok(match action {
        Action::Drop { at, normal, .. } => vec![BlendCommand::Drop {
            at: DVec3::from(parse::numbers::<3>(at, "at")?),
            normal: normal
                .as_deref()
                .map(|n| parse::numbers::<3>(n, "normal").map(DVec3::from))
                .transpose()?,
        }],
        Action::Adjust { lift, spin, tilt } => {
            let [a, b] = parse::numbers::<2>(tilt, "tilt")?;
            vec![BlendCommand::Adjust(LocalAdjust {
                lift: *lift,
                spin: spin.to_radians(),
                tilt: [a.to_radians(), b.to_radians()],
            })]
        }
        Action::Clear => vec![BlendCommand::Clear],
        Action::Commit => vec![BlendCommand::Commit],
        Action::Drag {
            from, to, steps, ..
        } => {
            let a = DVec3::from(parse::numbers::<3>(from, "from")?);
            let b = DVec3::from(parse::numbers::<3>(to, "to")?);
            anyhow::ensure!(*steps >= 1, "--steps must be at least 1");
            (0..=*steps)
                .map(|i| BlendCommand::Drop {
                    at: a.lerp(b, f64::from(i) / f64::from(*steps)),
                    normal: None,
                })
                .collect()
        }
    })
}
