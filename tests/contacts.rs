//! validation.md cases 10, 11 and 12, a sphere dropped on a net, and results independent of
//! the number of threads.

mod common;

use flexdem::contact::Material;
use flexdem::elements::builders::{
    chain, membrane_rectangle, net, straight_line, GridLayout, StructureOptions,
};
use flexdem::elements::{Dofs, Model};
use flexdem::geom::{Real, Vec3};
use flexdem::integrate::{Settings, Simulation, TimeStep};
use std::f64::consts::PI;

/// Case 11: two equal spheres, linear spring, no damping: contact time π·√(m*/kn) with
/// m* = m/2 and restitution 1, to 1e-3.
#[test]
fn normal_impact_contact_time_and_restitution() {
    let (r, e, rho, v) = (0.01, 1e8, 2650.0, 0.5);
    let mut model = Model::new();
    let m = model.add_material(Material::new(e, 0.3, rho, 0.5).unwrap()).unwrap();
    let a = model.add_sphere(Vec3::new(-r - 1e-4, 0.0, 0.0), r, m).unwrap();
    let b = model.add_sphere(Vec3::new(r + 1e-4, 0.0, 0.0), r, m).unwrap();
    model.particles.vel[a as usize] = Vec3::new(v, 0.0, 0.0);
    model.particles.vel[b as usize] = Vec3::new(-v, 0.0, 0.0);
    let mass = 4.0 / 3.0 * PI * r.powi(3) * rho;
    let kn = e * r; // eq 3 with equal spheres
    let tc = PI * (0.5 * mass / kn).sqrt();
    let dt = tc / 2000.0;
    let settings = Settings { time_step: TimeStep::Fixed(dt), ..Settings::default() };
    let mut sim = Simulation::new(model, settings).unwrap();
    let gap = |s: &Simulation| {
        let p = &s.model().particles.pos;
        (p[1] - p[0]).norm() - 2.0 * r
    };
    let (mut start, mut end) = (None, None);
    let mut prev = gap(&sim);
    while end.is_none() && sim.time() < 10.0 * tc + 1e-3 {
        sim.step().unwrap();
        let g = gap(&sim);
        let t_cross = sim.time() - sim.dt() * g / (g - prev); // linear interpolation
        if prev > 0.0 && g <= 0.0 {
            start = Some(t_cross);
        } else if prev <= 0.0 && g > 0.0 && start.is_some() {
            end = Some(t_cross);
        }
        prev = g;
    }
    let duration = end.unwrap() - start.unwrap();
    assert!((duration / tc - 1.0).abs() < 1e-3, "contact time {duration} vs {tc}");
    // a few steps later, when the spring is released
    sim.run(10).unwrap();
    let restitution = sim.model().particles.vel[1].x / v;
    assert!((restitution - 1.0).abs() < 1e-3, "restitution {restitution}");
}

/// Case 12 (Chung & Ooi 2011, test 4): a sphere hits a wall at angle θ from the normal in
/// gross sliding: the tangential velocity ratio is 1 − μ(1+e)/tanθ and the spin
/// 5μ(1+e)·vn/(2R); e = 1 here (no damping): 45° gives 0.816 and 508 rad/s, 60° gives 0.894.
#[test]
fn oblique_impact_on_a_wall_in_gross_sliding() {
    let (r, e, rho, mu, speed): (Real, Real, Real, Real, Real) =
        (2.5e-3, 380e9, 4000.0, 0.092, 3.9);
    for theta_deg in [45.0_f64, 60.0] {
        let theta = theta_deg.to_radians();
        let mut model = Model::new();
        let mat = model.add_material(Material::new(e, 0.3, rho, mu.atan()).unwrap()).unwrap();
        model.add_wall(Vec3::zeros(), Vec3::z(), mat).unwrap();
        let s = model.add_sphere(Vec3::new(0.0, 0.0, r + 1e-6), r, mat).unwrap();
        let (vt, vn) = (speed * theta.sin(), speed * theta.cos());
        model.particles.vel[s as usize] = Vec3::new(vt, 0.0, -vn);
        let mass = 4.0 / 3.0 * PI * r.powi(3) * rho;
        let tc = PI * (mass / (e * r)).sqrt();
        let settings = Settings { time_step: TimeStep::Fixed(tc / 1000.0), ..Settings::default() };
        let mut sim = Simulation::new(model, settings).unwrap();
        while sim.time() < 3.0 * tc {
            sim.step().unwrap();
        }
        let v = sim.model().particles.vel[0];
        let w = sim.model().particles.ang_vel[0];
        assert!(v.z > 0.0, "the sphere bounced: {v}");
        let ratio = v.x / vt;
        let expected = 1.0 - mu * 2.0 / theta.tan();
        assert!((ratio / expected - 1.0).abs() < 0.02, "{theta_deg}°: ratio {ratio} vs {expected}");
        let spin = 5.0 * mu * 2.0 * vn / (2.0 * r);
        assert!((w.y.abs() / spin - 1.0).abs() < 0.02, "{theta_deg}°: spin {} vs {spin}", w.y);
        assert!((v.z / vn - 1.0).abs() < 1e-2, "normal restitution {}", v.z / vn);
    }
}

/// Case 10: a sphere pushed slowly along a fixed flat PFacet mesh (or a straight chain) at
/// constant indentation: one contact throughout, the normal force constant within 1e-6
/// relative (no jump at edges or nodes), and the shear force carried over (it stays at the
/// Coulomb limit once sliding instead of restarting from zero at each element).
#[test]
fn sliding_across_elements_has_no_jump() {
    for structure in ["membrane", "chain"] {
        let mut model = Model::new();
        let mat = model.add_material(Material::new(1e7, 0.3, 1000.0, 0.4).unwrap()).unwrap();
        let opts = StructureOptions::new(structure, 0.01, mat);
        let s = if structure == "membrane" {
            membrane_rectangle(
                &mut model,
                Vec3::zeros(),
                Vec3::x(),
                Vec3::y(),
                1.0,
                0.5,
                8,
                4,
                &opts,
            )
            .unwrap()
        } else {
            let points =
                straight_line(Vec3::new(0.0, 0.25, 0.0), Vec3::new(1.0, 0.25, 0.0), 8).unwrap();
            chain(&mut model, &points, &opts).unwrap()
        };
        let nodes = model.structures[s as usize].nodes.clone();
        model.block(nodes, Dofs::ALL).unwrap();
        let (r, delta) = (0.05, 1e-3);
        // over a vertex row? start off-node, slide along x across cells, edges and nodes
        let sphere = model.add_sphere(Vec3::new(0.07, 0.25, 0.01 + r - delta), r, mat).unwrap();
        model.impose_velocity([sphere], Vec3::new(0.05, 0.0, 0.0)).unwrap();
        model.block([sphere], Dofs::ALL).unwrap();
        let settings = Settings { time_step: TimeStep::Fixed(2e-4), ..Settings::default() };
        let mut sim = Simulation::new(model, settings).unwrap();
        sim.step().unwrap();
        let fn0 = sim.contacts()[0].forces.normal_force;
        let mut saturated = false;
        let mut features = std::collections::BTreeSet::new();
        while sim.model().particles.pos[sphere as usize].x < 0.9 {
            sim.step().unwrap();
            assert_eq!(sim.contacts().len(), 1, "{structure}: {:?}", sim.contacts());
            let c = &sim.contacts()[0];
            features.insert(format!("{:?}", c.site2.feature).chars().take(4).collect::<String>());
            let f = c.forces.normal_force;
            assert!((f / fn0 - 1.0).abs() < 1e-6, "{structure}: normal force {f} vs {fn0}");
            let limit = f * 0.4f64.tan();
            let fs = c.forces.shear_force.norm();
            if fs > 0.999 * limit {
                saturated = true;
            } else {
                assert!(
                    !saturated,
                    "{structure}: shear force dropped to {fs} (limit {limit}) at x = {}",
                    sim.model().particles.pos[sphere as usize].x
                );
            }
        }
        assert!(saturated);
        assert!(features.len() >= 2, "{structure}: crossed {features:?}");
    }
}

/// A sphere dropped on a net pinned at its corners comes to rest on it, held by it.
#[test]
fn sphere_dropped_on_a_net_comes_to_rest() {
    let (mut sim, sphere) = net_drop(0.3);
    let mut quiet = 0;
    while quiet < 2000 && sim.time() < 8.0 {
        sim.step().unwrap();
        let v = common::max_speed(&sim);
        quiet = if v < 1e-4 { quiet + 1 } else { 0 };
    }
    assert!(quiet >= 2000, "still moving at t = {}", sim.time());
    let z = sim.model().particles.pos[sphere as usize].z;
    assert!(z > -0.2 && z < 0.05, "the sphere rests at z = {z}, on the net");
    // the net carries the sphere's weight: contact forces balance gravity
    let weight = sim.model().particles.mass[sphere as usize] * 9.81;
    let up: Real = sim.contacts().iter().map(|c| -c.forces.force_on_2.z).sum();
    assert!((up.abs() / weight - 1.0).abs() < 1e-3, "contacts carry {up} of {weight}");
}

fn net_drop(damping: Real) -> (Simulation, u32) {
    let mut model = Model::new();
    let steel = model.add_material(Material::new(2e9, 0.3, 7850.0, 0.5).unwrap()).unwrap();
    let opts = StructureOptions::new("net", 0.004, steel);
    let s = net(
        &mut model,
        Vec3::new(-0.5, -0.5, 0.0),
        Vec3::x(),
        Vec3::y(),
        1.0,
        1.0,
        10,
        10,
        false,
        &opts,
    )
    .unwrap();
    let grid = GridLayout::of(&model, s, 10, 10).unwrap();
    model.block(grid.corners(), Dofs::ALL).unwrap();
    let rock = model.add_material(Material::new(1e8, 0.3, 2600.0, 0.5).unwrap()).unwrap();
    let sphere = model.add_sphere(Vec3::new(0.03, 0.02, 0.15), 0.08, rock).unwrap();
    let settings = Settings {
        gravity: Vec3::new(0.0, 0.0, -9.81),
        damping,
        time_step: TimeStep::Auto { safety: 0.5 },
        ..Settings::default()
    };
    (Simulation::new(model, settings).unwrap(), sphere)
}

/// The same run with 1 and 2 threads gives bit-identical positions.
#[test]
fn results_do_not_depend_on_the_thread_count() {
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        pool.install(|| {
            let (mut sim, _) = net_drop(0.1);
            while sim.contacts().is_empty() {
                sim.step().unwrap();
            }
            sim.run(2000).unwrap();
            sim.model().particles.pos.clone()
        })
    };
    let (one, two) = (run(1), run(2));
    assert!(one.iter().zip(&two).all(|(a, b)| a == b), "positions differ between 1 and 2 threads");
}

/// Two PFacets of one structure, stacked 1.5 r apart (they overlap): one contact when the
/// structure touches itself, none with `self_contact` off (the collider never pairs them).
#[test]
fn a_structure_with_self_contact_off_does_not_touch_itself() {
    for on in [true, false] {
        let mut model = Model::new();
        let m = model.add_material(Material::new(1e7, 0.3, 1000.0, 0.5).unwrap()).unwrap();
        let r = 0.01;
        let s = model.add_structure("folded").unwrap();
        model.set_self_contact(s, on).unwrap();
        for z in [0.0, 1.5 * r] {
            let corners = [[0.0, 0.0, z], [1.0, 0.0, z], [0.0, 1.0, z]];
            let n = corners.map(|p| model.add_node(s, Vec3::from(p), r, m, 1).unwrap());
            let e = [[n[0], n[1]], [n[1], n[2]], [n[2], n[0]]]
                .map(|pair| model.add_connection(s, pair, r, m, 1).unwrap());
            model.add_pfacet(s, n, e, r, m, 1).unwrap();
        }
        let nodes = model.structures[s as usize].nodes.clone();
        model.block(nodes, Dofs::ALL).unwrap();
        let settings = Settings { time_step: TimeStep::Fixed(1e-6), ..Settings::default() };
        let mut sim = Simulation::new(model, settings).unwrap();
        sim.step().unwrap();
        assert_eq!(sim.contacts().len(), usize::from(on), "self_contact = {on}");
    }
}
