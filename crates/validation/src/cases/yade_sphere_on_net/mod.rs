//! `yade_sphere_on_net`: a sphere dropped on a net pinned at its corners, against YADE
//! 2023.02a (`validation/yade/sphere_on_net/`): the rest state of the reference run, the
//! contact forces at rest and the first dip over ensembles of starts.
//!
//! How a contact's force splits into normal and shear parts at rest is not set by the statics:
//! friction locks shear in during the bouncing transient, and which shear is chaotic in both
//! codes (a start 1e-10 m higher changes it). One run is one sample of it, so the forces are
//! compared as means over 100 starts in both codes ([`rest_ensemble`], YADE's
//! `sphere_on_net_rest_ensemble.py`), and the first dip as a mean over 200 starts
//! ([`first_dip`], YADE's `sphere_on_net_first_dip.py`). The 16 starts of YADE's
//! `sphere_on_net_ensemble.py` (the reference run among them) give the mean heights'
//! history.

mod first_dip;
mod plots;
mod rest_ensemble;
mod scene;
mod stats;

use super::yade_side_by_side::{json_number, read_csv_columns, read_json, yade_data_dir};
use crate::report::{CaseReport, Check, Context};
use crate::threads::on_all_threads;
use crate::ValidationError;
use first_dip::{
    flexdem_first_dips, push_first_dip, yade_first_dips, FIRST_DIP_KS, FIRST_DIP_SHIFT,
    FIRST_DIP_STEPS,
};
use flexdem_geom::{Real, Vec3};
use plots::{plot_history, plot_mean_history, plot_rest_shape};
use rayon::prelude::*;
use rest_ensemble::{flexdem_rest_ensemble, push_rest_forces, yade_rest_ensemble};
use scene::{
    rest_forces, run_net, spread, NetRun, RestForces, ENSEMBLE_KS, ENSEMBLE_SHIFT, NET_CELLS,
    NET_RADIUS, NET_SPACING, SPHERE_MASS, SPHERE_RADIUS,
};
use serde_json::Value;

/// The sphere on a net against YADE.
pub fn run_sphere_on_net(ctx: &Context) -> Result<CaseReport, ValidationError> {
    let dir = yade_data_dir().join("sphere_on_net");
    let summary_path = dir.join("sphere_on_net_summary.json");
    let summary = read_json(&summary_path)?;
    let number = |pointer: &str| json_number(&summary, pointer, &summary_path);
    let yade_sphere_z = number("/final/sphere_pos_final/2")?;
    let yade_centre_z = number("/final/centre_node_pos_final/2")?;
    let contacts = summary.pointer("/final/active_contacts_final").and_then(Value::as_array);
    let yade_fn: Vec<Real> = contacts
        .map(|list| list.iter().filter_map(|c| c.get("fn").and_then(Value::as_f64)).collect())
        .unwrap_or_default();
    if yade_fn.is_empty() {
        return Err(ValidationError::Data {
            path: summary_path,
            message: "no contact normal forces at /final/active_contacts_final".into(),
        });
    }
    let yade_nodes =
        read_csv_columns(&dir.join("sphere_on_net_final_nodes.csv"), &["i", "j", "x", "y", "z"])?;
    let ensemble_path = dir.join("sphere_on_net_ensemble.csv");
    let yade_ensemble = read_csv_columns(
        &ensemble_path,
        &["k", "fn_mean", "fs_mean", "min_sphere_z_history", "n_active"],
    )?;
    let yade_ks: Vec<i32> = yade_ensemble.iter().map(|r| r[0] as i32).collect();
    if yade_ks != ENSEMBLE_KS.collect::<Vec<_>>() {
        return Err(ValidationError::Data {
            path: ensemble_path,
            message: format!("starts k = {yade_ks:?}, expected {ENSEMBLE_KS:?}"),
        });
    }
    let dt = number("/dt")?;
    let max_steps = number("/final/steps")? as u64;

    // every start, in the order of k (the reference start, k = 0, among them)
    let runs: Vec<Result<NetRun, ValidationError>> = on_all_threads(|| {
        ENSEMBLE_KS
            .collect::<Vec<_>>()
            .into_par_iter()
            .map(|k| run_net(dt, max_steps, k as Real * ENSEMBLE_SHIFT))
            .collect()
    });
    let runs = runs.into_iter().collect::<Result<Vec<_>, _>>()?;
    let forces: Vec<RestForces> = runs.iter().map(rest_forces).collect();
    let reference = (0 - ENSEMBLE_KS.start()) as usize;
    let run = &runs[reference];
    let rest = forces[reference];
    let (sim, sphere, centre, grid) = (&run.sim, run.sphere, run.centre, &run.grid);
    let p = &sim.model().particles;
    let sphere_z = p.pos[sphere].z;
    let centre_z = p.pos[centre].z;
    let node_difference = yade_nodes
        .iter()
        .map(|row| {
            let q = p.pos[grid.node(row[0] as usize, row[1] as usize) as usize];
            (q - Vec3::new(row[2], row[3], row[4])).norm()
        })
        .fold(0.0, Real::max);
    let column = |rows: &[Vec<Real>], i: usize| rows.iter().map(|r| r[i]).collect::<Vec<_>>();
    let (yade_fn_ens, yade_fs_ens, yade_low_ens) =
        (column(&yade_ensemble, 1), column(&yade_ensemble, 2), column(&yade_ensemble, 3));
    let ours = |f: fn(&RestForces) -> Real| forces.iter().map(f).collect::<Vec<_>>();
    let (fn_ens, fs_ens, low_ens) = (ours(|f| f.normal), ours(|f| f.shear), ours(|f| f.lowest));

    let mut report = CaseReport::new("yade_sphere_on_net", "Sphere on a net against YADE 2023.02a");
    report.setup = format!(
        "The scene of `validation/yade/sphere_on_net/sphere_on_net.py` rebuilt in flexdem: a net of \
         {NET_CELLS} × {NET_CELLS} cells of {NET_SPACING} m (49 nodes, 84 links, r = {NET_RADIUS} m, \
         E = 1e8 Pa, ν = 0.3, ρ = 1000 kg/m³, friction 30°), flat at z = 0, the 4 corners pinned \
         (translations blocked, rotations free); a sphere r = {SPHERE_RADIUS} m of mass {SPHERE_MASS} \
         kg (E = 1e8 Pa, friction 30°) starting at rest touching the centre node from above; \
         g = 10 m/s², Cundall damping 0.3, dt = {dt:e} s as in YADE, `yade` link kinematics (YADE's \
         links, and for a contact on a link YADE's spin of the virtual sphere, moment shared \
         as node torques and non-ratcheting relative velocity), contact \
         kn = 2·E·r_s·E·r_c/(E·r_s + E·r_c), ks = 0.3·kn (eq 3–4, as YADE's FrictPhys). Run until \
         every speed stays below 1e-9 m/s at 10 successive outputs 1000 steps apart ({} steps; \
         YADE ran {max_steps}). The ensemble: the same run from {} starts k·{ENSEMBLE_SHIFT:e} m \
         higher, k = {}..{} (YADE: `sphere_on_net_ensemble.py`, the same starts). The first \
         dip: the sphere's lowest height over the first {FIRST_DIP_STEPS} steps, read at every \
         step, from {} starts k·{FIRST_DIP_SHIFT:e} m higher, k = {}..{} (YADE: \
         `sphere_on_net_first_dip.py`, the same starts).",
        run.steps,
        forces.len(),
        ENSEMBLE_KS.start(),
        ENSEMBLE_KS.end(),
        FIRST_DIP_KS.len(),
        FIRST_DIP_KS.start,
        FIRST_DIP_KS.end - 1,
    );
    report.checks.push(Check::relative(
        "sphere drop z0 − z",
        "m",
        run.z0 - yade_sphere_z,
        run.z0 - sphere_z,
        0.01,
        "YADE 2023.02a",
    ));
    report.checks.push(Check::relative(
        "centre node height",
        "m",
        yade_centre_z,
        centre_z,
        0.01,
        "YADE 2023.02a",
    ));
    let (yade_rest, ours_rest) = (yade_rest_ensemble(&dir)?, flexdem_rest_ensemble(dt, max_steps)?);
    push_rest_forces(&mut report, &yade_rest, &ours_rest);
    let (yade_dips, dips) = (yade_first_dips(&dir)?, flexdem_first_dips(dt)?);
    push_first_dip(&mut report, &yade_dips, &dips);
    report.checks.push(Check::absolute(
        "number of contacts carrying load",
        "",
        yade_fn.len() as Real,
        rest.count as Real,
        0.0,
        "YADE 2023.02a",
    ));
    let range = |x: &[Real], digits: usize| {
        let (mean, lo, hi) = spread(x);
        format!("mean {mean:.digits$}, {lo:.digits$} to {hi:.digits$}")
    };
    report.inform(
        "mean contact normal force over the 16 starts (N)",
        format!("flexdem {}; YADE {}", range(&fn_ens, 4), range(&yade_fn_ens, 4)),
    );
    report.inform(
        "mean contact shear force over the 16 starts (N)",
        format!("flexdem {}; YADE {}", range(&fs_ens, 4), range(&yade_fs_ens, 4)),
    );
    report.inform(
        "lowest sphere height at the outputs over the 16 starts (m)",
        format!("flexdem {}; YADE {}", range(&low_ens, 5), range(&yade_low_ens, 5)),
    );
    report.inform(
        "reference start: mean contact normal force",
        format!("flexdem {:.5} N, YADE {:.5} N", rest.normal, spread(&yade_fn).0),
    );
    report.inform(
        "reference start: energy balance error at rest, (B(t) − B(0)) / scale (YADE's pair does \
         not conserve energy; the beam pair's is tested in tests/energy.rs)",
        format!("{:.3e}", sim.energy_watch().relative_error(sim.energy())),
    );
    let support: Real = sim.contacts().iter().map(|c| c.forces.force_on_2.z.abs()).sum();
    report.inform("vertical contact force on the sphere (weight 10 N)", format!("{support:.6} N"));
    let centre_pos = p.pos[centre];
    for c in sim.contacts().iter().filter(|c| c.forces.normal_force > 0.0) {
        let f = c.forces.force_on_2;
        let normal_dir = (f - c.forces.shear_force).normalize();
        report.inform(
            "flexdem contact: distance from centre node, normal tilt, |Fs|, Fs_z",
            format!(
                "{:.5} m, {:.2}°, {:.4} N, {:.4} N",
                (c.point - centre_pos).norm(),
                normal_dir.z.abs().acos().to_degrees(),
                c.forces.shear_force.norm(),
                c.forces.shear_force.z
            ),
        );
    }
    report.inform("largest node position difference from YADE", format!("{node_difference:.3e} m"));
    plot_rest_shape(ctx, &mut report, run, &yade_nodes)?;
    plot_history(ctx, &mut report, run, &dir)?;
    plot_mean_history(ctx, &mut report, &runs, dt, &dir)?;
    let first_contact = |h: &[(Real, Real)]| {
        h.iter().find(|c| c.1 > 0.0).map_or("never".to_string(), |c| format!("{:.2} s", c.0))
    };
    let yade_history = read_csv_columns(
        &dir.join("sphere_on_net_history.csv"),
        &["time", "sphere_z", "n_contacts", "centre_node_z"],
    )?;
    let yade_contacts: Vec<(Real, Real)> = yade_history.iter().map(|r| (r[0], r[2])).collect();
    report.inform(
        "reference start: first output with a contact (every 1000 steps)",
        format!(
            "flexdem {}, YADE {}",
            first_contact(&run.contact_history),
            first_contact(&yade_contacts)
        ),
    );
    report.inform(
        "reference start: lowest sphere height at the outputs",
        format!(
            "flexdem {:.5} m, YADE {:.5} m",
            rest.lowest,
            number("/final/min_sphere_z_history")?
        ),
    );
    report.notes =
        "Tolerances: the rest state is set by the links' stiffness under the same total \
        load (weight of sphere and net), identical in both codes with the yade kinematics, and by \
        how each contact's force splits into normal and shear parts. The heights are checked to \
        1%. The split is not set by the statics: friction locks shear in while the sphere bounces \
        on the net, and which shear is chaotic in both codes: over 16 starts 1e-10 m apart YADE's \
        mean normal force per contact ranges as shown above (its reference run is one of them). \
        Over those 16 starts flexdem's mean moved by 1.4% (2.6274 to 2.5910 N; YADE 2.6298 N) \
        when the links' atan changed by one ulp (2026-12-05): 16 starts so alike are too few for \
        2%. So the normal force is checked as the mean over 100 starts 1e-8 m apart in both \
        codes, each run until at rest by the same criterion (YADE's \
        `sphere_on_net_rest_ensemble.py`), to 2% (YADE's starts spread about 2% about their \
        mean; the standard errors of both means are given above). The first dip, the sphere's \
        lowest height in its first impact, is chaotic too (a start 1e-10 m higher moves it by up \
        to 20%), so it is checked as the mean over 200 starts 1e-8 m apart in both codes \
        (YADE's `sphere_on_net_first_dip.py`), read at every step, to 5%: each mean's standard \
        error, from blocks of 10 neighbouring starts (neighbouring starts give correlated dips), \
        is about 1.3%, so 5% is about 2.6 standard errors of their difference. Its step is \
        checked to 0.25%: 15 steps, about four standard errors of the difference (the starts \
        spread by about 21 steps). Until 2026-12-05 the first dip was the mean of the lowest heights at the \
        outputs every 1000 steps over the 16 starts 1e-10 m apart, and it failed: flexdem \
        -0.01072 m against YADE's -0.01011 m, 6%. Those 16 starts are too few and too alike \
        for 5%: read at every step over 200 starts 1e-10 m apart, the means are -0.010558 m \
        (flexdem) and -0.010271 m (YADE), 2.8% apart, and the 16 of them give -0.010748 and \
        -0.010141 m; over 200 starts 1e-8 m apart, the check's ensemble, 1.3% apart (values \
        above). **The `yade` link kinematics are YADE's pair for a contact on a \
        link:** the virtual sphere spins with the axis at YADE's s × (v₂ − v₁) (the rigid rate \
        is s × (v₂ − v₁)/L², docs/model.md) and the contact's moment goes to the nodes as node \
        torques w·τ, as YADE's Law2_ScGridCoGeom_FrictPhys_CundallStrack does, and the \
        shear increment takes YADE's non-ratcheting relative velocity α(v₂ − v₁) − r₂ω₂×n − \
        r₁ω₁×n (the `beam` kinematics keep the exact spin, the contact point's velocity and \
        share the moment's perpendicular part as a force couple, which conserves energy; \
        YADE's pair does not). A single impact of a sliding sphere on a free three-node chain \
        then follows YADE to 1e-8 of the forces (the contact point's velocity: 3e-4 at the \
        second step of contact, 5 % of a node's lateral velocity after it). Measured step by step against \
        YADE's history written every step (2026-12-04): the first contact's shear force 0.6714 \
        N against YADE's 0.6716 (exact spin: 0.7734), the second bounce's forces within 0.3%, \
        the third's within 10% (the chatter that follows is sensitive to the nets' small \
        difference before the first contact: the centre node's height differs by 4.5e-12 m at \
        step 1000 and 1.8e-9 m at step 3000, relative 8e-10 and 3e-8, more than round-off; a \
        likely source, not tested, is the links' shear force, which YADE turns with the \
        contact to first order in the rotation each step and flexdem exactly). Over the 16 starts (means): exact spin \
        and force couple 2.747 N normal, 0.737 N shear, first dip -0.0212 m; YADE's spin with \
        the force couple 2.707 N, 0.564 N, -0.0102 m, but the sphere at rest on four sliding \
        contacts rocked at a growing amplitude (spin 1e-11 to 8e-4 rad/s from step 7 700; \
        YADE's stays at 1e-10); YADE's pair 2.611 N, 0.212 N, -0.0107 m; YADE 2.630 N, 0.250 \
        N, -0.0101 m; with the non-ratcheting velocity too 2.627 N, 0.292 N, -0.0107 m. \
        The ensembles' mean heights every 1000 steps over \
        the 16 starts (figure) agree before the first impact and part in it by 2-3 standard \
        errors of independent samples at the outputs; over 200 starts the first dips agree \
        within their standard errors, so this was the 16 starts' sampling."
            .into();
    Ok(report)
}
