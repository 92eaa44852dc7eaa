//! The simulation's state apart from its pipeline: a state taken out and put back continues
//! bit-identically, and every change through the API keeps the pipeline right or is refused
//! without changing anything.

use flexdem_contact::{LinkKinematicsMode, Material};
use flexdem_elements::builders::{chain, straight_line};
use flexdem_elements::{Dofs, Model, StructureOptions};
use flexdem_geom::{Real, Vec3};
use flexdem_integrate::{Load, Ramp, Settings, Simulation, TimeStep};

/// A chain of 4 nodes pinned at its first node, and a sphere falling on a wall beside it.
fn scene() -> Simulation {
    let mut model = Model::new();
    let mat = model.add_material(Material::new(1e7, 0.3, 1000.0, 0.5).unwrap()).unwrap();
    let points = straight_line(Vec3::zeros(), Vec3::x(), 4).unwrap();
    chain(&mut model, &points, &StructureOptions::new("c", 0.01, mat)).unwrap();
    model.block([0], Dofs::ALL).unwrap(); // the chain's first node
    model.add_sphere(Vec3::new(0.0, 1.0, 0.06), 0.05, mat).unwrap();
    model.add_wall(Vec3::zeros(), Vec3::z(), mat).unwrap();
    let settings = Settings { gravity: Vec3::new(0.0, 0.0, -9.81), ..Settings::default() };
    Simulation::new(model, settings).unwrap()
}

fn bits(v: &[Vec3]) -> Vec<[u64; 3]> {
    v.iter().map(|x| [x.x.to_bits(), x.y.to_bits(), x.z.to_bits()]).collect()
}

#[test]
fn a_state_put_back_continues_bit_identically() {
    let mut a = scene();
    while a.contacts().is_empty() {
        a.step().unwrap();
    }
    a.run(20).unwrap();
    let mut b = Simulation::from_state(a.state().clone()).unwrap();
    let mut c =
        Simulation::from_state(Simulation::from_state(a.state().clone()).unwrap().into_state())
            .unwrap();
    for sim in [&mut a, &mut b, &mut c] {
        sim.run(200).unwrap();
    }
    for other in [&b, &c] {
        assert_eq!(bits(&a.model().particles.pos), bits(&other.model().particles.pos));
        assert_eq!(bits(&a.model().particles.vel), bits(&other.model().particles.vel));
        assert_eq!(a.energy(), other.energy());
        assert_eq!(a.contacts(), other.contacts());
        assert_eq!(a.dt().to_bits(), other.dt().to_bits());
    }
}

#[test]
fn a_state_that_does_not_fit_its_model_is_refused() {
    let sim = scene();
    let mut s = sim.state().clone();
    s.clock.dt = Real::NAN;
    assert!(Simulation::from_state(s).is_err());
    let mut s = sim.state().clone();
    s.loads.push(Load {
        particles: vec![99],
        force: Vec3::zeros(),
        torque: Vec3::zeros(),
        ramp: Ramp::Constant,
    });
    let err = Simulation::from_state(s).map(|_| ()).unwrap_err().to_string();
    assert!(err.contains("inconsistent parts"), "{err}");
    // links that do not fit the model (a damaged checkpoint used to be restored and panic in
    // `Links::add_loads` at the first step)
    let mut s = sim.state().clone();
    s.links.nodes[1] = [0, 3];
    let err = Simulation::from_state(s).map(|_| ()).unwrap_err().to_string();
    assert!(err.contains("inconsistent parts"), "{err}");
    // an energy watch that would stop every step (a lowest balance of −∞) or never (NaN)
    for lowest in [Real::NEG_INFINITY, Real::NAN, sim.energy_watch().initial_balance + 1.0] {
        let mut s = sim.state().clone();
        s.energy.watch.lowest_balance = lowest;
        assert!(Simulation::from_state(s).is_err(), "{lowest}");
    }
    let mut s = sim.state().clone();
    s.energy.watch.scale = -1.0;
    assert!(Simulation::from_state(s).is_err());
    // nor one whose sum of contacts found late, or its credit, is NaN or negative
    for bad in [Real::NAN, -1.0] {
        let mut s = sim.state().clone();
        s.energy.watch.late_births = bad;
        assert!(Simulation::from_state(s).is_err(), "late births {bad}");
        let mut s = sim.state().clone();
        s.energy.watch.late_credit = bad;
        assert!(Simulation::from_state(s).is_err(), "credit {bad}");
    }
}

#[test]
fn a_model_edit_rebuilds_the_pipeline_or_changes_nothing() {
    let mut sim = scene();
    sim.run(10).unwrap();
    let elements = sim.collider().elements.len();
    // a new sphere: the collider, the force buffers and the time step follow
    let mat = sim.model().particles.material[0];
    let id =
        sim.edit_model(|m| m.add_sphere(Vec3::new(2.0, 0.0, 0.5), 0.05, mat)).unwrap().unwrap();
    assert_eq!(sim.collider().elements.len(), elements + 1);
    sim.run(10).unwrap();
    assert_eq!(sim.forces().len(), sim.model().particles.len());
    assert!(sim.model().particles.vel[id as usize].z < 0.0, "the new sphere falls");
    // a free DOF without mass is refused, and the model stays as it was
    let (before, count) = (sim.model().particles.blocked.clone(), sim.model().particles.len());
    let err = sim.edit_model(|m| {
        let s = m.add_structure("loose").unwrap();
        let n = m.add_node(s, Vec3::new(5.0, 0.0, 1.0), 0.01, mat, 1).unwrap();
        m.particles.blocked[n as usize] = Dofs::NONE;
    });
    assert!(err.is_err());
    assert_eq!(sim.model().particles.blocked, before);
    assert_eq!(sim.model().particles.len(), count);
    sim.run(5).unwrap();
}

/// The scene of `scene()` with the sphere pressed on the wall and the chain sagging, at a
/// fixed step (so that an edit does not change it).
fn loaded_scene() -> Simulation {
    let mut sim = scene();
    while sim.contacts().is_empty() {
        sim.step().unwrap();
    }
    sim.run(50).unwrap();
    let fixed = Settings { time_step: TimeStep::Fixed(sim.dt()), ..sim.settings().clone() };
    sim.set_settings(fixed).unwrap();
    let e = *sim.energy();
    assert!(e.elastic_contacts > 0.0 && e.elastic_links > 0.0, "{e:?}");
    sim
}

/// A model edit that only adds bodies apart from the others (a chain of new nodes, a sphere,
/// a wall, held still) keeps every contact and link as it was: the old bodies then move as
/// in a twin without the edit, bit for bit, and the energy terms are the twin's (the new
/// bodies hold none). Before, the contacts ended (their shear springs lost) and the links
/// were made anew at rest in the sagged shape (their prestress lost).
#[test]
fn a_model_edit_that_only_adds_bodies_keeps_every_contact_and_link() {
    let (mut a, mut b) = (loaded_scene(), loaded_scene());
    let (n, links) = (a.model().particles.len(), a.model().connections.len());
    let mat = a.model().particles.material[0];
    a.edit_model(|m| {
        let points = straight_line(Vec3::new(0.0, 3.0, 1.0), Vec3::new(1.0, 3.0, 1.0), 2).unwrap();
        chain(m, &points, &StructureOptions::new("new", 0.01, mat)).unwrap();
        let s = m.add_sphere(Vec3::new(3.0, 3.0, 1.0), 0.05, mat).unwrap();
        m.block([s], Dofs::ALL).unwrap();
        let new: Vec<u32> = (n as u32..m.particles.len() as u32).collect();
        m.block(new, Dofs::ALL).unwrap();
        m.add_wall(Vec3::new(0.0, 0.0, 5.0), -Vec3::z(), mat).unwrap();
    })
    .unwrap();
    assert_eq!(a.contacts(), b.contacts());
    assert_eq!(a.links().state[..links], b.links().state[..]);
    assert_eq!(a.links().state.len(), links + 2);
    for sim in [&mut a, &mut b] {
        sim.run(200).unwrap();
    }
    let old = |sim: &Simulation| bits(&sim.model().particles.pos[..n]);
    assert_eq!(old(&a), old(&b));
    assert_eq!(bits(&a.model().particles.vel[..n]), bits(&b.model().particles.vel[..n]));
    assert_eq!(a.contacts(), b.contacts());
    assert_eq!(a.links().state[..links], b.links().state[..]);
    assert_eq!(a.energy(), b.energy());
    assert_eq!(a.energy_watch().late_births, 0.0);
}

/// A model edit that changes the topology (a new node joined to an old one, an old rest
/// length changed by 1 %) ends the contacts, their elastic energy released. Of the links,
/// only the changed one is made anew: its old elastic energy goes to `links_dissipated`, its
/// normal spring's `½·kn·(L0 − L)²` at the new rest length is the user's work; the others
/// keep their state. The balance holds across the edit.
#[test]
fn a_model_edit_that_ends_contacts_and_changes_a_link_keeps_the_balance() {
    let mut sim = loaded_scene();
    let e = *sim.energy();
    let balance = e.balance();
    let released = sim.links().elastic_energy(0, &sim.model().particles);
    let kept = sim.links().state[1..].to_vec();
    let mat = sim.model().particles.material[0];
    sim.edit_model(|m| {
        let s = m.add_structure("joined").unwrap();
        let node = m.add_node(s, Vec3::new(1.0, 0.0, 0.5), 0.01, mat, 1).unwrap();
        m.add_connection(s, [3, node], 0.01, mat, 1).unwrap();
        m.block([node], Dofs::ALL).unwrap(); // (no mass lumped: held)
        m.connections[0].rest_length *= 1.01;
    })
    .unwrap();
    let after = *sim.energy();
    let (spring, p) = (*sim.links().spring_of(0), &sim.model().particles);
    let stretch = spring.rest_length - (p.pos[1] - p.pos[0]).norm();
    let stretched = 0.5 * spring.stiffness.kn * stretch * stretch;
    // (the new link's rest length is its nodes' distance: it holds nothing)
    let joined = {
        let new = sim.links().len() - 1;
        let (spring, [a, b]) = (sim.links().spring_of(new), sim.links().nodes[new]);
        let stretch = spring.rest_length - (p.pos[b as usize] - p.pos[a as usize]).norm();
        0.5 * spring.stiffness.kn * stretch * stretch
    };
    assert!(released > 0.0 && stretched > 0.0);
    assert_eq!(after.contact_releases, e.contact_releases + e.elastic_contacts);
    assert_eq!(after.links_dissipated, e.links_dissipated + released);
    let made = after.load_work - e.load_work;
    assert!((made - (stretched + joined)).abs() <= 1e-12 * made, "{made} {stretched} {joined}");
    let unchanged = &sim.links().state[1..=kept.len()];
    assert_eq!(unchanged, &kept[..], "the links of unchanged connections go on");
    assert!((after.balance() - balance).abs() <= 1e-12 * balance.abs().max(e.stored()));
    assert!(sim.contacts().is_empty());
    // the next step adds the links' dissipation (none: elastic) to what was booked
    sim.step().unwrap();
    assert_eq!(sim.energy().links_dissipated, after.links_dissipated);
}

/// A sagging chain, no contact: a rest length shortened by hand puts `½·kn·(L0 − L)²` into
/// that link's normal spring, booked as the user's work, and the balance closes over the
/// steps after it as it did before the edit. (Before, every link was made anew at rest and
/// all of their elastic energy was booked as dissipated, though the normal strains came back
/// at the next step, the rest lengths kept: energy from nothing, about `elastic_links`.)
#[test]
fn a_rest_length_changed_by_hand_is_the_users_work() {
    let mut model = Model::new();
    let mat = model.add_material(Material::new(1e7, 0.3, 1000.0, 0.5).unwrap()).unwrap();
    let points = straight_line(Vec3::zeros(), Vec3::x(), 6).unwrap();
    chain(&mut model, &points, &StructureOptions::new("c", 0.01, mat)).unwrap();
    let last = (points.len() - 1) as u32;
    model.block([0, last], Dofs::ALL).unwrap();
    let settings = Settings { gravity: Vec3::new(0.0, 0.0, -9.81), ..Settings::default() };
    let mut sim = Simulation::new(model, settings).unwrap();
    sim.run(300).unwrap();
    let fixed = Settings { time_step: TimeStep::Fixed(sim.dt()), ..sim.settings().clone() };
    sim.set_settings(fixed).unwrap();
    let drift = |sim: &mut Simulation| {
        let start = sim.energy().balance();
        sim.run(300).unwrap();
        (sim.energy().balance() - start).abs()
    };
    let before = drift(&mut sim);
    let e = *sim.energy();
    sim.edit_model(|m| m.connections[2].rest_length *= 0.999).unwrap();
    let made = sim.energy().load_work - e.load_work;
    let (spring, p) = (*sim.links().spring_of(2), &sim.model().particles);
    let stretch = spring.rest_length - (p.pos[3] - p.pos[2]).norm();
    let expected = 0.5 * spring.stiffness.kn * stretch * stretch;
    assert!(expected > 0.0 && (made - expected).abs() <= 1e-12 * expected, "{made} {expected}");
    let after = drift(&mut sim);
    // the link's force changes at once by kn·ΔL, which the leapfrog's half-step kinetic
    // energy sees late: an error of a few % of what the edit put in (2.9 % here); the old
    // booking's error was about the links' normal energy, `elastic_links`, ten times more
    let bound = before + 0.05 * made;
    assert!(after <= bound, "drift {after} against {before} before the edit, {made} put in");
    assert!(e.elastic_links > 10.0 * bound, "{e:?}");
}

/// After a model edit an automatic step grows by at most the factor of any re-estimate
/// (1.1), here where heavier bodies would allow ten times the step at once; a fixed step
/// stays as it is.
#[test]
fn an_edit_raises_an_automatic_step_by_at_most_the_growth_factor() {
    let mut sim = scene();
    sim.run(20).unwrap();
    let dt = sim.dt();
    let heavier = |m: &mut Model| {
        m.particles.mass.iter_mut().for_each(|x| *x *= 100.0);
        m.particles.inertia.iter_mut().for_each(|x| *x *= 100.0);
    };
    sim.edit_model(heavier).unwrap();
    // (the default step is half the critical one)
    assert!(sim.critical_dt() * 0.5 > 9.0 * dt, "{} against {dt}", sim.critical_dt());
    assert_eq!(sim.dt(), 1.1 * dt);
    // (no step after it: masses changed by hand scale the kinetic energy, which no work
    // books, and the watch would stop the run)
}

#[test]
fn settings_changes_are_checked_and_rebuild_what_depends_on_them() {
    let mut sim = scene();
    sim.run(5).unwrap();
    let settings = sim.settings().clone();
    let yade = Settings { link_mode: LinkKinematicsMode::Yade, ..settings.clone() };
    assert!(sim.set_settings(yade).is_err(), "the links were made with another kinematics");
    assert!(sim.set_damping(1.5).is_err());
    assert_eq!(sim.settings(), &settings);
    sim.set_damping(0.2).unwrap();
    assert_eq!(sim.settings().damping, 0.2);
    let coarse = Settings { verlet_factor: 2.0, ..sim.settings().clone() };
    sim.set_settings(coarse).unwrap();
    assert_eq!(sim.collider().builds, 0, "a new collider");
    sim.step().unwrap();
    assert_eq!(sim.collider().builds, 1);
    let fixed = Settings { time_step: TimeStep::Fixed(1e-6), ..sim.settings().clone() };
    sim.set_settings(fixed).unwrap();
    assert_eq!(sim.dt(), 1e-6);
}

#[test]
fn setters_check_their_ids_and_values() {
    let mut sim = scene();
    let n = sim.model().particles.len() as u32;
    assert!(sim.set_velocity(n, Vec3::zeros()).is_err());
    assert!(sim.set_position(0, Vec3::new(Real::NAN, 0.0, 0.0)).is_err());
    assert!(sim.set_wall_velocity(1, Vec3::zeros()).is_err());
    sim.set_wall_velocity(0, Vec3::new(0.0, 0.0, 0.1)).unwrap();
    assert_eq!(sim.model().walls[0].velocity.z, 0.1);
    sim.set_velocity(1, Vec3::new(0.0, 0.0, 1.0)).unwrap();
    assert_eq!(sim.model().particles.vel[1].z, 1.0);
    sim.unblock([0], Dofs::ALL).unwrap();
    sim.block([0], Dofs::ALL).unwrap();
    assert!(sim
        .add_load(Load {
            particles: vec![n],
            force: Vec3::zeros(),
            torque: Vec3::zeros(),
            ramp: Ramp::Constant
        })
        .is_err());
    assert!(sim.loads().is_empty());
    sim.run(5).unwrap();
}
