//! How a command ends: its outcome, or an error that says whose fault it is (exit code).

use std::fmt;

/// How a command that did not fail ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// It did what was asked (exit code 0).
    Done,
    /// Ctrl-C stopped the run after writing a checkpoint (exit code 130).
    Interrupted,
}

/// Why a command failed; the message is printed as is after `error: `.
#[derive(Debug)]
pub enum CliError {
    /// Bad input: a scene or checkpoint that cannot be read or built, an impossible option
    /// (exit code 2). Scene errors name the file, line, column and key.
    Input(String),
    /// The run went wrong after it started: an unstable simulation, an output file that cannot
    /// be written (exit code 1).
    Run(String),
}

impl CliError {
    /// The process exit code for this error.
    pub fn exit_code(&self) -> i32 {
        match self {
            CliError::Input(_) => 2,
            CliError::Run(_) => 1,
        }
    }
}

impl From<flexdem_run::RunError> for CliError {
    /// Bad input (exit code 2) or a failed run (exit code 1), as the error says.
    fn from(e: flexdem_run::RunError) -> CliError {
        if e.is_bad_input() {
            CliError::Input(e.to_string())
        } else {
            CliError::Run(e.to_string())
        }
    }
}

impl fmt::Display for CliError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CliError::Input(m) | CliError::Run(m) => f.write_str(m),
        }
    }
}

impl std::error::Error for CliError {}
