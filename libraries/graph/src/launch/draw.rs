//! The wiring of a launch file as text and as a Mermaid flowchart
//! (`shroud launch FILE --graph`).

use super::error::LaunchError;
use super::file::LaunchFile;
use super::kind::Direction;
use super::wiring::Source;
use std::fmt::Write;

/// One line per node: its kind, what it reads (and from whom) and writes.
pub fn wiring_text(file: &LaunchFile) -> Result<String, LaunchError> {
    let edges = file.edges()?;
    let mut out = format!(
        "graph {:?}: {} nodes (topics under shroud/{}/)\n",
        file.namespace,
        file.nodes.len(),
        file.namespace
    );
    for node in &file.nodes {
        let _ = writeln!(out, "{} [{}]", node.name, node.kind);
        for edge in edges.iter().filter(|e| std::ptr::eq(e.to, node)) {
            let from = match &edge.from {
                Source::Node(n) => n.name.as_str(),
                Source::External => "outside the file",
            };
            let _ = writeln!(out, "  reads  {} from {from}", edge.stream);
        }
        if node.kind.observes_everything() {
            let _ = writeln!(out, "  reads  every topic of the namespace");
        }
        for wire in node.wires()? {
            if wire.port.direction == Direction::Output {
                let _ = writeln!(out, "  writes {}", wire.stream);
            }
        }
    }
    Ok(out)
}

/// A Mermaid flowchart: a box per node, an arrow per stream from its
/// producer (or from outside) to each reader.
pub fn wiring_mermaid(file: &LaunchFile) -> Result<String, LaunchError> {
    let edges = file.edges()?;
    let mut out = String::from("flowchart LR\n");
    for (i, node) in file.nodes.iter().enumerate() {
        let _ = writeln!(out, "  n{i}[\"{}<br/><i>{}</i>\"]", node.name, node.kind);
    }
    let index = |name: &str| file.nodes.iter().position(|n| n.name == name);
    let mut outside = Vec::new();
    for edge in &edges {
        let to = index(&edge.to.name).unwrap_or_default();
        match &edge.from {
            Source::Node(from) => {
                let from = index(&from.name).unwrap_or_default();
                let _ = writeln!(out, "  n{from} -- \"{}\" --> n{to}", edge.stream);
            }
            Source::External => {
                let id = match outside.iter().position(|s| *s == edge.stream) {
                    Some(k) => k,
                    None => {
                        outside.push(edge.stream.clone());
                        let k = outside.len() - 1;
                        let _ = writeln!(out, "  x{k}((\"{} (outside)\"))", edge.stream);
                        k
                    }
                };
                let _ = writeln!(out, "  x{id} --> n{to}");
            }
        }
    }
    for (i, node) in file.nodes.iter().enumerate() {
        if node.kind.observes_everything() {
            let _ = writeln!(out, "  all((\"every topic\")) -.-> n{i}");
        }
    }
    Ok(out)
}
