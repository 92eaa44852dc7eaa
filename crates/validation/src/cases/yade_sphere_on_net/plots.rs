//! The case's figures: the rest shape, the reference start's heights, and the two
//! ensembles' mean heights.

use super::scene::{NetRun, ENSEMBLE_KS, NET_CELLS};
use crate::cases::yade_side_by_side::read_csv_columns;
use crate::plot::{plot_xy, Curve, CurveStyle, PlotSpec};
use crate::report::{CaseReport, Context, Figure};
use crate::ValidationError;
use flexdem_geom::Real;

/// The rest shape of the middle row of nodes in both codes.
pub(super) fn plot_rest_shape(
    ctx: &Context,
    report: &mut CaseReport,
    run: &NetRun,
    yade_nodes: &[Vec<Real>],
) -> Result<(), ValidationError> {
    let half = NET_CELLS / 2;
    let p = &run.sim.model().particles;
    let yade_row: Vec<(Real, Real)> = yade_nodes
        .iter()
        .filter(|row| row[1] as usize == half)
        .map(|row| (row[2], row[4]))
        .collect();
    let ours: Vec<(Real, Real)> = (0..=NET_CELLS)
        .map(|i| {
            let q = p.pos[run.grid.node(i, half) as usize];
            (q.x, q.z)
        })
        .collect();
    let file = "yade_sphere_on_net_profile.png";
    plot_xy(
        &ctx.out_dir.join(file),
        &PlotSpec {
            title: "Sphere on a net: nodes of the middle row (y = 0.3) at rest",
            x_label: "x (m)",
            y_label: "z (m)",
            curves: &[
                Curve::new("YADE 2023.02a", yade_row, CurveStyle::Line),
                Curve::new("flexdem (yade kinematics)", ours, CurveStyle::Points),
            ],
        },
    )?;
    report.figures.push(Figure {
        file: file.into(),
        caption: "Rest shape of the middle row of nodes: YADE (line) and flexdem (points).".into(),
    });
    Ok(())
}

/// The heights of the sphere and the centre node during the drop in both codes.
pub(super) fn plot_history(
    ctx: &Context,
    report: &mut CaseReport,
    run: &NetRun,
    dir: &std::path::Path,
) -> Result<(), ValidationError> {
    let yade_history = read_csv_columns(
        &dir.join("sphere_on_net_history.csv"),
        &["time", "sphere_z", "n_contacts", "centre_node_z"],
    )?;
    let t_end = run.history.last().map_or(0.0, |h| h.0).max(1.0);
    let yade = |column: usize| -> Vec<(Real, Real)> {
        yade_history.iter().map(|r| (r[0], r[column])).filter(|r| r.0 <= t_end).collect()
    };
    let file = "yade_sphere_on_net_history.png";
    plot_xy(
        &ctx.out_dir.join(file),
        &PlotSpec {
            title: "Sphere on a net: heights of the sphere's centre and the centre node",
            x_label: "time (s)",
            y_label: "z (m)",
            curves: &[
                Curve::new("YADE 2023.02a", yade(1), CurveStyle::Line),
                Curve::new("flexdem (yade kinematics)", run.history.clone(), CurveStyle::Dashed),
                Curve::new("YADE: centre node", yade(3), CurveStyle::Line),
                Curve::new("flexdem: centre node", run.centre_history.clone(), CurveStyle::Dashed),
            ],
        },
    )?;
    report.figures.push(Figure {
        file: file.into(),
        caption: "Heights of the sphere's centre and of the net's centre node during the drop \
                  (reference start): YADE (lines) and flexdem (dashed), every 1000 steps."
            .into(),
    });
    Ok(())
}

/// Outputs (every 1000 steps) over which the ensembles' mean heights are compared, as far as
/// `sphere_on_net_ensemble.py` writes them (100 000 steps).
const MEAN_HISTORY_OUTPUTS: usize = 100;

/// Mean and standard error over the starts of the sphere's height at each output:
/// `histories[start][output]`, as long as every start has it.
fn mean_history(histories: &[Vec<Real>]) -> Vec<(Real, Real)> {
    let outputs = histories.iter().map(Vec::len).min().unwrap_or(0);
    let n = histories.len() as Real;
    (0..outputs)
        .map(|i| {
            let mean = histories.iter().map(|h| h[i]).sum::<Real>() / n;
            let var = histories.iter().map(|h| (h[i] - mean).powi(2)).sum::<Real>() / (n - 1.0);
            (mean, (var / n).sqrt())
        })
        .collect()
}

/// The two ensembles' mean heights of the sphere during the drop, and how far apart they are
/// at the first dip and the rebound, in standard errors.
pub(super) fn plot_mean_history(
    ctx: &Context,
    report: &mut CaseReport,
    runs: &[NetRun],
    dt: Real,
    dir: &std::path::Path,
) -> Result<(), ValidationError> {
    let rows = read_csv_columns(
        &dir.join("sphere_on_net_ensemble_history.csv"),
        &["k", "step", "sphere_z"],
    )?;
    let mut yade: Vec<Vec<Real>> = Vec::new();
    for k in ENSEMBLE_KS {
        let mut h: Vec<(Real, Real)> =
            rows.iter().filter(|r| r[0] as i32 == k).map(|r| (r[1], r[2])).collect();
        h.sort_by(|a, b| a.0.total_cmp(&b.0));
        yade.push(h.into_iter().map(|(_, z)| z).collect());
    }
    // flexdem's histories start at step 0; YADE's at step 1000
    let ours: Vec<Vec<Real>> = runs
        .iter()
        .map(|r| r.history.iter().skip(1).take(MEAN_HISTORY_OUTPUTS).map(|h| h.1).collect())
        .collect();
    let (yade, ours) = (mean_history(&yade), mean_history(&ours));
    let at = |i: usize| (i + 1) as Real * 1000.0 * dt;
    let curve = |m: &[(Real, Real)]| m.iter().enumerate().map(|(i, v)| (at(i), v.0)).collect();
    let file = "yade_sphere_on_net_mean_history.png";
    plot_xy(
        &ctx.out_dir.join(file),
        &PlotSpec {
            title: "Sphere on a net: the sphere's height, mean over the 16 starts",
            x_label: "time (s)",
            y_label: "z (m)",
            curves: &[
                Curve::new("YADE 2023.02a", curve(&yade), CurveStyle::Line),
                Curve::new("flexdem (yade kinematics)", curve(&ours), CurveStyle::Dashed),
            ],
        },
    )?;
    report.figures.push(Figure {
        file: file.into(),
        caption: "The sphere's height every 1000 steps, mean over the same 16 starts in both \
                  codes: YADE (line) and flexdem (dashed)."
            .into(),
    });
    let apart = |step: usize| {
        let i = step / 1000 - 1;
        match (yade.get(i), ours.get(i)) {
            (Some(y), Some(f)) => format!(
                "step {step}: flexdem {:.5}, YADE {:.5} ({:+.1} standard errors)",
                f.0,
                y.0,
                (f.0 - y.0) / (f.1 * f.1 + y.1 * y.1).sqrt().max(Real::MIN_POSITIVE)
            ),
            _ => format!("step {step}: no data"),
        }
    };
    report.inform(
        "mean sphere height over the starts (m)",
        [5000, 6000, 11_000, 15_000].map(apart).join("; "),
    );
    Ok(())
}
