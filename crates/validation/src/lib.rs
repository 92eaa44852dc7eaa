//! Validation of flexdem against cases with a known answer (`shared/spec/validation.md`), the
//! Chung & Ooi (2011) benchmark and YADE 2023.02a run side by side.
//!
//! A [`Case`] is a plain function that builds a model with the public API of
//! `flexdem-elements`/`flexdem-integrate`, runs it, draws its PNG plots into
//! [`Context::out_dir`] and returns a [`CaseReport`]: a list of [`Check`]s (expected value,
//! measured value, tolerance, where the expected value comes from). [`run_cases`] runs the
//! registered [`cases`] and [`write_report`] writes them as `report.md`.
//!
//! A failed physics check never panics: the case reports the numbers and
//! [`CaseReport::passed`] is false. Only a failure to run at all is a [`ValidationError`].

pub mod cases;
mod error;
pub mod plot;
pub mod report;
pub mod rest;
pub mod runner;
pub mod threads;

pub use cases::{cases, Case};
pub use error::ValidationError;
pub use plot::{plot_xy, Curve, CurveStyle, PlotSpec};
pub use report::{CaseReport, Check, Context, Figure, Tolerance};
pub use runner::{
    report_markdown, run_case, run_cases, run_cases_with, selected_cases, single_threaded,
    write_report, CaseResult, REPORT_FILE,
};
