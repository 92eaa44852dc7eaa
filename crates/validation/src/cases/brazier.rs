//! Validation case 15 (paper §6): Brazier buckling of a PFacet tube under an end moment.
//!
//! A tube of PFacets is first pulled (tension test: axial membrane stiffness C and Poisson
//! ratio ν of its wall), then bent by a moment M raised slowly at its free end until the
//! cross-section ovalises and the tube collapses (Brazier 1927), compared with eq 18
//! `M_max = 2√2·K_n·d / (9(1 − ν²))`. After the collapse the moment is held and the tube winds
//! onto itself; the final state is checked for self-penetration.
//!
//! The tube, its boundary conditions and measurements are in [`tube`]; the loading protocol
//! in [`loading`]; the analytic stiffness of the PFacet lattice in [`lattice`].

mod lattice;
mod loading;
mod tube;

pub use lattice::{brazier_moment, brazier_path, eq18_moment, BrazierPoint, LatticeStiffness};
pub use loading::{bend, tension_test, BendingResult, Protocol, TensionResult};
pub use tube::{min_self_distance, TubeCase};

use crate::plot::{plot_xy, Curve, CurveStyle, PlotSpec};
use crate::report::{CaseReport, Check, Context, Figure};
use crate::ValidationError;
use flexdem_geom::Real;
use std::f64::consts::PI;

/// Tolerance of the tension-test stiffness against the truss model of the lattice: the beam
/// links' bending (12EI/L³ against EA/L, a relative 3r²/L² ≈ 0.8 %) and the end rings stiffen
/// the measured wall a little.
const STIFFNESS_TOL: Real = 0.03;
/// Tolerance of the buckling moment against eq 18 (validation.md case 15).
const BUCKLING_TOL: Real = 0.10;
/// Tolerance of the initial bending stiffness against the one the tension test predicts.
const BENDING_TOL: Real = 0.03;
/// Energy balance error during the post-buckling winding, over the energy scale.
const WINDING_ENERGY_TOL: Real = 1e-2;
/// Self-penetration after winding beyond the largest contact overlap F_n/k_n, as a fraction
/// of the wall thickness 2r: a deeper one would be a pair the contact detection missed.
const UNEXPLAINED_PENETRATION: Real = 0.1;

/// Runs the case: tension test, bending to buckling (full run) or to half of eq 18's moment
/// (quick run), post-buckling winding and the self-contact check (full run).
pub fn run(ctx: &Context) -> Result<CaseReport, ValidationError> {
    let protocol = if ctx.quick { Protocol::quick() } else { Protocol::full() };
    run_tube(ctx, &TubeCase::default(), &protocol)
}

/// Runs the case on `tube` with `protocol` (see [`run`]).
pub fn run_tube(
    ctx: &Context,
    tube: &TubeCase,
    protocol: &Protocol,
) -> Result<CaseReport, ValidationError> {
    let tube = *tube;
    let mut report = CaseReport::new("brazier", "Brazier buckling of a PFacet tube (paper §6)");
    let lattice = LatticeStiffness::of(&tube);

    let tension = tension_test(&tube)?;
    let k_n = PI * tube.radius * tension.membrane_stiffness;
    let d = 2.0 * tube.node_radius;
    let m18 = eq18_moment(k_n, tension.poisson, d);
    let m_lattice = brazier_moment(tube.radius, tension.membrane_stiffness, lattice.ring_bending);
    let bending = bend(&tube, protocol, m18, Some(&ctx.out_dir))?;

    report.setup = setup_text(&tube, protocol, &lattice, &tension, m18, bending.dt);
    report.checks.push(Check::relative(
        "axial membrane stiffness C (tension test)",
        "N/m",
        lattice.axial,
        tension.membrane_stiffness,
        STIFFNESS_TOL,
        "truss model of the lattice: C = E·πr²/a",
    ));
    let section_stiffness = tension.membrane_stiffness * tube.chord() * tube.ring_inertia_sum();
    report.checks.push(Check::relative(
        "initial bending stiffness M/φ",
        "N·m/rad",
        section_stiffness / tube.length,
        bending.initial_stiffness,
        BENDING_TOL,
        "C·a·Σy²/L from the tension test",
    ));
    if let Some(m_buckle) = bending.buckling_moment {
        report.checks.push(Check::relative(
            "buckling moment",
            "N·m",
            m18,
            m_buckle,
            BUCKLING_TOL,
            "eq 18 with K_n = πRC, ν from the tension test",
        ));
    } else if !ctx.quick {
        report.checks.push(Check::relative(
            "buckling moment",
            "N·m",
            m18,
            Real::NAN,
            BUCKLING_TOL,
            "eq 18 (the tube did not buckle)",
        ));
    }
    if let Some(final_state) = &bending.final_state {
        let penetration = d - final_state.min_distance;
        report.checks.push(Check::absolute(
            "self-penetration not carried by a contact: (2r − min distance) − max F_n/k_n",
            "m",
            0.0,
            (penetration - final_state.largest_overlap).max(0.0),
            UNEXPLAINED_PENETRATION * d,
            "contact law eq 1 (δ = F_n/k_n): no missed self-contact",
        ));
        report.checks.push(Check::absolute(
            "energy balance error during the winding, max |B(t) − B(start)| / energy scale",
            "",
            0.0,
            final_state.balance_error,
            WINDING_ENERGY_TOL,
            "energy conservation (the end moment's work counted), issue: ≤ 1e-2",
        ));
        report.inform(
            "self-penetration 2r − min distance node–PFacet at the end",
            format!("{penetration:.4e} m ({:.3}·2r)", penetration / d),
        );
        report.inform("self-contacts at the end", final_state.contacts.to_string());
        report.inform(
            "min distance node–PFacet (non-neighbours) at the end",
            format!("{:.4e} m ({:.3}·2r)", final_state.min_distance, final_state.min_distance / d),
        );
        report.inform("end rotation at the end", format!("{:.3} rad", final_state.rotation));
        report.inform(
            "min distance node–PFacet during the winding",
            format!(
                "{:.4e} m ({:.3}·2r)",
                final_state.min_distance_during,
                final_state.min_distance_during / d
            ),
        );
        report.inform(
            "largest contact overlap F_n/k_n at the end",
            format!(
                "{:.4e} m ({:.3}·2r)",
                final_state.largest_overlap,
                final_state.largest_overlap / d
            ),
        );
    }
    inform_values(
        &mut report,
        &tension,
        &bending,
        k_n,
        m18,
        m_lattice,
        &lattice,
        (tube.radius, tube.length),
    );
    let path = brazier_path(
        tube.radius,
        tension.membrane_stiffness,
        lattice.ring_bending,
        section_stiffness,
        60,
    );
    report.figures = plots(ctx, &bending, m18, &path, tube.length)?;
    if let Some(vtk) = &bending.vtk_file {
        report.inform("final state (ParaView)", vtk.clone());
    }
    let missed = bending
        .final_state
        .as_ref()
        .is_some_and(|f| (d - f.min_distance) - f.largest_overlap > UNEXPLAINED_PENETRATION * d);
    report.notes = notes_text(m18, m_lattice, &bending, missed);
    Ok(report)
}

/// The measured values shown besides the checks.
fn inform_values(
    report: &mut CaseReport,
    tension: &TensionResult,
    bending: &BendingResult,
    k_n: Real,
    m18: Real,
    m_lattice: Real,
    lattice: &LatticeStiffness,
    (radius, length): (Real, Real),
) {
    report.inform("Poisson ratio ν (ring contraction)", format!("{:.4}", tension.poisson));
    report.inform("Poisson ratio of the truss model", format!("{:.4}", lattice.poisson));
    report.inform("K_n = πRC", format!("{k_n:.4} N"));
    report.inform("M_max eq 18", format!("{m18:.4} N·m"));
    report
        .inform("M_max Brazier with the lattice's ring stiffness D", format!("{m_lattice:.4} N·m"));
    if let Some(m) = bending.last_stable_moment {
        report.inform(
            "last moment held in equilibrium",
            format!("{m:.4} N·m ({:.3}·eq 18)", m / m18),
        );
    }
    if let Some(m) = bending.buckling_moment {
        report.inform("buckling moment / eq 18", format!("{:.4}", m / m18));
        report.inform("buckling moment / lattice Brazier", format!("{:.4}", m / m_lattice));
    }
    if let Some(x) = bending.collapse_position {
        report.inform(
            "collapse at (most ovalised ring when buckling is detected)",
            format!("x/L = {x:.2}"),
        );
    }
    if let Some(p) = bending.stable_state {
        let kappa = p.rotation / length;
        let zeta = tension.membrane_stiffness * radius.powi(4) * kappa * kappa
            / (12.0 * lattice.ring_bending);
        report.inform(
            "last stable state: φ, Dmax/Dmin at mid-length, Brazier's (1 + ζ)/(1 − ζ) at κ = φ/L",
            format!(
                "{:.4} rad, {:.4}, {:.4}",
                p.rotation,
                p.ovalisation,
                (1.0 + zeta) / (1.0 - zeta)
            ),
        );
    }
    if let Some(m) = bending.nonlinear_moment {
        report.inform("non-linearity detected at", format!("{m:.4} N·m ({:.3}·eq 18)", m / m18));
    }
    report.inform(
        "max kinetic/elastic energy during the ramp",
        format!("{:.3e}", bending.ramp_energy_ratio),
    );
    if let Some((slow, diff)) = bending.rate_check {
        report.inform(
            "ramp-rate check: end rotation at the detection moment, half rate vs rate",
            format!("{slow:.5} rad, relative difference {diff:.2e}"),
        );
    }
    report.inform("steps", bending.steps.to_string());
}

/// Moment–rotation and ovalisation–moment plots, the simulation up to 1.5 times the larger of
/// the last stable rotation and Brazier's limit rotation (the post-buckling rotations, of
/// several radians, are reported as values), against Brazier's path with the lattice's D.
fn plots(
    ctx: &Context,
    bending: &BendingResult,
    m18: Real,
    path: &[BrazierPoint],
    length: Real,
) -> Result<Vec<Figure>, ValidationError> {
    let stable = bending.stable_state.map_or(0.0, |p| p.rotation);
    let limit = path.last().map_or(0.0, |p| p.curvature * length);
    let cut = 1.5 * stable.max(limit);
    let shown: Vec<_> = bending.curve.iter().filter(|p| p.rotation.abs() <= cut).collect();
    let moment_rotation = [
        Curve::new(
            "simulation",
            shown.iter().map(|p| (p.rotation, p.moment)).collect(),
            CurveStyle::Line,
        ),
        Curve::new("eq 18", vec![(0.0, m18), (cut, m18)], CurveStyle::Dashed),
        Curve::new(
            "Brazier, lattice D",
            path.iter().map(|p| (p.curvature * length, p.moment)).collect(),
            CurveStyle::Dashed,
        ),
    ];
    let file_mr = "brazier_moment_rotation.png".to_string();
    plot_xy(
        &ctx.out_dir.join(&file_mr),
        &PlotSpec {
            title: "Brazier: end moment against end rotation",
            x_label: "end rotation (rad)",
            y_label: "moment (N m)",
            curves: &moment_rotation,
        },
    )?;
    let ratio = |zeta: Real| (1.0 + zeta) / (1.0 - zeta);
    let oval = [
        Curve::new(
            "simulation, mid-length ring",
            shown.iter().map(|p| (p.moment, p.ovalisation)).collect(),
            CurveStyle::Points,
        ),
        Curve::new(
            "Brazier, lattice D",
            path.iter().map(|p| (p.moment, ratio(p.ovalisation))).collect(),
            CurveStyle::Dashed,
        ),
    ];
    let file_ov = "brazier_ovalisation.png".to_string();
    plot_xy(
        &ctx.out_dir.join(&file_ov),
        &PlotSpec {
            title: "Brazier: ovalisation of the mid-length ring",
            x_label: "moment (N m)",
            y_label: "Dmax/Dmin",
            curves: &oval,
        },
    )?;
    Ok(vec![
        Figure {
            file: file_mr,
            caption: "End moment against end rotation (ramp, holds, onset of the collapse), \
                      eq 18's M_max and Brazier's path M = EI·κ(1 − (κ/κ*)²/3), κ = φ/L, \
                      with the lattice's ring-bending stiffness D (dashed)."
                .into(),
        },
        Figure {
            file: file_ov,
            caption: "Ovalisation (largest over smallest diameter) of the mid-length ring \
                      against the moment, and Brazier's (1 + ζ)/(1 − ζ) with \
                      ζ = CR⁴κ²/(12D) (dashed)."
                .into(),
        },
    ])
}

/// The setup section: geometry, materials, loading, what K_n means.
fn setup_text(
    tube: &TubeCase,
    protocol: &Protocol,
    lattice: &LatticeStiffness,
    tension: &TensionResult,
    m18: Real,
    dt: Real,
) -> String {
    format!(
        "Tube (`builders::tube`): radius R = {r} m, length L = {l} m (L/R = {lr:.0}), {m} nodes \
         around × {k} segments along (cell a = {a:.4} m around × b = {b:.4} m along, one diagonal \
         per cell), node/PFacet radius r = {nr} m (wall thickness d = 2r = {d} m). Material E = \
         {e:.3e} Pa, ν = {nu}, ρ = {rho} kg/m³, friction angle {phi} rad, beam links (`Beam` \
         mode), no gravity, Cundall damping λ = {lambda}, dt = {dt:.3e} s (auto, safety 0.5).\n\n\
         Boundary conditions (paper §6): the nodes of the ring at x = 0 are blocked along x only; \
         to remove the remaining rigid-body motion one of them is also blocked along y and z and \
         the opposite one along y (stops translation in y, z and rotation about x, leaves the \
         ring free to ovalise). On the ring at x = L, node forces \
         f_k = M·ẑ × (p_k − p̄)/Σ|(p_k − p̄)⊥ẑ|², recomputed every step from the current \
         positions: Σf_k = 0 and Σ(p_k − p̄) × f_k has z-component M; in the initial state \
         f_k = −M·y_k/Σy_k² x̂, the paper's distribution linear in y.\n\n\
         **Tension test**: the same tube and supports, a total axial force F = {f:.4} N shared \
         by the nodes of the ring at x = L, ramped and held to rest. C = (F/2πR)/ε (force per \
         unit circumference over strain, ε between the rings at L/4 and 3L/4), ν = −ε_θ/ε with \
         ε_θ the change of the mean radius of the mid-length ring.\n\n\
         **What K_n must be.** Eq 18 is a moment, so K_n·d must be N·m: K_n is a force (a \
         stiffness per unit strain). Brazier's limit for a shell of axial membrane stiffness \
         C (N/m) and ring-bending stiffness D (N·m) is M = (2√2π/9)·R·√(12·C·D) \
         (energy ½πR³Cκ²(1 − 3ζ/2) + 9πDζ²/(2R) minimised over the ovalisation ζ, then \
         max over κ: ζ = 2/9). For a continuous shell of thickness d, C = E·d and \
         D = E·d³/(12(1 − ν²)), giving Brazier's (2√2/9)·π·E·R·d²/√(1 − ν²); eq 18 is the \
         same with **K_n = π·R·C** (the tension stiffness of half the tube, πR·E·d) up to \
         (1 − ν²) where Brazier has √(1 − ν²) (identical for ν = 0). With C from the tension \
         test and ν = {nu_t:.4}: eq 18 gives M_max = {m18:.4} N·m.\n\n\
         Analytic lattice (pin-jointed truss of the links, EA = Eπr²): C = EA/a = {c:.4} N/m, \
         ν = {nu_l:.3} (one diagonal per cell: under axial tension only the axial bars are \
         loaded and the tube twists freely); ring-bending stiffness of the lattice \
         D = [EI·a + c(EI·sin⁴θ + GJ·sin²θcos²θ)]/(ab) = {dd:.4e} N·m (ring bars and \
         diagonals, θ the diagonal's angle to the axis), against E·d³/12 = {dc:.4e} N·m \
         for a plate of thickness 2r.\n\n\
         **Bending**: M ramped at {rate:.3e} N·m/s (ramp to eq 18 over {ramp_periods} periods \
         of the slowest mode) until the secant stiffness M/φ drops {nl:.0} % below its initial \
         value (non-linearity); then raised in steps of {step:.0} % of eq 18, each held \
         until the end rotation changes by less than {conv:.0e} (relative) over a tenth \
         of a period; buckling is the first step whose rotation still grows after \
         {hold} periods (or grows by {runaway:.0} %). After buckling the moment is held for \
         {post} periods (winding, self-contact). φ is the rotation about z of the end ring's \
         normal, ovalisation the ratio of the largest to the smallest of the {half} diameters \
         of the mid-length ring.",
        r = tube.radius,
        l = tube.length,
        lr = tube.length / tube.radius,
        m = tube.n_around,
        k = tube.n_along,
        a = tube.chord(),
        b = tube.length / tube.n_along as Real,
        nr = tube.node_radius,
        d = 2.0 * tube.node_radius,
        e = tube.young,
        nu = tube.poisson,
        rho = tube.density,
        phi = tube.friction_angle,
        lambda = tube.damping,
        f = tension.force,
        nu_t = tension.poisson,
        c = lattice.axial,
        nu_l = lattice.poisson,
        dd = lattice.ring_bending,
        dc = tube.young * (2.0 * tube.node_radius).powi(3) / 12.0,
        rate = bending_rate(protocol, m18, tube),
        ramp_periods = protocol.ramp_periods,
        nl = protocol.nonlinear_drop * 100.0,
        step = protocol.moment_step * 100.0,
        conv = protocol.convergence,
        hold = protocol.max_hold_periods,
        runaway = protocol.runaway * 100.0,
        post = protocol.post_periods,
        half = tube.n_around / 2,
    )
}

/// The ramp rate of the bending protocol (N·m/s).
fn bending_rate(protocol: &Protocol, m18: Real, tube: &TubeCase) -> Real {
    m18 / (protocol.ramp_periods * tube.slowest_period())
}

/// Notes: what the numbers mean, why eq 18 and the lattice's Brazier limit differ, and what
/// the measured collapse is.
fn notes_text(m18: Real, m_lattice: Real, bending: &BendingResult, missed: bool) -> String {
    let mut notes = format!(
        "Eq 18 assumes a continuous wall of thickness d = 2r. The PFacet lattice has its own \
         ring-bending stiffness D (links of circular section, EI = Eπr⁴/4, plus the torsion of \
         the diagonals), not C·d²/12: Brazier's limit with the lattice's D is {m_lattice:.4} N·m, \
         {:.1} % above eq 18. The measured buckling moment is compared with eq 18 as the paper \
         does. The moment is held in equilibrium at each step (Cundall damping does not change \
         equilibria), so the buckling moment does not depend on the ramp rate; its resolution is \
         the moment step.\n\nSelf-contact: after the collapse the tube winds onto itself and \
         the folds press its walls together. Contacts are linear springs (eq 1, k_n = E·r for \
         two PFacets), so a fold carrying a large force overlaps by F_n/k_n, here a sizeable \
         fraction of the wall thickness 2r. The check therefore compares the deepest \
         node–PFacet penetration with the largest overlap the contact law needs for its force: \
         a penetration beyond it would be a self-contact the detection missed. Until 2026-12 \
         one was: a node resting on a fold lost its contact whenever an element holding it \
         reached deeper into the other fold an element's length away, and nodes sank through \
         the walls (the end turned 84.7 rad through the tube's own walls, with the winding's \
         balance off by 6.1e-2). A touching is now one place (docs/model.md §2), and until \
         2026-12-02 walls still sank into each other behind the overlap offsets that keep a \
         handed-over contact's force continuous, kept for the contact's life, and where \
         PFacets intersect (their distance is 0 however deep): the offsets are now given \
         back over 50 steps with their energy booked, and the overlap of intersecting faces \
         follows their motion (docs/model.md §1, §2).",
        (m_lattice / m18 - 1.0) * 100.0
    );
    if let Some(end) = &bending.final_state {
        notes.push_str(&format!(
            " Here the folds press together and hold: the end rotation is {:.1} rad after \
             the winding, with {} self-contacts.",
            end.rotation, end.contacts
        ));
    }
    if missed {
        notes.push_str(
            "\n\n**Why the check of no missed self-contact fails.** The winding is chaotic \
             (round-off changes its path) and the check passes in some runs and fails in others \
             (docs/model.md §2). Where it fails, the deepest node is where the PFacets holding \
             it cross another PFacet (the face–face distance is 0 however deep they are, the \
             limit of docs/model.md §1), and most self-contacts carry overlap offsets from \
             hand-overs (§2), so their forces are below what their depths ask. Open (issue 12).",
        );
    }
    match (bending.buckling_moment, bending.collapse_position) {
        (Some(m), Some(x)) if (m / m18 - 1.0).abs() > BUCKLING_TOL => notes.push_str(&format!(
            "\n\n**Why the buckling check fails.** Up to the collapse the tube follows \
             Brazier's path computed with the lattice's D (moment–rotation and ovalisation \
             plots): the ovalisation mechanism is reproduced. But it collapses at \
             {:.3}·eq 18 ({:.3} of the lattice's own Brazier limit), by a sudden local \
             buckle that starts at the loaded free end (most ovalised ring at x/L = {x:.2} \
             when the hold fails), not at Brazier's limit point, where dM/dκ = 0 and the \
             ovalisation would reach 2/9. A finer mesh makes it earlier, not later: 24 × 30 \
             cells (same R, L, r) buckle at 0.825·eq 18 (0.761 of its lattice Brazier \
             limit) against {:.3} here, so the gap is not a discretisation error that \
             vanishes with refinement. Neither is it the ramp rate (equilibrium holds) nor the \
             detection (the rotation jumps from about 0.1 rad to several radians within a \
             tenth of a period). The paper's \"close to the theoretical limit\" is not \
             reproduced within 10 % with this loading: the end ring, loaded by \
             concentrated node forces and free to warp, is the weak point.",
            m / m18,
            m / m_lattice,
            m / m18,
        )),
        (None, _) => notes.push_str(
            " The run stopped before buckling (quick run: tension test and the linear range of \
             bending only).",
        ),
        _ => {}
    }
    notes
}
