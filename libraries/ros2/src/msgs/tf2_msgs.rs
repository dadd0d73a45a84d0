//! tf2_msgs (geometry2, Jazzy): TFMessage.msg, what `/tf` and `/tf_static` carry.

use super::geometry_msgs::TransformStamped;

ros_message! {
    /// A batch of transforms (tf2_msgs/msg/TFMessage).
    "tf2_msgs/msg/TFMessage",
    "RIHS01_e369d0f05a23ae52508854b66f6aa0437f3449d652e8cbf22d5abe85d020f087";
    pub struct TFMessage {
        pub transforms: Vec<TransformStamped>,
    }
}
