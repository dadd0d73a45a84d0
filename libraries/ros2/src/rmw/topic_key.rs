//! The zenoh key a topic's samples travel on:
//! `<domain>/<topic without leading or trailing '/'>/<DDS type>/<type hash>`
//! (rmw_zenoh docs/design.md@99a6a2bd; liveliness_utils.cpp@3411fdec, `TopicInfo`).

use super::error::RmwError;
use crate::msgs::dds_type_name;

/// Checks a topic name by ROS 2's rules for an expanded name (rcl's
/// `rmw_validate_full_topic_name`, the leading '/' optional): not empty,
/// only `[A-Za-z0-9_/]`, no `//`, no trailing '/', no token starting with a
/// digit. Returns the name without its leading '/'.
pub fn validate_topic_name(name: &str) -> Result<&str, RmwError> {
    let error = |problem| RmwError::TopicName {
        name: name.to_string(),
        problem,
    };
    let relative = name.strip_prefix('/').unwrap_or(name);
    if relative.is_empty() {
        return Err(error("is empty"));
    }
    if !relative
        .chars()
        .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '/')
    {
        return Err(error("may hold only A-Z, a-z, 0-9, '_' and '/'"));
    }
    if relative.ends_with('/') {
        return Err(error("ends with '/'"));
    }
    if relative.split('/').any(str::is_empty) {
        return Err(error("holds '//'"));
    }
    if relative
        .split('/')
        .any(|token| token.starts_with(|c: char| c.is_ascii_digit()))
    {
        return Err(error("has a token starting with a digit"));
    }
    Ok(relative)
}

/// The key of `topic`'s samples in `domain_id`, e.g.
/// `0/shroud/cloud/sensor_msgs::msg::dds_::PointCloud2_/RIHS01_9198…`.
/// `type_name` is the ROS name (`sensor_msgs/msg/PointCloud2`) or already
/// its DDS form; the key carries the DDS form.
pub fn topic_key(
    domain_id: u32,
    topic: &str,
    type_name: &str,
    type_hash: &str,
) -> Result<String, RmwError> {
    let topic = validate_topic_name(topic)?;
    let dds_type = if type_name.contains("::") {
        check_key_part("type name", type_name)?.to_string()
    } else {
        dds_type_name(type_name).map_err(|e| RmwError::KeyPart {
            part: "type name",
            value: type_name.to_string(),
            problem: e.problem,
        })?
    };
    let type_hash = check_key_part("type hash", type_hash)?;
    Ok(format!("{domain_id}/{topic}/{dds_type}/{type_hash}"))
}

/// A single key chunk: not empty, none of zenoh's special characters.
fn check_key_part<'a>(part: &'static str, value: &'a str) -> Result<&'a str, RmwError> {
    let problem = if value.is_empty() {
        "is empty"
    } else if value.contains(['/', '*', '$', '#', '?']) {
        "holds one of / * $ # ?"
    } else {
        return Ok(value);
    };
    Err(RmwError::KeyPart {
        part,
        value: value.to_string(),
        problem,
    })
}
