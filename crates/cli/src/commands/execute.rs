//! What `run` and `resume` share once their [`Run`] is set up: the run itself (in
//! `flexdem-run`) with a progress bar and the warnings on the terminal, then the report, the
//! JSON summary and the exit status; and the Ctrl-C flag.

use crate::cli::ExecOptions;
use crate::error::{CliError, Outcome};
use crate::progress::Progress;
use crate::report;
use flexdem_integrate::Simulation;
use flexdem_io::scene::RunLength;
use flexdem_run::{write_json, Run, RunObserver, Status};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, OnceLock};

/// The flag set by Ctrl-C, with the handler installed on first use. A second Ctrl-C while
/// the first is being handled ends the process at once (exit code 130).
pub fn interrupt_flag() -> Result<Arc<AtomicBool>, CliError> {
    static FLAG: OnceLock<Result<Arc<AtomicBool>, String>> = OnceLock::new();
    FLAG.get_or_init(|| {
        let flag = Arc::new(AtomicBool::new(false));
        let handler_flag = Arc::clone(&flag);
        ctrlc::set_handler(move || {
            if handler_flag.swap(true, Ordering::SeqCst) {
                eprintln!("\nsecond Ctrl-C: stopping now, without a checkpoint");
                std::process::exit(130);
            }
        })
        .map_err(|e| format!("cannot install the Ctrl-C handler: {e}"))?;
        Ok(flag)
    })
    .clone()
    .map_err(CliError::Run)
}

/// The terminal's view of a run: a progress bar (unless quiet) and the warnings on stderr.
struct Terminal {
    quiet: bool,
    progress: Option<Progress>,
}

impl RunObserver for Terminal {
    fn started(&mut self, sim: &Simulation, target: RunLength) {
        self.progress = Some(Progress::new(sim, target, self.quiet));
    }

    fn stepped(&mut self, sim: &Simulation) {
        if let Some(progress) = self.progress.as_mut() {
            progress.tick(sim);
        }
    }

    fn warning(&mut self, message: &str) {
        match &self.progress {
            Some(progress) => progress.suspend(|| eprintln!("warning: {message}")),
            None => eprintln!("warning: {message}"),
        }
    }

    fn finished(&mut self, _sim: &Simulation) {
        if let Some(progress) = self.progress.take() {
            progress.finish();
        }
    }
}

/// Runs `run` to its end, Ctrl-C or an error; prints the report and writes the summary as
/// `exec` asks.
pub fn execute(mut run: Run, exec: &ExecOptions) -> Result<Outcome, CliError> {
    let mut terminal = Terminal { quiet: exec.quiet, progress: None };
    let summary = run.execute(&mut terminal)?;
    if !exec.quiet {
        print!("{}", report::text(&summary));
    }
    if let Some(path) = &exec.summary {
        write_json(&summary, path)?;
    }
    match (summary.status, &summary.error) {
        (_, Some(message)) => Err(CliError::Run(match &summary.output {
            Some(o) => {
                format!("{message}\n(the output written so far is in {})", o.directory.display())
            }
            None => message.clone(),
        })),
        (Status::Interrupted, None) => {
            let path = run.checkpoint_path().display();
            eprintln!(
                "interrupted at step {}: checkpoint written to {path}; continue with \
                 `flexdem resume {path}`",
                run.sim().steps(),
            );
            Ok(Outcome::Interrupted)
        }
        _ => Ok(Outcome::Done),
    }
}
