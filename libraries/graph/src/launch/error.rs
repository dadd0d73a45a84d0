//! Why a launch file cannot be used.

use thiserror::Error;

#[derive(Debug, Error, Clone, PartialEq)]
pub enum LaunchError {
    #[error("launch file is not valid TOML for the launch schema: {0}")]
    Syntax(String),
    #[error("launch file declares no node")]
    NoNodes,
    #[error("lines {first} and {again}: two nodes are named {name:?}; node names must be unique")]
    DuplicateNode {
        name: String,
        first: usize,
        again: usize,
    },
    #[error("line {line}: node {node:?}: {reason}")]
    Node {
        node: String,
        line: usize,
        reason: String,
    },
    #[error("{field}: {reason}")]
    Invalid { field: String, reason: String },
}
