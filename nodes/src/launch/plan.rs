//! Every node's command line, built from its settings and ports and checked
//! by the node's own option parser before the launcher starts anything: a
//! misspelt setting is an error naming the file's line, not a restart loop.

use crate::node::NodeCommand;
use clap::{CommandFactory, Parser};
use shroud_graph::launch::{LaunchError, LaunchFile, NodeSpec};

/// A node of the file with the options it is started with (after the
/// launcher's own).
#[derive(Debug, Clone)]
pub struct PlannedNode {
    pub spec: NodeSpec,
    pub args: Vec<String>,
}

/// `shroud node ...` as the node itself parses it.
#[derive(Debug, Parser)]
#[command(name = "node")]
struct NodeLine {
    #[command(subcommand)]
    node: NodeCommand,
}

/// Builds and checks every node's command line.
pub fn plan(file: &LaunchFile) -> Result<Vec<PlannedNode>, LaunchError> {
    file.nodes.iter().map(plan_node).collect()
}

fn plan_node(spec: &NodeSpec) -> Result<PlannedNode, LaunchError> {
    let root = NodeLine::command();
    let command = root
        .find_subcommand(spec.kind.as_str())
        .ok_or_else(|| spec.error(format!("{} is not a node subcommand", spec.kind)))?;
    let mut args = spec.port_args()?;
    args.extend(setting_args(command, spec)?);
    let mut line = vec!["node".to_owned(), spec.kind.as_str().to_owned()];
    line.extend(["--name".to_owned(), spec.name.clone()]);
    line.extend(args.iter().cloned());
    NodeLine::try_parse_from(&line).map_err(|e| spec.error(one_line(&e.to_string())))?;
    Ok(PlannedNode {
        spec: spec.clone(),
        args,
    })
}

/// clap's message on one line, without its usage and help footer (a missing
/// option is named on the lines after the first).
fn one_line(message: &str) -> String {
    let body = message
        .split("\n\nUsage:")
        .next()
        .and_then(|m| m.split("\n\nFor more information").next())
        .unwrap_or(message);
    let lines = body.lines().filter(|l| !l.trim_start().starts_with("tip:"));
    let text = lines
        .flat_map(str::split_whitespace)
        .collect::<Vec<_>>()
        .join(" ");
    text.strip_prefix("error: ").unwrap_or(&text).to_owned()
}

/// `settings` as options: `key = value` is `--key=value`, an array repeats
/// the option, `true` turns a switch on, a positional argument takes its value
/// in place.
fn setting_args(command: &clap::Command, spec: &NodeSpec) -> Result<Vec<String>, LaunchError> {
    let mut options = Vec::new();
    let mut positional = Vec::new();
    for (key, value) in &spec.settings {
        let long = key.replace('_', "-");
        let id = key.replace('-', "_");
        let arg = command
            .get_arguments()
            .find(|a| {
                a.get_long() == Some(long.as_str())
                    || a.get_all_aliases()
                        .is_some_and(|v| v.contains(&long.as_str()))
                    || (a.is_positional() && a.get_id().as_str() == id)
            })
            .ok_or_else(|| {
                spec.error(format!(
                    "settings.{key} is not an option of a {} node (its settings: {})",
                    spec.kind,
                    settings_of(command, spec).join(", ")
                ))
            })?;
        let values =
            scalars(value).map_err(|reason| spec.error(format!("settings.{key}: {reason}")))?;
        if arg.is_positional() {
            positional.extend(values);
        } else if !arg.get_action().takes_values() {
            match value {
                toml::Value::Boolean(true) => options.push(format!("--{long}")),
                toml::Value::Boolean(false) => {}
                _ => return Err(spec.error(format!("settings.{key} is a switch: true or false"))),
            }
        } else {
            options.extend(values.into_iter().map(|v| format!("--{long}={v}")));
        }
    }
    // After `--`, a value that starts with `-` is still a positional value.
    if !positional.is_empty() {
        options.push("--".to_owned());
        options.extend(positional);
    }
    Ok(options)
}

/// The options a launch file may set for this kind.
fn settings_of(command: &clap::Command, spec: &NodeSpec) -> Vec<String> {
    command
        .get_arguments()
        .filter_map(|a| match a.get_long() {
            Some(long) => Some(long),
            None if a.is_positional() => Some(a.get_id().as_str()),
            None => None,
        })
        .filter(|name| *name != "help" && spec.reserved_setting(name).is_none())
        .map(|name| name.replace('-', "_"))
        .collect()
}

/// A setting's value or values as text.
fn scalars(value: &toml::Value) -> Result<Vec<String>, String> {
    match value {
        toml::Value::Array(items) => items.iter().map(scalar).collect(),
        other => Ok(vec![scalar(other)?]),
    }
}

fn scalar(value: &toml::Value) -> Result<String, String> {
    match value {
        toml::Value::String(s) => Ok(s.clone()),
        toml::Value::Integer(i) => Ok(i.to_string()),
        toml::Value::Float(f) => Ok(f.to_string()),
        toml::Value::Boolean(b) => Ok(b.to_string()),
        other => Err(format!(
            "a {} is not an option value (text, a number, true/false or an array of them)",
            other.type_str()
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use shroud_graph::launch::{Direction, NodeKind};

    fn planned(text: &str) -> Result<Vec<PlannedNode>, String> {
        let file = LaunchFile::from_toml_str(text).map_err(|e| e.to_string())?;
        plan(&file).map_err(|e| e.to_string())
    }

    const FIT: &str = "external = [\"cloud/c\"]\n\n[[node]]\nname = \"fit\"\nkind = \"fit\"\n\
                       inputs = { cloud = \"c\" }\noutputs = { surrogate = \"s\" }\n";

    #[test]
    fn settings_become_options_in_order() {
        let text = format!("{FIT}settings = {{ grid = \"8x8\", dir = \"0,0,-1\", queue = 2 }}\n");
        let nodes = planned(&text).unwrap();
        assert_eq!(
            nodes[0].args,
            vec![
                "--input=c",
                "--output=s",
                "--dir=0,0,-1",
                "--grid=8x8",
                "--queue=2"
            ]
        );
    }

    #[test]
    fn switches_arrays_and_positionals() {
        let text = "[[node]]\nname = \"r\"\nkind = \"replay\"\n\
                    outputs = { cloud = \"c\" }\n\
                    settings = { file = \"a.mcap\", loop = true, restamp = false }\n\
                    [[node]]\nname = \"b\"\nkind = \"blend\"\n\
                    inputs = { blend = \"b\" }\noutputs = { cloud = \"o\" }\nexternal_ok = 1\n";
        // `external_ok` is not a field: the whole file is refused.
        assert!(planned(text).unwrap_err().contains("external_ok"));
        let text = text.replace(
            "external_ok = 1\n",
            "settings = { child_part = [\"hemisphere\", \"half-cylinder\"], parent = \"p.ply\" }\n",
        );
        let text = format!("external = [\"blend/b\"]\n{text}");
        let nodes = planned(&text).unwrap();
        assert_eq!(
            nodes[0].args,
            vec!["--topics=cloud/c", "--loop", "--", "a.mcap"]
        );
        assert_eq!(
            nodes[1].args,
            vec![
                "--stream=b",
                "--output=o",
                "--child-part=hemisphere",
                "--child-part=half-cylinder",
                "--parent=p.ply"
            ]
        );
    }

    /// A setting may name an option by its alias (the viewers' `points_budget`).
    #[test]
    fn an_alias_is_a_setting_too() {
        for kind in ["dashboard", "foxglove"] {
            for key in ["point_budget", "points_budget"] {
                let text = format!(
                    "[[node]]\nname = \"v\"\nkind = \"{kind}\"\nsettings = {{ {key} = 2000 }}\n"
                );
                let nodes = planned(&text).unwrap();
                let flag = format!("--{}=2000", key.replace('_', "-"));
                assert!(nodes[0].args.contains(&flag), "{kind}: {:?}", nodes[0].args);
            }
        }
    }

    #[test]
    fn a_wrong_setting_is_refused_with_its_line_before_anything_runs() {
        for (settings, needle) in [
            (
                "grd = \"8x8\"",
                "line 3: node \"fit\": settings.grd is not an option of a fit node (its settings:",
            ),
            (
                "queue = \"many\"",
                "line 3: node \"fit\": invalid value 'many' for '--queue <QUEUE>'",
            ),
            ("side = \"both\"", "invalid value 'both'"),
            (
                "queue = { n = 1 }",
                "settings.queue: a table is not an option value",
            ),
        ] {
            let text = format!("{FIT}settings = {{ {settings} }}\n");
            let err = planned(&text).unwrap_err();
            assert!(err.contains(needle), "{settings}: {err}");
        }
        let switch = "[[node]]\nname = \"a\"\nkind = \"arm\"\ninputs = { collision = \"a\" }\n\
                      outputs = { joints = \"a\" }\nsettings = { arm_file = \"x.toml\", ignore_guard = \"yes\" }\n";
        let text = format!("external = [\"collision/a\"]\n{switch}");
        assert!(planned(&text)
            .unwrap_err()
            .contains("settings.ignore_guard is a switch"));
    }

    #[test]
    fn a_missing_option_is_named_and_a_mount_joint_needs_its_joints() {
        let guard = "[[node]]\nname = \"g\"\nkind = \"guard\"\n\
                     inputs = { surrogate = \"s\", joints = \"a\" }\noutputs = { collision = \"a\" }\n";
        let text = format!("external = [\"surrogate/s\", \"joints/a\"]\n{guard}");
        let err = planned(&text).unwrap_err();
        let needle = "line 2: node \"g\": the following required arguments were not provided: \
                      --arm-file <ARM_FILE>";
        assert!(err.contains(needle), "{err}");
        let serial = "[[node]]\nname = \"s\"\nkind = \"serial\"\noutputs = { cloud = \"c\" }\n\
                      settings = { port = \"/dev/null\", device = \"tfmini\", mount_joint = \"tilt\" }\n";
        let err = planned(serial).unwrap_err();
        assert!(
            err.contains("inputs.joints and settings.mount_joint go together"),
            "{err}"
        );
        let fed = serial.replace("outputs =", "inputs = { joints = \"m\" }\noutputs =");
        let text = format!("external = [\"joints/m\"]\n{fed}");
        let nodes = planned(&text).unwrap();
        assert!(
            nodes[0].args.contains(&"--joints=m".to_string()),
            "{:?}",
            nodes[0].args
        );
    }

    /// Every port's option exists on its node, so the kind table cannot
    /// drift from the nodes' parsers; and the kinds are exactly the node
    /// subcommands (all but `list`).
    #[test]
    fn the_kind_table_matches_the_nodes_options() {
        let root = NodeLine::command();
        let mut kinds: Vec<&str> = root
            .get_subcommands()
            .map(|c| c.get_name())
            .filter(|n| *n != "list")
            .collect();
        kinds.sort();
        let mut known: Vec<&str> = NodeKind::ALL.iter().map(|k| k.as_str()).collect();
        known.sort();
        assert_eq!(kinds, known);
        for kind in NodeKind::ALL {
            let command = root.find_subcommand(kind.as_str()).unwrap();
            for port in kind.ports() {
                let arg = command
                    .get_arguments()
                    .find(|a| a.get_long() == Some(port.flag))
                    .unwrap_or_else(|| panic!("{kind}: no --{}", port.flag));
                assert!(arg.get_action().takes_values(), "{kind}: --{}", port.flag);
                if port.many && port.direction == Direction::Input {
                    assert!(
                        matches!(arg.get_action(), clap::ArgAction::Append),
                        "{kind}: --{} is not repeatable",
                        port.flag
                    );
                }
            }
        }
    }

    /// The shipped launch files parse, wire and pass every node's parser.
    #[test]
    fn the_shipped_launch_files_are_valid() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../launch");
        let mut seen = 0;
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            if path.extension().is_some_and(|e| e == "toml") {
                let text = std::fs::read_to_string(&path).unwrap();
                if let Err(e) = planned(&text) {
                    panic!("{}: {e}", path.display());
                }
                seen += 1;
            }
        }
        assert!(seen >= 7, "{seen} launch files");
    }

    /// The picture of the demo's graph in the docs is what `--graph` draws.
    #[test]
    fn the_docs_show_the_demos_graph_as_drawn() {
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
        let demo = std::fs::read_to_string(root.join("launch/demo.toml")).unwrap();
        let chart =
            shroud_graph::launch::wiring_mermaid(&LaunchFile::from_toml_str(&demo).unwrap())
                .unwrap();
        let docs = std::fs::read_to_string(root.join("docs/node-graph.md")).unwrap();
        assert!(
            docs.contains(&format!("```mermaid\n{chart}```")),
            "docs/node-graph.md: redraw with `shroud launch launch/demo.toml --graph`"
        );
    }
}
