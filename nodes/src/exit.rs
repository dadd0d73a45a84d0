//! An error that asks for a particular exit status (the binary's edge maps
//! every other error to 1).

use std::fmt;

/// Ends the program with `code` after printing `message` as the error.
#[derive(Debug)]
pub struct ExitWith {
    pub code: u8,
    pub message: String,
}

impl ExitWith {
    pub fn new(code: u8, message: String) -> Self {
        Self { code, message }
    }
}

impl fmt::Display for ExitWith {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for ExitWith {}
