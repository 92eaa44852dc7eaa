//! The sphere's first dip into the net over 200 starts in both codes (YADE's
//! `sphere_on_net_first_dip.py`).
//!
//! The first dip (the sphere's lowest height in its first impact, near step 6 100) follows
//! the chatter of steps 3 900–4 500, which is chaotic: a start 1e-10 m higher moves it by up
//! to 20 %. So it is compared as a mean over many starts, read at every step. Neighbouring
//! starts give correlated dips, so the standard error of a mean is taken from the means of
//! blocks of consecutive starts ([`block_standard_error`]), not from the starts as if they
//! were independent.

use super::scene::run_net;
use super::stats::{block_standard_error, describe, mean, standard_deviation};
use crate::cases::yade_side_by_side::read_csv_columns;
use crate::report::{CaseReport, Check};
use crate::threads::on_all_threads;
use crate::ValidationError;
use flexdem_geom::Real;
use rayon::prelude::*;
use std::path::Path;

/// The starts: the sphere `k·FIRST_DIP_SHIFT` higher for `k` in [`FIRST_DIP_KS`], as in
/// `sphere_on_net_first_dip.py`.
pub(super) const FIRST_DIP_SHIFT: Real = 1e-8;
pub(super) const FIRST_DIP_KS: std::ops::Range<i32> = -100..100;
/// Steps over which the lowest height is taken (0.4 s: the first dip, not the second).
pub(super) const FIRST_DIP_STEPS: u64 = 10_000;

/// One code's first dips, in the order of `k`.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct FirstDips {
    /// The sphere's lowest height over the first [`FIRST_DIP_STEPS`] steps (m).
    pub(super) lowest: Vec<Real>,
    /// The step at which it was reached.
    pub(super) step: Vec<Real>,
}

/// flexdem's run from the start `shift` higher: the sphere's lowest height over the first
/// [`FIRST_DIP_STEPS`] steps, read after every step, and the step.
fn first_dip(dt: Real, shift: Real) -> Result<(Real, u64), ValidationError> {
    let mut run = run_net(dt, 0, shift)?;
    let mut lowest = (run.sim.model().particles.pos[run.sphere].z, 0);
    for step in 1..=FIRST_DIP_STEPS {
        run.sim.run(1)?;
        let z = run.sim.model().particles.pos[run.sphere].z;
        if z < lowest.0 {
            lowest = (z, step);
        }
    }
    Ok(lowest)
}

/// flexdem's first dips from every start, in the order of `k`.
pub(super) fn flexdem_first_dips(dt: Real) -> Result<FirstDips, ValidationError> {
    let dips: Vec<Result<(Real, u64), ValidationError>> = on_all_threads(|| {
        FIRST_DIP_KS
            .collect::<Vec<_>>()
            .into_par_iter()
            .map(|k| first_dip(dt, k as Real * FIRST_DIP_SHIFT))
            .collect()
    });
    let dips = dips.into_iter().collect::<Result<Vec<_>, _>>()?;
    Ok(FirstDips {
        lowest: dips.iter().map(|d| d.0).collect(),
        step: dips.iter().map(|d| d.1 as Real).collect(),
    })
}

/// YADE's first dips (`sphere_on_net_first_dip.csv` in `dir`), checked to be from the same
/// starts, in the order of `k`.
pub(super) fn yade_first_dips(dir: &Path) -> Result<FirstDips, ValidationError> {
    let path = dir.join("sphere_on_net_first_dip.csv");
    let rows = read_csv_columns(&path, &["k", "shift", "min_sphere_z", "min_step"])?;
    let ks: Vec<i32> = rows.iter().map(|r| r[0] as i32).collect();
    let shifts_match =
        rows.iter().all(|r| (r[1] - r[0] * FIRST_DIP_SHIFT).abs() <= 1e-3 * FIRST_DIP_SHIFT);
    if ks != FIRST_DIP_KS.collect::<Vec<_>>() || !shifts_match {
        return Err(ValidationError::Data {
            path,
            message: format!(
                "expected the starts k = {FIRST_DIP_KS:?} in order, shifted k × {FIRST_DIP_SHIFT:e} m"
            ),
        });
    }
    Ok(FirstDips {
        lowest: rows.iter().map(|r| r[2]).collect(),
        step: rows.iter().map(|r| r[3]).collect(),
    })
}

/// The checks of the first dip: both codes' mean lowest height and mean step of it over the
/// starts, and what the ensembles say about their spread.
///
/// Tolerances: the height to 5 %, about 2.6 standard errors of the difference of the two
/// means (each about 1.3 % of the mean, from blocks of starts); the step to 0.25 %, 15 steps,
/// about four standard errors of the difference (the starts spread by about 21 steps, each
/// mean's standard error is 2.5–3 steps).
pub(super) fn push_first_dip(report: &mut CaseReport, yade: &FirstDips, ours: &FirstDips) {
    let n = ours.lowest.len();
    report.checks.push(Check::relative(
        &format!(
            "first dip: lowest sphere height over the first {FIRST_DIP_STEPS} steps, mean over \
             {n} starts"
        ),
        "m",
        mean(&yade.lowest),
        mean(&ours.lowest),
        0.05,
        "YADE 2023.02a, the same starts",
    ));
    report.checks.push(Check::relative(
        "first dip: step of the lowest height, mean over the starts",
        "",
        mean(&yade.step),
        mean(&ours.step),
        0.0025,
        "YADE 2023.02a, the same starts",
    ));
    report.inform(
        &format!("first dip over {n} starts k·{FIRST_DIP_SHIFT:e} m higher (m)"),
        format!("flexdem {}; YADE {}", describe(&ours.lowest, 6), describe(&yade.lowest, 6)),
    );
    let apart = (mean(&ours.lowest) - mean(&yade.lowest))
        / block_standard_error(&ours.lowest).hypot(block_standard_error(&yade.lowest));
    report.inform(
        "first dip: flexdem's mean less YADE's, in standard errors of the difference",
        format!("{apart:+.2}"),
    );
    report.inform(
        "first dip: step of the lowest height (mean, standard deviation)",
        format!(
            "flexdem {:.1}, {:.1}; YADE {:.1}, {:.1}",
            mean(&ours.step),
            standard_deviation(&ours.step),
            mean(&yade.step),
            standard_deviation(&yade.step)
        ),
    );
}
