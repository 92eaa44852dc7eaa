//! Viscous contact damping (model.md §7) against known answers: the coefficient of
//! restitution and the contact duration of normal impacts (a sphere on a wall, two spheres
//! head on) for the clamped linear spring–dashpot, computed analytically; the energy balance
//! of oblique impacts with tangential dashpots and friction, and of a damped column settling
//! under gravity in a box.

use flexdem_contact::{damping_ratio, restitution_of_ratio, ContactDamping, Material};
use flexdem_elements::Model;
use flexdem_geom::{Real, Vec3};
use flexdem_integrate::{Settings, Simulation, TimeStep};
use std::f64::consts::PI;

const R: Real = 0.01;
const YOUNG: Real = 1e8;
const RHO: Real = 2650.0;

fn sphere_mass() -> Real {
    4.0 / 3.0 * PI * R.powi(3) * RHO
}

fn material(damping: ContactDamping, friction_deg: Real) -> Material {
    Material::new(YOUNG, 0.3, RHO, friction_deg.to_radians()).unwrap().with_damping(damping)
}

/// The clamped linear spring–dashpot `m·δ̈ = −max(kn·δ + cn·δ̇, 0)` from δ = 0, δ̇ = v0 > 0,
/// solved exactly (model.md §7): with `ωd = ω0·√(1 − ζ²)` and `ψ = arccos ζ`, the force
/// `∝ sin(2ψ − ωd·t)` vanishes at `ωd·t = 2ψ`; the bodies then part at the speed
/// `v0·exp(−ζ·ω0·t)` and the overlap closes `sin(2ψ)/ωd` later without force.
#[derive(Debug)]
struct Clamped {
    /// The time the force lasts, `2ψ/ωd` (s).
    force_duration: Real,
    /// The time the bodies overlap, `(2ψ + sin 2ψ)/ωd` (s).
    overlap_duration: Real,
    /// `exp(−2ζ·ψ/√(1 − ζ²))`.
    restitution: Real,
}

fn clamped(zeta: Real, omega0: Real) -> Clamped {
    let s = (1.0 - zeta * zeta).sqrt();
    let wd = omega0 * s;
    let psi = zeta.acos();
    Clamped {
        force_duration: 2.0 * psi / wd,
        overlap_duration: (2.0 * psi + (2.0 * psi).sin()) / wd,
        restitution: (-2.0 * zeta * psi / s).exp(),
    }
}

/// What a normal impact measured.
#[derive(Debug)]
struct Impact {
    restitution: Real,
    force_duration: Real,
    overlap_duration: Real,
    /// (balance at the end − balance after the first step) / initial kinetic energy.
    balance_error: Real,
    /// What the contact dashpots dissipated over the kinetic energy lost.
    dashpot_share: Real,
}

/// A sphere at speed `v` onto a wall (`spheres = false`) or two spheres at ±v head on, all of
/// `m`; steps of `dt`.
fn normal_impact(m: Material, spheres: bool, v: Real, dt: Real) -> Impact {
    let mut model = Model::new();
    let mat = model.add_material(m).unwrap();
    let gap0 = 1e-5;
    if spheres {
        let a = model.add_sphere(Vec3::new(-R - gap0, 0.0, 0.0), R, mat).unwrap();
        let b = model.add_sphere(Vec3::new(R + gap0, 0.0, 0.0), R, mat).unwrap();
        model.particles.vel[a as usize] = Vec3::new(v, 0.0, 0.0);
        model.particles.vel[b as usize] = Vec3::new(-v, 0.0, 0.0);
    } else {
        model.add_wall(Vec3::zeros(), Vec3::x(), mat).unwrap();
        let a = model.add_sphere(Vec3::new(R + 2.0 * gap0, 0.0, 0.0), R, mat).unwrap();
        model.particles.vel[a as usize] = Vec3::new(-v, 0.0, 0.0);
    }
    let settings = Settings { time_step: TimeStep::Fixed(dt), ..Settings::default() };
    let mut sim = Simulation::new(model, settings).unwrap();
    let gap = |s: &Simulation| {
        let p = &s.model().particles.pos;
        if spheres {
            (p[1] - p[0]).x - 2.0 * R
        } else {
            p[0].x - R
        }
    };
    let speed = |s: &Simulation| {
        let vel = &s.model().particles.vel;
        if spheres {
            (vel[1] - vel[0]).x / (2.0 * v)
        } else {
            vel[0].x / v
        }
    };
    let kinetic = if spheres { sphere_mass() * v * v } else { 0.5 * sphere_mass() * v * v };
    let (mut start, mut end) = (None, None);
    let mut pushing = 0u64;
    let mut prev = gap(&sim);
    while end.is_none() {
        sim.step().unwrap();
        assert!(sim.steps() < 1_000_000, "no rebound");
        // the force at the start of the step just done
        if sim.contacts().iter().any(|c| c.forces.normal_force > 0.0) {
            pushing += 1;
        }
        let g = gap(&sim);
        let t_cross = sim.time() - sim.dt() * g / (g - prev);
        if prev > 0.0 && g <= 0.0 {
            start = Some(t_cross);
        } else if prev <= 0.0 && g > 0.0 && start.is_some() {
            end = Some(t_cross);
        }
        prev = g;
    }
    sim.run(5).unwrap();
    let e = sim.energy();
    Impact {
        restitution: speed(&sim),
        force_duration: pushing as Real * dt,
        overlap_duration: end.unwrap() - start.unwrap(),
        balance_error: (e.balance() - sim.energy_watch().initial_balance) / kinetic,
        dashpot_share: e.contact_damping / (kinetic - e.stored()),
    }
}

/// `|a/b − 1| ≤ tol`.
fn within(a: Real, b: Real, tol: Real) -> bool {
    (a / b - 1.0).abs() <= tol
}

/// Normal impacts with `restitution = e`: the measured restitution and durations match the
/// clamped model's within 1 % (they are not e and π/ωd: the clamp ends the force early).
#[test]
fn restitution_and_duration_of_normal_impacts() {
    let m = sphere_mass();
    let kn = YOUNG * R; // eq 3 for equal radii, and for a wall (the sphere's radius)
    for spheres in [false, true] {
        let m_eff = if spheres { 0.5 * m } else { m };
        let omega0 = (kn / m_eff).sqrt();
        for e in [0.9, 0.5, 0.1] {
            let zeta = damping_ratio(e);
            let expected = clamped(zeta, omega0);
            let unclamped = PI / (omega0 * (1.0 - zeta * zeta).sqrt());
            let dt = unclamped / 2000.0;
            let got =
                normal_impact(material(ContactDamping::Restitution(e), 30.0), spheres, 0.5, dt);
            println!(
                "{} e = {e}: ζ = {zeta:.4}, restitution {:.5} (clamped model {:.5}, unclamped {e}), \
                 force {:.4e} s (clamped {:.4e}), overlap {:.4e} s (clamped {:.4e}, π/ωd {:.4e}), \
                 balance error {:.1e}, dashpots {:.6} of the loss",
                if spheres { "two spheres" } else { "sphere on a wall" },
                got.restitution,
                expected.restitution,
                got.force_duration,
                expected.force_duration,
                got.overlap_duration,
                expected.overlap_duration,
                unclamped,
                got.balance_error,
                got.dashpot_share,
            );
            assert!(within(got.restitution, expected.restitution, 0.01), "{e}: {got:?}");
            assert!(within(got.force_duration, expected.force_duration, 0.01), "{e}: {got:?}");
            assert!(within(got.overlap_duration, expected.overlap_duration, 0.01), "{e}: {got:?}");
            assert!(got.balance_error.abs() < 1e-9, "{e}: {got:?}");
            assert!(within(got.dashpot_share, 1.0, 1e-6), "{e}: {got:?}");
        }
    }
}

/// The same with LAMMPS's rates per unit mass: cn = m_eff·γn, so one γn gives a wall impact
/// (m_eff = m) and a head-on impact (m_eff = m/2) different damping ratios,
/// ζ = γn·√(m_eff/kn)/2.
#[test]
fn restitution_of_normal_impacts_with_rates_per_unit_mass() {
    let m = sphere_mass();
    let kn = YOUNG * R;
    for gamma_n in [300.0, 3000.0, 12000.0] {
        for spheres in [false, true] {
            let m_eff = if spheres { 0.5 * m } else { m };
            let omega0 = (kn / m_eff).sqrt();
            let zeta = gamma_n * (m_eff / kn).sqrt() / 2.0;
            assert!(zeta < 1.0);
            let expected = clamped(zeta, omega0);
            let dt = PI / omega0 / 2000.0;
            let damping = ContactDamping::Viscous { gamma_n, gamma_t: 0.0 };
            let got = normal_impact(material(damping, 30.0), spheres, 0.5, dt);
            println!(
                "γn = {gamma_n} /s, {}: ζ = {zeta:.4}, restitution {:.5} (clamped model {:.5}, \
                 unclamped exp(−πζ/√(1−ζ²)) = {:.5}), balance error {:.1e}",
                if spheres { "two spheres" } else { "sphere on a wall" },
                got.restitution,
                expected.restitution,
                restitution_of_ratio(zeta),
                got.balance_error,
            );
            assert!(within(got.restitution, expected.restitution, 0.01), "{gamma_n}: {got:?}");
            assert!(within(got.force_duration, expected.force_duration, 0.01), "{got:?}");
            assert!(got.balance_error.abs() < 1e-9, "{gamma_n}: {got:?}");
        }
    }
}

/// A material whose restitution is 1 has no dashpot: its runs are bit-identical to those of a
/// material without damping (the engine's damped path with zero dashpots).
#[test]
fn restitution_one_is_the_undamped_contact_bit_for_bit() {
    let dt = 1e-6;
    let run = |d: ContactDamping| {
        let got = normal_impact(material(d, 30.0), true, 0.5, dt);
        format!("{got:?}")
    };
    assert_eq!(run(ContactDamping::Restitution(1.0)), run(ContactDamping::None));
}

/// (balance − balance after the first step) / `scale` after running `sim` for `steps`.
fn balance_error(sim: &mut Simulation, steps: u64, scale: Real) -> Real {
    sim.run(steps).unwrap();
    (sim.energy().balance() - sim.energy_watch().initial_balance) / scale
}

/// An oblique impact of a sphere on a wall (50° from the normal, a little sideways, spinning
/// unless `rotations` are blocked) or of two spheres off-centre (one spinning), with steps of
/// `tc/500`: the balance error over the energy at the start.
fn oblique_impact(mat: Material, on_wall: bool, rotations: bool) -> (Real, Real) {
    let m = sphere_mass();
    let inertia = 0.4 * m * R * R;
    let tc = PI * (m / (YOUNG * R)).sqrt();
    let mut model = Model::new();
    let id = model.add_material(mat).unwrap();
    let (v, w) = if on_wall {
        model.add_wall(Vec3::zeros(), Vec3::z(), id).unwrap();
        model.add_sphere(Vec3::new(0.0, 0.0, R + 1e-5), R, id).unwrap();
        let a = 50f64.to_radians();
        (Vec3::new(0.5 * a.sin(), 0.1, -0.5 * a.cos()), Vec3::new(20.0, -40.0, 30.0))
    } else {
        model.add_sphere(Vec3::new(2.0 * R * 0.8, 2.0 * R * 0.6, 0.0) * 1.0005, R, id).unwrap();
        model.add_sphere(Vec3::zeros(), R, id).unwrap();
        (Vec3::new(-0.6, 0.1, 0.05), Vec3::new(20.0, -40.0, 30.0))
    };
    model.particles.vel[0] = v;
    let mut scale = 0.5 * m * v.norm_squared();
    if rotations {
        model.particles.ang_vel[0] = w;
        scale += 0.5 * inertia * w.norm_squared();
    } else {
        for b in model.particles.blocked.iter_mut() {
            *b = flexdem_elements::Dofs::ROTATION;
        }
    }
    let settings = Settings { time_step: TimeStep::Fixed(tc / 500.0), ..Settings::default() };
    let mut sim = Simulation::new(model, settings).unwrap();
    let error = balance_error(&mut sim, 2000, scale);
    assert!(sim.contacts().is_empty(), "the impact is over");
    (error, sim.energy().contact_damping / scale)
}

/// Oblique impacts with tangential dashpots and friction (sliding, sticking, the spring set
/// against the slip by a dashpot above the Coulomb limit, and ended holding it): the energy
/// balance closes to round-off when the spheres cannot turn; with rotations, the shear
/// spring's lever arm (r − δ/2 for a wall, the normal turning between spheres) changing over
/// a step leaves the first-order error the undamped contact has too.
#[test]
fn oblique_impacts_with_dashpots_and_friction_close_the_balance() {
    for (e, friction) in [(0.5, 20.0), (0.1, 40.0), (0.9, 5.0)] {
        let mat = material(ContactDamping::Restitution(e), friction);
        let elastic = material(ContactDamping::None, friction);
        for on_wall in [true, false] {
            let (held, dashpots) = oblique_impact(mat, on_wall, false);
            let (free, _) = oblique_impact(mat, on_wall, true);
            let (held0, _) = oblique_impact(elastic, on_wall, false);
            let (free0, _) = oblique_impact(elastic, on_wall, true);
            println!(
                "e = {e}, friction {friction}°, {}: balance error {held:.2e} without rotation \
                 (the dashpots took {dashpots:.3} of the energy), {free:.2e} with; undamped: \
                 {held0:.2e}, {free0:.2e}",
                if on_wall { "on a wall" } else { "two spheres" }
            );
            assert!(dashpots > 0.0);
            if on_wall {
                assert!(held.abs() < 1e-11, "{e}: {held:e}");
            }
            assert!(held.abs() < 1e-6 && free.abs() < 1e-6, "{e}: {held:e} {free:e}");
        }
    }
}

/// A column of `count` damped spheres (restitution 0.3, friction 30°, E = 10⁷ Pa) above
/// each other, scattered sideways, in a box of five walls 5R wide; and its potential energy.
fn damped_column(count: usize) -> (Model, Real) {
    let width = 5.0 * R;
    let mut model = Model::new();
    let mat = Material::new(1e7, 0.3, RHO, 30f64.to_radians())
        .unwrap()
        .with_damping(ContactDamping::Restitution(0.3));
    let id = model.add_material(mat).unwrap();
    model.add_wall(Vec3::zeros(), Vec3::z(), id).unwrap();
    for (point, normal) in [
        (Vec3::new(-0.5 * width, 0.0, 0.0), Vec3::x()),
        (Vec3::new(0.5 * width, 0.0, 0.0), -Vec3::x()),
        (Vec3::new(0.0, -0.5 * width, 0.0), Vec3::y()),
        (Vec3::new(0.0, 0.5 * width, 0.0), -Vec3::y()),
    ] {
        model.add_wall(point, normal, id).unwrap();
    }
    // a simple generator: the same column on every platform
    let mut seed = 12345u64;
    let mut next = || {
        seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (seed >> 11) as Real / (1u64 << 53) as Real - 0.5
    };
    let g = 9.81;
    let mut potential = 0.0;
    for k in 0..count {
        let reach = 0.5 * width - R;
        let c = Vec3::new(next() * reach, next() * reach, R + 1e-3 + k as Real * 2.3 * R);
        model.add_sphere(c, R, id).unwrap();
        potential += sphere_mass() * g * c.z;
    }
    (model, potential)
}

/// The damped column's run is the same with one thread and with two, bit for bit, energy
/// terms included (the free spheres' pairs go through a one-pass path with one thread).
#[test]
fn damped_runs_do_not_depend_on_the_thread_count() {
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        pool.install(|| {
            let (model, _) = damped_column(12);
            let settings = Settings { gravity: Vec3::new(0.0, 0.0, -9.81), ..Settings::default() };
            let mut sim = Simulation::new(model, settings).unwrap();
            sim.run(6000).unwrap();
            assert!(sim.energy().contact_damping > 0.0);
            (sim.model().particles.pos.clone(), *sim.energy())
        })
    };
    let (one, two) = (run(1), run(2));
    assert!(one.0 == two.0, "positions differ between 1 and 2 threads");
    assert_eq!(format!("{:?}", one.1), format!("{:?}", two.1));
}

/// A column of 50 damped spheres (restitution 0.3, friction 30°, E = 10⁷ Pa) dropped into a
/// box of five walls under gravity, with a fixed step (each change of an automatic step
/// leaves an error of the springs' own, model.md §3): it comes to rest in 1.2 s, and the
/// energy balance closes to 5e-5 of the potential energy it started with (1.3e-5 with half
/// the step; not to round-off: the springs' trapezoidal work is exact only where the overlap
/// is linear in the positions, and between spheres that roll or slide over each other the
/// normal turns; the same column without friction and tangential dashpots leaves 4e-5, and
/// without dashpots, settled by Cundall damping 0.3, 4e-4).
#[test]
fn a_damped_column_settles_in_a_box_and_the_balance_closes() {
    let (model, potential) = damped_column(50);
    let g = 9.81;
    let settings = Settings {
        gravity: Vec3::new(0.0, 0.0, -g),
        time_step: TimeStep::Fixed(6e-5),
        ..Settings::default()
    };
    let mut sim = Simulation::new(model, settings).unwrap();
    assert!(sim.critical_dt() > 6e-5 * 1.5);
    let kinetic = |s: &Simulation| s.energy().kinetic_translation + s.energy().kinetic_rotation;
    while sim.steps() < 200_000 {
        sim.run(5_000).unwrap();
        if kinetic(&sim) < 1e-12 * potential {
            break;
        }
    }
    let e = sim.energy();
    let error = (e.balance() - sim.energy_watch().initial_balance) / potential;
    let fastest = sim.model().particles.vel.iter().map(|v| v.norm()).fold(0.0, Real::max);
    println!(
        "{} steps ({:.2} s): fastest {fastest:.2e} m/s, kinetic {:.2e} of the potential energy \
         {potential:.4} J; dashpots {:.4} J, friction {:.4} J, released {:.2e} J, births \
         {:.2e} J; balance error {error:.2e}",
        sim.steps(),
        sim.time(),
        kinetic(&sim) / potential,
        e.contact_damping,
        e.friction,
        e.contact_releases,
        e.contact_births,
    );
    assert!(kinetic(&sim) < 1e-12 * potential, "still moving: {fastest} m/s");
    assert!(error.abs() < 1e-4, "{error:e}: {e:?}");
}

/// A damped sphere dropped on a PFacet membrane: the contact sits on a face, a virtual sphere
/// interpolated from three nodes. Held in place (every node blocked), the face is infinitely
/// massive: m_eff is the sphere's mass, the dashpot is the wall's and the bounce the clamped
/// model's, with the balance closed to round-off (3e-13). Free (corners pinned), the face
/// moves with the interpolated mass Σ wᵢ·mᵢ of its nodes at the contact's birth, and the
/// balance of sphere, membrane and dashpots closes to 9e-11.
#[test]
fn a_damped_sphere_on_a_membrane_sees_the_face_s_interpolated_mass() {
    use flexdem_elements::builders::{membrane_rectangle, StructureOptions};
    use flexdem_elements::Dofs;
    let e = 0.5;
    for held in [true, false] {
        let mut model = Model::new();
        let id = model.add_material(material(ContactDamping::Restitution(e), 20.0)).unwrap();
        let opts = StructureOptions::new("membrane", 0.002, id);
        let (o, u, v) = (Vec3::new(-0.1, -0.1, 0.0), Vec3::x(), Vec3::y());
        let s = membrane_rectangle(&mut model, o, u, v, 0.2, 0.2, 4, 4, &opts).unwrap();
        let nodes = model.structures[s as usize].nodes.clone();
        if held {
            model.block(nodes.clone(), Dofs::ALL).unwrap();
        } else {
            let corners = [0, 4, 20, 24].map(|k| nodes.start + k);
            model.block(corners, Dofs::TRANSLATION).unwrap();
        }
        // above the middle of a PFacet (not on an edge of the grid)
        let c = Vec3::new(0.013, -0.012, 0.002 + R + 1e-5);
        let sphere = model.add_sphere(c, R, id).unwrap();
        model.particles.vel[sphere as usize] = Vec3::new(0.0, 0.0, -0.5);
        let m = sphere_mass();
        let tc = PI * (m / (YOUNG * R)).sqrt();
        let settings = Settings { time_step: TimeStep::Fixed(tc / 1000.0), ..Settings::default() };
        let mut sim = Simulation::new(model, settings).unwrap();
        while sim.contact_count() == 0 {
            sim.step().unwrap();
            assert!(sim.steps() < 10_000, "no contact");
        }
        let contacts = sim.contacts();
        assert_eq!(contacts.len(), 1, "{contacts:?}");
        let c = &contacts[0];
        // body 1 is the free sphere, body 2 the face
        assert!(matches!(c.site2.feature, flexdem_elements::virtual_sphere::Feature::Face(_)));
        let p = &sim.model().particles;
        let site: Real =
            (0..3).map(|k| c.site2.weights[k] * p.mass[c.site2.nodes[k] as usize]).sum();
        let m_eff = if held { m } else { m * site / (m + site) };
        let zeta = damping_ratio(e);
        let cn = 2.0 * zeta * (m_eff * c.params.kn).sqrt();
        let ct = 2.0 * zeta * (m_eff * c.params.ks).sqrt();
        assert!(within(c.params.cn, cn, 1e-12) && within(c.params.ct, ct, 1e-12), "{:?}", c.params);
        let scale = 0.5 * m * 0.25;
        sim.run((3.0 * tc / sim.dt()) as u64).unwrap();
        let vz = sim.model().particles.vel[sphere as usize].z;
        let error = (sim.energy().balance() - sim.energy_watch().initial_balance) / scale;
        println!(
            "membrane {}: face mass {site:.3e} kg against the sphere's {m:.3e} kg, m_eff \
             {m_eff:.3e} kg; rebound {:.4} of the impact speed, balance error {error:.2e}",
            if held { "held" } else { "free" },
            vz / 0.5
        );
        if held {
            let expected = clamped(zeta, (c.params.kn / m).sqrt()).restitution;
            assert!(within(vz / 0.5, expected, 0.01), "{vz} vs {expected}");
            assert!(error.abs() < 1e-9, "{error:e}");
        } else {
            // the membrane gives way and carries the sphere down: no bounce yet, but the
            // dashpots, the links and the contact keep the books
            assert!(sim.energy().contact_damping > 0.0);
            assert!(error.abs() < 1e-9, "{error:e}");
        }
    }
}
