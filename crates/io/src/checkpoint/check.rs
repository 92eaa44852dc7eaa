//! Checks of the parts of a state read from a file that the engine's own checks
//! (`Simulation::from_state`: the model, the settings, the links' topology, ids in range)
//! leave to the file: the numbers of the contacts and of the loads, the step counters. A damaged checkpoint whose
//! checksum was recomputed (the mutation fuzzer) can hold NaN weights or a non-unit normal in
//! a contact, which the contact law assumes away.

use flexdem_contact::{FrictionalContact, FrictionalParams};
use flexdem_elements::virtual_sphere::{Feature, Site};
use flexdem_geom::{Real, Vec3};
use flexdem_integrate::{Contact, ContactKey, Load, PairContact, Ramp, State};

fn finite(v: &Vec3) -> bool {
    v.iter().all(|x| x.is_finite())
}

/// What is wrong with site `site` of a contact, if anything.
fn check_site(s: &State, site: &Site) -> Result<(), String> {
    let model = &s.model;
    let (used, in_range) = match site.feature {
        Feature::Particle(i) => (1, (i as usize) < model.particles.len()),
        Feature::Edge(c) => (2, (c as usize) < model.connections.len()),
        Feature::Face(f) => (3, (f as usize) < model.pfacets.len()),
        Feature::Wall(w) => (0, (w as usize) < model.walls.len()),
    };
    if !in_range {
        return Err(format!("feature {:?} does not exist", site.feature));
    }
    let weights = &site.weights[..used];
    let sum: Real = weights.iter().sum();
    let weights_ok = weights.iter().all(|w| w.is_finite() && (-1e-9..=1.0 + 1e-9).contains(w))
        && (used == 0 || (sum - 1.0).abs() <= 1e-6);
    if !weights_ok {
        return Err(format!(
            "weights {:?} of {:?} are not barycentric",
            site.weights, site.feature
        ));
    }
    if site.nodes[..used].iter().any(|&n| (n as usize) >= model.particles.len()) {
        return Err(format!("nodes {:?} of {:?} do not exist", site.nodes, site.feature));
    }
    if !(site.radius.is_finite() && site.radius >= 0.0) {
        return Err(format!("radius {} of {:?}", site.radius, site.feature));
    }
    Ok(())
}

/// What is wrong with contact `c`, if anything.
fn check_contact(s: &State, c: &Contact) -> Result<(), String> {
    check_site(s, &c.site1)?;
    check_site(s, &c.site2)?;
    if !finite(&c.point) {
        return Err("a contact point that is not finite".into());
    }
    check_law(&c.params, &c.state)
}

/// What is wrong with the touching pair `key` of the free spheres' neighbour list, if
/// anything: its bodies a free sphere and a free sphere or a wall of the model, its state.
fn check_pair(s: &State, key: &ContactKey, c: &PairContact) -> Result<(), String> {
    let model = &s.model;
    for f in [key.0, key.1] {
        let ok = match f {
            Feature::Particle(i) => (i as usize) < model.particles.len(),
            Feature::Wall(w) => (w as usize) < model.walls.len(),
            Feature::Edge(_) | Feature::Face(_) => false,
        };
        if !ok {
            return Err(format!("feature {f:?} is not a free sphere or wall of the model"));
        }
    }
    check_law(&c.params, &c.state)
}

/// What is wrong with a contact's constants and state, if anything.
fn check_law(p: &FrictionalParams, st: &FrictionalContact) -> Result<(), String> {
    let non_negative = |x: Real| x.is_finite() && x >= 0.0;
    if !(non_negative(p.kn) && non_negative(p.ks) && non_negative(p.tan_phi)) {
        return Err(format!("stiffness or friction {p:?}"));
    }
    if !(non_negative(p.cn) && non_negative(p.ct)) {
        return Err(format!("dashpots {p:?}"));
    }
    if !(finite(&st.shear_force) && finite(&st.normal)) {
        return Err("a shear force or normal that is not finite".into());
    }
    if (st.normal.norm_squared() - 1.0).abs() > 1e-6 {
        return Err(format!("a normal of length {} (expected 1)", st.normal.norm()));
    }
    // negative while two intersecting faces are driven deeper (model.md §1)
    if !st.overlap_offset.is_finite() {
        return Err(format!("an overlap offset of {} m", st.overlap_offset));
    }
    // both enter the energy balance (a spring's energy at its end, the friction booked),
    // where a NaN would pass the energy watch unseen
    if !(st.normal_force.is_finite() && st.dissipated_friction.is_finite()) {
        return Err(format!(
            "a normal force of {} N or a friction dissipation of {} J",
            st.normal_force, st.dissipated_friction
        ));
    }
    Ok(())
}

/// What is wrong with load `l`, if anything (its particle ids are the engine's to check).
fn check_load(l: &Load) -> Result<(), String> {
    if !(finite(&l.force) && finite(&l.torque)) {
        return Err("a force or torque that is not finite".into());
    }
    match l.ramp {
        Ramp::Linear { start, duration }
            if !(start.is_finite() && start >= 0.0 && duration.is_finite() && duration > 0.0) =>
        {
            Err(format!("a ramp from {start} s over {duration} s"))
        }
        _ => Ok(()),
    }
}

/// `Err(what)` when the contacts or loads of `s` hold numbers no run produces.
pub(crate) fn check_state(s: &State) -> Result<(), String> {
    if s.clock.dt_updated_at > s.clock.steps {
        return Err(format!(
            "the time step was estimated at step {}, after the last step {}",
            s.clock.dt_updated_at, s.clock.steps
        ));
    }
    for (i, c) in s.contacts.list.iter().enumerate() {
        check_contact(s, c).map_err(|e| format!("contact {i}: {e}"))?;
    }
    for (i, (key, c)) in s.contacts.pairs.touching().enumerate() {
        check_pair(s, &key, c).map_err(|e| format!("contact {i} of the free spheres: {e}"))?;
    }
    for (i, l) in s.loads.iter().enumerate() {
        check_load(l).map_err(|e| format!("load {i}: {e}"))?;
    }
    Ok(())
}
