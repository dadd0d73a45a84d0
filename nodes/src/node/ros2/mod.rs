//! `shroud node ros2`: shroud as a node of a ROS 2 system over rmw_zenoh,
//! with no ROS installation (docs/ros2.md). Reads a `PointCloud2` topic
//! into a cloud stream (`--cloud`) and a `JointState` topic into an arm's
//! joint states (`--arm`), and sends the arm's verdicts, its shapes
//! coloured by clearance, the surrogates (`--surrogate`) and clouds
//! (`--publish-cloud`) to ROS, under `--topic-prefix`.

mod inbound;
mod outbound;
mod ros_graph;

use crate::args::RosCloudArgs;
use crate::arm_file::{joint_names, read_arm_file};
use crate::node::viewer::Inbox;
use crate::runtime::{run_node, NodeCommon, NodeContext};
use crate::to_foxglove::SURFACE_PER_CELL;
use anyhow::Result;
use clap::Args;
use inbound::{clouds_in, joints_in, CloudInput, JointsInput};
use outbound::{MountTransform, StreamOutputs, VerdictOutput};
use ros_graph::{latched, reliable, RosIdentity, RosNode, RosTopic};
use shroud_guard::ArmFile;
use shroud_msg::{CollisionMessage, TopicKind};
use shroud_ros2::QosProfile;
use shroud_ros2::{DiagnosticStatus, Float64, JointState, MarkerArray, PointCloud2, TFMessage};
use shroud_ros2_bridge::{CloudMount, JointMatcher};
use shroud_viewers::scene::RecentJoints;
use std::collections::BTreeMap;
use std::path::PathBuf;
use std::sync::{Arc, Mutex};
use zenoh::qos::Priority;

/// Joint states kept to find the one a verdict answered: a quarter of a
/// second of a 1 kHz controller, far more than a guard's decision takes.
const RECENT_JOINTS: usize = 256;

#[derive(Debug, Clone, Args)]
pub struct Ros2Args {
    #[command(flatten)]
    pub common: NodeCommon,
    /// The ROS 2 domain id (`ROS_DOMAIN_ID`): the first segment of every key.
    #[arg(long, default_value_t = 0)]
    pub domain_id: u32,
    /// This node's name in the ROS graph (`ros2 node list`).
    #[arg(long, default_value = "shroud_bridge")]
    pub node_name: String,
    /// This node's ROS namespace.
    #[arg(long, default_value = "/")]
    pub ros_namespace: String,
    /// shroud's world frame as the ROS side names it: the `frame_id` of
    /// every cloud and marker the bridge sends, and the parent of the
    /// cloud frame's mount on `/tf_static`.
    #[arg(long, default_value = "world")]
    pub frame_id: String,
    /// The ROS `sensor_msgs/PointCloud2` topic read into `--cloud`.
    #[arg(long, default_value = "/points")]
    pub points_topic: String,
    /// The shroud cloud stream the ROS clouds are published on (none: the
    /// bridge reads no clouds).
    #[arg(long)]
    pub cloud: Option<String>,
    #[command(flatten)]
    pub placement: RosCloudArgs,
    /// The ROS `sensor_msgs/JointState` topic read into `--arm`.
    #[arg(long, default_value = "/joint_states")]
    pub joint_states_topic: String,
    /// The shroud arm: joint states from ROS are published on its stream,
    /// and its guard's verdicts are sent to ROS (needs --arm-file).
    #[arg(long)]
    pub arm: Option<String>,
    /// The arm file (its joint names and collision shapes).
    #[arg(long, value_name = "FILE")]
    pub arm_file: Option<PathBuf>,
    /// A surrogate stream to send to ROS as markers (repeatable).
    #[arg(long)]
    pub surrogate: Vec<String>,
    /// A shroud cloud stream to send to ROS as `PointCloud2` (repeatable).
    #[arg(long)]
    pub publish_cloud: Vec<String>,
    /// Send the cloud frame's mount on `/tf_static` (as `frame_id` -> the
    /// cloud's frame): only when no other node publishes that frame's
    /// parent (a robot's URDF usually does; a frame with two parents breaks
    /// every ROS consumer's transforms).
    #[arg(long)]
    pub publish_mount_tf: bool,
    /// The prefix of the ROS topics the bridge sends on.
    #[arg(long, default_value = "/shroud")]
    pub topic_prefix: String,
    /// Most messages a second of each cloud, surrogate and arm-shape stream
    /// sent to ROS (verdicts are never paced).
    #[arg(long, default_value_t = 10.0)]
    pub max_rate: f64,
}

/// What the options say, checked.
struct Plan {
    identity: RosIdentity,
    mount: CloudMount,
    arm: Option<(String, ArmFile)>,
    pace_ns: u64,
}

fn plan(args: &Ros2Args) -> Result<Plan> {
    anyhow::ensure!(
        args.max_rate > 0.0 && args.max_rate <= 1000.0,
        "--max-rate must be in (0, 1000] messages a second"
    );
    let mount = args.placement.mount()?;
    distinct_cloud_topics(&args.publish_cloud)?;
    let arm = match (&args.arm, &args.arm_file) {
        (Some(arm), Some(file)) => Some((arm.clone(), read_arm_file(file)?)),
        (None, None) => None,
        _ => anyhow::bail!("--arm and --arm-file go together"),
    };
    Ok(Plan {
        identity: RosIdentity {
            domain_id: args.domain_id,
            namespace: args.ros_namespace.clone(),
            node_name: args.node_name.clone(),
        },
        mount,
        arm,
        pace_ns: (1e9 / args.max_rate) as u64,
    })
}

pub fn run(args: Ros2Args) -> Result<()> {
    let plan = plan(&args)?;
    let common = args.common.clone();
    run_node(&common, "ros2", move |ctx| bridge(ctx, args, plan))
}

/// A ROS topic under `--topic-prefix`.
fn out_topic(args: &Ros2Args, name: &str) -> String {
    format!("{}/{name}", args.topic_prefix.trim_end_matches('/'))
}

/// Two streams sent to ROS must not land on one topic: `ros_token` maps
/// `cloud/a-b` and `cloud/a_b` alike.
fn distinct_cloud_topics(streams: &[String]) -> Result<()> {
    let mut seen = BTreeMap::new();
    for stream in streams {
        if let Some(other) = seen.insert(ros_token(stream), stream) {
            anyhow::ensure!(
                other == stream,
                "--publish-cloud {other} and {stream} would both be sent on ROS topic cloud/{}",
                ros_token(stream)
            );
        }
    }
    Ok(())
}

/// A shroud stream name as a ROS name token (letters, digits, `_`).
fn ros_token(stream: &str) -> String {
    stream
        .chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
        .collect()
}

fn bridge(ctx: Arc<NodeContext>, args: Ros2Args, plan: Plan) -> Result<()> {
    let ros = RosNode::declare(&ctx.session, plan.identity.clone())?;
    let frame = Arc::new(Mutex::new(None));
    let latest_joints = Arc::new(Mutex::new(RecentJoints::new(RECENT_JOINTS)));
    let mut keep = Vec::new();
    let mut workers = Vec::new();
    if let Some(stream) = &args.cloud {
        let input = CloudInput {
            topic: RosTopic::of::<PointCloud2>(&args.points_topic, QosProfile::SENSOR_DATA),
            output: ctx.output_shared(stream, 64 << 20)?,
            mount: plan.mount,
            source: stream.clone(),
            frame: frame.clone(),
        };
        let (subscription, worker) = clouds_in(&ros, &ctx, input)?;
        keep.push(subscription);
        workers.push(worker);
    }
    let mut listeners = Vec::new();
    if let Some((arm, file)) = &plan.arm {
        let input = JointsInput {
            topic: RosTopic::of::<JointState>(&args.joint_states_topic, QosProfile::DEFAULT),
            output: ctx.output(arm)?,
            matcher: JointMatcher::new(arm, joint_names(file)),
            latest: latest_joints.clone(),
        };
        keep.push(joints_in(&ros, &ctx, input)?);
        let verdicts = Arc::new(VerdictOutput {
            status: ros.publisher(
                &RosTopic::of::<DiagnosticStatus>(
                    &out_topic(&args, "verdict"),
                    QosProfile::DEFAULT,
                ),
                Priority::RealTime,
            )?,
            speed: ros.publisher(
                &RosTopic::of::<Float64>(&out_topic(&args, "speed_scale"), QosProfile::DEFAULT),
                Priority::RealTime,
            )?,
            shapes: ros.publisher(
                &RosTopic::of::<MarkerArray>(&out_topic(&args, "arm_clearance"), reliable(1)),
                Priority::default(),
            )?,
            model: file.arm.clone(),
            frame_id: args.frame_id.clone(),
            latest_joints: latest_joints.clone(),
            pace_ns: plan.pace_ns,
            last_shapes_ns: Mutex::new(None),
        });
        let handler_ctx = ctx.clone();
        listeners.push(
            ctx.listen::<CollisionMessage>(arm, move |_: &_, verdict: CollisionMessage| {
                verdicts.on_verdict(&handler_ctx, &verdict)
            })?,
        );
    }
    let outputs = stream_outputs(&ros, &args, &plan, frame)?;
    let inbox = Arc::new(Inbox::new());
    for (kind, streams) in [
        (TopicKind::Surrogate, &args.surrogate),
        (TopicKind::Cloud, &args.publish_cloud),
    ] {
        for stream in streams {
            let key = ctx.key(kind, stream)?;
            let inbox = inbox.clone();
            listeners.push(ctx.listen_raw(&key, move |arrival| {
                inbox.push(&arrival.key, arrival.payload)
            })?);
        }
    }
    tracing::info!(
        node = %args.node_name,
        domain = args.domain_id,
        "in the ROS 2 graph as {}{}",
        args.ros_namespace.trim_end_matches('/'),
        format_args!("/{}", args.node_name)
    );
    outputs.run(&ctx, &inbox);
    for worker in workers {
        let _ = worker.join();
    }
    drop((keep, listeners));
    Ok(())
}

fn stream_outputs(
    ros: &RosNode,
    args: &Ros2Args,
    plan: &Plan,
    frame: Arc<Mutex<Option<String>>>,
) -> Result<StreamOutputs> {
    let surrogates = match args.surrogate.is_empty() {
        true => None,
        false => Some(ros.publisher(
            &RosTopic::of::<MarkerArray>(&out_topic(args, "surrogates"), reliable(1)),
            Priority::default(),
        )?),
    };
    let mut clouds = BTreeMap::new();
    for stream in &args.publish_cloud {
        let name = out_topic(args, &format!("cloud/{}", ros_token(stream)));
        let topic = RosTopic::of::<PointCloud2>(&name, QosProfile::SENSOR_DATA);
        clouds.insert(stream.clone(), ros.publisher(&topic, Priority::DataLow)?);
    }
    let tf = match args.cloud.is_some() && args.publish_mount_tf {
        true => Some(MountTransform {
            publisher: ros.publisher(
                &RosTopic::of::<TFMessage>("/tf_static", latched()),
                Priority::default(),
            )?,
            mount: plan.mount,
            frame,
        }),
        false => None,
    };
    Ok(StreamOutputs {
        surrogates,
        clouds,
        frame_id: args.frame_id.clone(),
        per_cell: SURFACE_PER_CELL,
        pace_ns: plan.pace_ns,
        tf,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn streams_that_would_share_a_ros_topic_are_refused_by_name() {
        let streams = ["cloud/a-b".to_string(), "cloud/a_b".to_string()];
        let error = distinct_cloud_topics(&streams).unwrap_err().to_string();
        assert!(
            error.contains("cloud/a-b") && error.contains("cloud/a_b"),
            "{error}"
        );
        assert!(error.contains("cloud/cloud_a_b"), "{error}");
    }

    #[test]
    fn distinct_streams_and_a_repeated_one_are_accepted() {
        let streams = ["cloud/a".into(), "cloud/b".into(), "cloud/a".into()];
        distinct_cloud_topics(&streams).unwrap();
    }
}
