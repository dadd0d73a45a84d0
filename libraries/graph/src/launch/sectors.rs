//! A guard reads the sectors of a surrogate stream only if it is told how
//! many there are (its `sectors` setting), and a fit node publishes them only
//! with the same setting: a mismatch leaves sector streams unread, or a guard
//! waiting for streams nobody writes. Never unsound (each view holds alone),
//! but silently looser than the file says, so the launcher refuses it.

use super::error::LaunchError;
use super::file::NodeSpec;
use super::kind::NodeKind;
use std::fmt::Display;

/// A node's `sectors` setting: 0 when absent (the node's default), `None`
/// when it is not an integer (the node's own parser names that value before
/// anything starts).
pub(super) fn sectors_of(node: &NodeSpec) -> Option<i64> {
    match node.settings.get("sectors") {
        None => Some(0),
        Some(toml::Value::Integer(n)) => Some(*n),
        Some(toml::Value::String(s)) => s.trim().parse().ok(),
        Some(_) => None,
    }
}

/// Refuses a guard that reads sectors while ignoring unseen space: a sector
/// says nothing outside its cone, so judged by occupied space alone it would
/// call free what another view saw blocked.
pub(super) fn check_sectors_policy(node: &NodeSpec) -> Result<(), LaunchError> {
    let ignores = node
        .settings
        .get("unobserved")
        .and_then(toml::Value::as_str)
        == Some("ignore");
    if node.kind == NodeKind::Guard && ignores && sectors_of(node).is_some_and(|n| n != 0) {
        return Err(node.error(
            "sectors need unobserved = \"stop\": a sector says nothing outside its cone".into(),
        ));
    }
    Ok(())
}

/// Refuses a guard that reads `stream` from a fit node with another
/// `sectors` setting than its own; any other pair of nodes passes.
pub(super) fn check_sectors_match(
    reader: &NodeSpec,
    writer: &NodeSpec,
    stream: impl Display,
) -> Result<(), LaunchError> {
    if reader.kind != NodeKind::Guard || writer.kind != NodeKind::Fit {
        return Ok(());
    }
    let (Some(reads), Some(fits)) = (sectors_of(reader), sectors_of(writer)) else {
        return Ok(());
    };
    if reads == fits {
        return Ok(());
    }
    Err(reader.error(format!(
        "reads {stream} with sectors = {reads}, but node {:?} fits it with sectors = {fits}: \
         give both the same",
        writer.name
    )))
}

#[cfg(test)]
mod tests {
    use crate::launch::{check_graph, LaunchFile};

    fn graph(fit_sectors: &str, guard_sectors: &str) -> String {
        format!(
            "namespace = \"t\"\n\
             external = [\"cloud/c\", \"joints/arm\"]\n\
             [[node]]\nname = \"fit\"\nkind = \"fit\"\n\
             inputs = {{ cloud = \"c\" }}\noutputs = {{ surrogate = \"s\" }}\n\
             settings = {{ {fit_sectors} }}\n\
             [[node]]\nname = \"guard\"\nkind = \"guard\"\n\
             inputs = {{ surrogate = \"s\", joints = \"arm\" }}\noutputs = {{ collision = \"arm\" }}\n\
             settings = {{ arm_file = \"a.toml\" {guard_sectors} }}\n"
        )
    }

    fn check(text: &str) -> Result<(), String> {
        let file = LaunchFile::from_toml_str(text).map_err(|e| e.to_string())?;
        check_graph(&file).map_err(|e| e.to_string())
    }

    #[test]
    fn a_guard_and_its_fit_node_must_agree_on_sectors() {
        assert_eq!(check(&graph("sectors = 4", ", sectors = 4")), Ok(()));
        assert_eq!(check(&graph("sectors = \"4\"", ", sectors = 4")), Ok(()));
        let ignoring = check(&graph(
            "sectors = 2",
            ", sectors = 2, unobserved = \"ignore\"",
        ));
        assert!(ignoring.unwrap_err().contains("sectors need unobserved"));
        assert_eq!(check(&graph("", "")), Ok(()));
        for (fit, guard, reads, fits) in [
            ("sectors = 4", "", 0, 4),
            ("", ", sectors = 2", 2, 0),
            ("sectors = 3", ", sectors = 4", 4, 3),
        ] {
            let err = check(&graph(fit, guard)).unwrap_err();
            let expected = format!(
                "reads surrogate/s with sectors = {reads}, but node \"fit\" fits it with sectors = {fits}"
            );
            assert!(err.contains(&expected), "{err}");
            assert!(err.contains("node \"guard\""), "{err}");
        }
    }
}
