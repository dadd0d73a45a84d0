//! The DDS spelling of a ROS type name, which rmw_zenoh puts in topic keys
//! and liveliness tokens (rosidl's DDS mangling: `pkg::msg::dds_::Name_`).

/// A ROS type name that is not `package/kind/Name`.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("type name {type_name:?}: {problem}")]
pub struct TypeNameError {
    pub type_name: String,
    pub problem: &'static str,
}

/// `"sensor_msgs/msg/PointCloud2"` → `"sensor_msgs::msg::dds_::PointCloud2_"`.
pub fn dds_type_name(type_name: &str) -> Result<String, TypeNameError> {
    let error = |problem| TypeNameError {
        type_name: type_name.to_string(),
        problem,
    };
    let parts: Vec<&str> = type_name.split('/').collect();
    let [package, kind, name] = parts[..] else {
        return Err(error("needs three parts, package/kind/Name"));
    };
    if !matches!(kind, "msg" | "srv" | "action") {
        return Err(error("the kind must be msg, srv or action"));
    }
    let is_identifier = |part: &str| {
        part.chars().next().is_some_and(|c| c.is_ascii_alphabetic())
            && part.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
    };
    if !is_identifier(package) || !is_identifier(name) {
        return Err(error("package and name must be [A-Za-z][A-Za-z0-9_]*"));
    }
    Ok(format!("{package}::{kind}::dds_::{name}_"))
}
