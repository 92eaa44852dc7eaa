use super::*;
use flexdem_geom::Real;
use proptest::prelude::*;

fn v3() -> impl Strategy<Value = Vec3> {
    prop::array::uniform3(-2.0..2.0f64).prop_map(Vec3::from)
}

/// A site on 1, 2 or 3 of four particles, with random positive weights summing to 1.
fn site() -> impl Strategy<Value = Site> {
    (0usize..3, prop::array::uniform3(0.01..1.0f64), 0.001..0.1f64).prop_map(|(kind, w, r)| {
        match kind {
            0 => Site::particle(2, r),
            1 => Site::edge(7, [0, 3], w[0], r),
            _ => {
                let s = w[0] + w[1] + w[2];
                Site::face(4, [1, 3, 0], [w[0] / s, w[1] / s, w[2] / s], r)
            }
        }
    })
}

fn rigid_motion(pos: &[Vec3], v: &Vec3, omega: &Vec3) -> (Vec<Vec3>, Vec<Vec3>) {
    let vel = pos.iter().map(|x| v + omega.cross(x)).collect();
    let ang = pos.iter().map(|_| *omega).collect();
    (vel, ang)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Eq 17 and the moment sharing: node forces sum to F, and the node loads have the same
    /// moment as F applied at the contact point, about any point.
    #[test]
    fn distribution_balances_force_and_moment(
        site in site(),
        pos in prop::array::uniform4(v3()),
        point in v3(),
        force in v3(),
        origin in v3(),
    ) {
        let zeros = [Vec3::zeros(); 4];
        let k = Kinematics { pos: &pos, vel: &zeros, ang_vel: &zeros, link_mode: LinkKinematicsMode::Beam };
        let vs = virtual_sphere(&site, &k);
        let loads = distribute_force(&site, &pos, &vs.center, &point, &force);
        let mut f = Vec3::zeros();
        let mut m = Vec3::zeros();
        for l in &loads {
            f += l.force;
            m += (pos[l.node as usize] - origin).cross(&l.force) + l.torque;
        }
        let m_expected = (point - origin).cross(&force);
        let scale = force.norm() * 10.0 + 1e-12;
        prop_assert!((f - force).norm() <= 1e-12 * scale, "force {f} vs {force}");
        prop_assert!((m - m_expected).norm() <= 1e-12 * scale, "moment {m} vs {m_expected}");
    }

    /// The distribution is the transpose of the interpolation: the power of the node loads
    /// equals the power of F at the contact point carried by the virtual sphere.
    #[test]
    fn distribution_and_interpolation_deliver_the_same_power(
        site in site(),
        pos in prop::array::uniform4(v3()),
        vel in prop::array::uniform4(v3()),
        ang in prop::array::uniform4(v3()),
        point in v3(),
        force in v3(),
    ) {
        let k = Kinematics { pos: &pos, vel: &vel, ang_vel: &ang, link_mode: LinkKinematicsMode::Beam };
        let vs = virtual_sphere(&site, &k);
        prop_assume!(site.node_count() < 2 || (pos[site.nodes[1] as usize] - pos[site.nodes[0] as usize]).norm() > 1e-3);
        let loads = distribute_force(&site, &pos, &vs.center, &point, &force);
        let nodes: Real = loads[..site.node_count()]
            .iter()
            .map(|l| l.force.dot(&vel[l.node as usize]) + l.torque.dot(&ang[l.node as usize]))
            .sum();
        let at_point = force.dot(&(vs.velocity + vs.angular_velocity.cross(&(point - vs.center))));
        let scale = force.norm() * (1.0 + vel.iter().chain(&ang).map(|v| v.norm()).sum::<Real>()) * 1e3;
        prop_assert!((nodes - at_point).abs() <= 1e-12 * scale, "{nodes} vs {at_point}");
    }

    /// Eq 16 and the edge interpolation: for a rigid motion of the nodes the virtual sphere
    /// moves with the rigid motion at its centre and spins at its rate.
    #[test]
    fn interpolation_reproduces_rigid_motion(
        site in site(),
        pos in prop::array::uniform4(v3()),
        v in v3(),
        omega in v3(),
    ) {
        let (vel, ang) = rigid_motion(&pos, &v, &omega);
        let k = Kinematics { pos: &pos, vel: &vel, ang_vel: &ang, link_mode: LinkKinematicsMode::Beam };
        let vs = virtual_sphere(&site, &k);
        let expected = v + omega.cross(&vs.center);
        let scale = v.norm() + omega.norm() * 4.0 + 1e-12;
        prop_assert!((vs.velocity - expected).norm() <= 1e-12 * scale);
        prop_assert!((vs.angular_velocity - omega).norm() <= 1e-11 * scale,
            "{} vs {}", vs.angular_velocity, omega);
    }

    /// Two spheres in a common rigid motion have no relative velocity at the contact point.
    #[test]
    fn rigid_motion_has_no_relative_contact_velocity(
        c1 in v3(), dir in v3(), v in v3(), omega in v3(),
    ) {
        prop_assume!(dir.norm() > 1e-3);
        let c2 = c1 + dir.normalize() * 0.15;
        let s1 = VirtualSphere { center: c1, velocity: v + omega.cross(&c1), angular_velocity: omega };
        let s2 = VirtualSphere { center: c2, velocity: v + omega.cross(&c2), angular_velocity: omega };
        // the previous normal on the same side as the centres: the usual geometry
        let side = (dir.normalize() + Vec3::new(0.3, -0.2, 0.1)).normalize();
        prop_assume!(side.dot(&dir) > 0.0);
        let g = contact_geometry(&s1, 0.1, &s2, 0.1, &side);
        prop_assert!((g.overlap - 0.05).abs() < 1e-12);
        prop_assert!((g.normal - dir.normalize()).norm() < 1e-12);
        prop_assert!(g.relative_velocity.norm() <= 1e-12 * (v.norm() + 4.0 * omega.norm() + 1.0));
        prop_assert!((g.spin_about_normal - omega.dot(&g.normal)).abs() < 1e-12 * (1.0 + omega.norm()));
    }
}

#[test]
fn edge_spin_includes_one_over_length_squared() {
    // A 2 m segment along x whose far end moves up at 1 m/s turns at 0.5 rad/s about -y...
    let pos = [Vec3::zeros(), Vec3::new(2.0, 0.0, 0.0)];
    let vel = [Vec3::zeros(), Vec3::new(0.0, 0.0, 1.0)];
    let ang = [Vec3::zeros(); 2];
    let site = Site::edge(0, [0, 1], 0.5, 0.1);
    let vs = virtual_sphere(
        &site,
        &Kinematics { pos: &pos, vel: &vel, ang_vel: &ang, link_mode: LinkKinematicsMode::Beam },
    );
    // ... so the rate is s × dv / L² = (2,0,0) × (0,0,1) / 4 = (0,-0.5,0) (YADE: (0,-2,0)).
    assert!((vs.angular_velocity - Vec3::new(0.0, -0.5, 0.0)).norm() < 1e-15);
    assert!((vs.velocity - Vec3::new(0.0, 0.0, 0.5)).norm() < 1e-15);
    // with YADE's kinematics the rate is YADE's s × dv, the spin about the axis unchanged
    let ang = [Vec3::new(3.0, 0.0, 0.0), Vec3::new(1.0, 0.0, 0.0)];
    let k = Kinematics { pos: &pos, vel: &vel, ang_vel: &ang, link_mode: LinkKinematicsMode::Beam };
    let yade = virtual_sphere(&site, &k.with_link_mode(LinkKinematicsMode::Yade));
    assert!((yade.angular_velocity - Vec3::new(2.0, -2.0, 0.0)).norm() < 1e-15);
    assert_eq!(yade.velocity, vs.velocity);
}

#[test]
fn coincident_centres_use_the_fallback_normal() {
    let s = VirtualSphere {
        center: Vec3::new(1.0, 2.0, 3.0),
        velocity: Vec3::zeros(),
        angular_velocity: Vec3::zeros(),
    };
    let g = contact_geometry(&s, 0.1, &s, 0.2, &Vec3::y());
    assert_eq!(g.normal, Vec3::y());
    assert!((g.overlap - 0.3).abs() < 1e-15);
    assert!(g.point.iter().all(|x| x.is_finite()));
}

/// Two skeletons that have passed through each other (body 2's centre behind body 1's along
/// the contact's previous normal) keep that normal, and the overlap is measured along it:
/// larger than r1 + r2, growing the further through they are, continuous at d = 0.
#[test]
fn crossed_centres_keep_the_side_the_contact_was_made_on() {
    let at = |z: Real| VirtualSphere {
        center: Vec3::new(0.3, 0.0, z),
        velocity: Vec3::zeros(),
        angular_velocity: Vec3::zeros(),
    };
    let n0 = Vec3::new(0.0, 0.6, 0.8);
    let s1 = at(0.0);
    for (z, expected) in [(-0.01, 0.3 + 0.008), (-0.05, 0.3 + 0.04), (-1e-300, 0.3)] {
        let g = contact_geometry(&s1, 0.1, &at(z), 0.2, &n0);
        assert_eq!(g.normal, n0);
        assert!((g.overlap - expected).abs() < 1e-15, "z {z}: {}", g.overlap);
    }
    // on the side it was made on, the ordinary normal and overlap
    let g = contact_geometry(&s1, 0.1, &at(0.25), 0.2, &n0);
    assert!((g.normal - Vec3::z()).norm() < 1e-15);
    assert!((g.overlap - 0.05).abs() < 1e-15);
}

#[test]
fn zero_length_edge_keeps_interpolated_spin() {
    let pos = [Vec3::x(), Vec3::x()];
    let vel = [Vec3::zeros(), Vec3::z()];
    let ang = [Vec3::z(), Vec3::z()];
    let vs = virtual_sphere(
        &Site::edge(0, [0, 1], 0.3, 0.1),
        &Kinematics { pos: &pos, vel: &vel, ang_vel: &ang, link_mode: LinkKinematicsMode::Beam },
    );
    assert_eq!(vs.angular_velocity, Vec3::z());
}

/// Energy `½·kn·δ²` and node forces of the frictionless contact of two connections (nodes
/// 0–1 and 2–3 of `pos`, radius 0.1 each) with previous normal `n0`, the crossed normal
/// from [`crossing_normal`].
fn crossed_connections(pos: &[Vec3; 4], n0: &Vec3) -> (Real, [Vec3; 4]) {
    use crate::pairs::{connection_connection, ConnectionRef};
    let conn = |id: u32, a: usize| ConnectionRef {
        id,
        nodes: [a as u32, a as u32 + 1],
        ends: [pos[a], pos[a + 1]],
        radius: 0.1,
    };
    let c = connection_connection(&conn(0, 0), &conn(1, 2));
    let vel = [Vec3::zeros(); 4];
    let k = Kinematics { pos, vel: &vel, ang_vel: &vel, link_mode: LinkKinematicsMode::Beam };
    let (s1, s2) = (virtual_sphere(&c.site1, &k), virtual_sphere(&c.site2, &k));
    let g = contact_geometry_crossing(&s1, 0.1, &s2, 0.1, n0, || {
        crossing_normal(&c.site1, &c.site2, pos, n0)
    });
    let kn = 1e4;
    let force = g.normal * (kn * g.overlap);
    let mut f = [Vec3::zeros(); 4];
    for l in distribute_force(&c.site2, pos, &s2.center, &g.point, &force) {
        f[l.node as usize] += l.force;
    }
    for l in distribute_force(&c.site1, pos, &s1.center, &g.point, &(-force)) {
        f[l.node as usize] += l.force;
    }
    (0.5 * kn * g.overlap * g.overlap, f)
}

proptest! {
    /// Two connections crossed (the second's axis passed below the first's, against the
    /// contact's normal n0 = +z): the force of the crossed contact derives from its energy,
    /// `Σ f·dx = −dE` to second order for any small motion of the four nodes, turning the
    /// axes too. (With the normal kept at n0 the work misses how d·n0 changes as the closest
    /// points slide, and a crossed contact made or lost energy.)
    #[test]
    fn a_crossed_contact_of_connections_is_conservative(
        tilt in prop::array::uniform4(-0.3..0.3f64),
        depth in 0.01..0.15f64,
        dx in prop::array::uniform4(prop::array::uniform3(-1.0..1.0f64)),
    ) {
        let pos = [
            Vec3::new(-1.0, tilt[0], 0.0),
            Vec3::new(1.0, tilt[1], 0.1 * tilt[2]),
            Vec3::new(tilt[3], -1.0, -depth),
            Vec3::new(-tilt[3], 1.0, -depth + 0.1 * tilt[0]),
        ];
        let n0 = Vec3::z();
        let (e0, f) = crossed_connections(&pos, &n0);
        let h = 1e-6;
        let moved: [Vec3; 4] = std::array::from_fn(|i| pos[i] + Vec3::from(dx[i]) * h);
        let (e1, _) = crossed_connections(&moved, &n0);
        let work: Real = (0..4).map(|i| f[i].dot(&Vec3::from(dx[i])) * h).sum();
        let scale = f.iter().map(|x| x.norm()).sum::<Real>() * h;
        prop_assert!(
            (work + (e1 - e0)).abs() <= 1e-4 * scale,
            "work {work:e}, energy change {:e}", e1 - e0
        );
    }
}

/// The crossed normal follows the features: a face's normal for a node under it, the axes'
/// common perpendicular for two edges, both turned along the previous normal.
#[test]
fn crossed_normals_follow_the_features() {
    let pos = [
        Vec3::zeros(),
        Vec3::x(),
        Vec3::y(),
        Vec3::new(0.2, 0.2, -0.01),
        Vec3::new(0.0, 0.5, 1.0),
        Vec3::new(1.0, 0.5, 1.0),
    ];
    let face = Site::face(0, [0, 1, 2], [0.6, 0.2, 0.2], 0.1);
    let node = Site::particle(3, 0.1);
    let n0 = Vec3::new(0.1, -0.2, 0.97).normalize();
    assert_eq!(crossing_normal(&face, &node, &pos, &n0), Vec3::z());
    assert_eq!(crossing_normal(&node, &face, &pos, &-n0), -Vec3::z());
    let e1 = Site::edge(0, [0, 1], 0.3, 0.1);
    let e2 = Site::edge(1, [0, 2], 0.3, 0.1);
    assert_eq!(crossing_normal(&e1, &e2, &pos, &n0), Vec3::z());
    // a node on an edge: the previous normal less its component along the edge
    let n = crossing_normal(&e1, &node, &pos, &n0);
    assert!((n - Vec3::new(0.0, -0.2, 0.97).normalize()).norm() < 1e-15);
    // parallel edges: the previous normal less its component along them
    let e3 = Site::edge(2, [4, 5], 0.5, 0.1);
    let n = crossing_normal(&e1, &e3, &pos, &n0);
    assert!((n - Vec3::new(0.0, -0.2, 0.97).normalize()).norm() < 1e-15);
}

/// With YADE's kinematics an edge contact's moment about the virtual sphere goes to the two
/// nodes as torques `wₖ·τ` and the force as `wₖ·F` (YADE's
/// `Law2_ScGridCoGeom_FrictPhys_CundallStrack`): the forces sum to F and the moments about
/// any point to `(c − O) × F`, as with the force couple of the beam kinematics; particles
/// and faces are shared alike in both modes.
#[test]
fn yade_sharing_puts_the_edge_moment_on_the_nodes_as_torques() {
    let pos = [Vec3::zeros(), Vec3::new(0.1, 0.0, 0.02), Vec3::new(0.0, 0.1, 0.0)];
    let edge = Site::edge(0, [0, 1], 0.3, 0.005);
    let center = pos[0] * 0.7 + pos[1] * 0.3;
    let point = center + Vec3::new(0.0, 0.0, 0.004);
    let force = Vec3::new(0.2, -1.5, -3.0);
    let tau = (point - center).cross(&force);
    let yade = distribute_force_as(LinkKinematicsMode::Yade, &edge, &pos, &center, &point, &force);
    let beam = distribute_force(&edge, &pos, &center, &point, &force);
    for (slot, w) in [(0, 0.7), (1, 0.3)] {
        assert!((yade[slot].force - force * w).norm() < 1e-15);
        assert!((yade[slot].torque - tau * w).norm() < 1e-15);
    }
    // the beam kinematics put the perpendicular part of τ into the forces instead
    assert!((beam[0].force - force * 0.7).norm() > 1e-3);
    let moment = |loads: &[NodeLoad; 3], o: Vec3| -> Vec3 {
        loads[..2].iter().map(|l| (pos[l.node as usize] - o).cross(&l.force) + l.torque).sum()
    };
    let o = Vec3::new(0.3, -0.2, 0.5);
    for loads in [&yade, &beam] {
        let sum: Vec3 = loads[..2].iter().map(|l| l.force).sum();
        assert!((sum - force).norm() < 1e-14);
        assert!((moment(loads, o) - (point - o).cross(&force)).norm() < 1e-14);
    }
    let face = Site::face(0, [0, 1, 2], [0.2, 0.3, 0.5], 0.005);
    let fc = pos[0] * 0.2 + pos[1] * 0.3 + pos[2] * 0.5;
    assert_eq!(
        distribute_force_as(LinkKinematicsMode::Yade, &face, &pos, &fc, &point, &force),
        distribute_force(&face, &pos, &fc, &point, &force)
    );
}

/// YADE's non-ratcheting relative velocity: at zero overlap the contact point's relative
/// velocity; with an overlap δ the translation scaled by α = (r₁ + r₂)/(r₁ + r₂ − δ) and the
/// spins taken at the full radii.
#[test]
fn the_non_ratcheting_velocity_is_the_contact_points_at_zero_overlap() {
    let n = Vec3::new(0.0, 0.6, -0.8);
    let (r1, r2) = (0.1, 0.005);
    let s1 = VirtualSphere {
        center: Vec3::zeros(),
        velocity: Vec3::new(0.3, 0.2, -1.0),
        angular_velocity: Vec3::new(1.0, -2.0, 0.5),
    };
    let mut s2 = VirtualSphere {
        center: n * (r1 + r2),
        velocity: Vec3::new(-0.1, 0.0, 0.2),
        angular_velocity: Vec3::new(-3.0, 0.4, 7.0),
    };
    let at_point = |s1: &VirtualSphere, s2: &VirtualSphere, c: Vec3| {
        (s2.velocity + s2.angular_velocity.cross(&(c - s2.center)))
            - (s1.velocity + s1.angular_velocity.cross(&(c - s1.center)))
    };
    let touching = non_ratcheting_relative_velocity(&s1, r1, &s2, r2, &n, 0.0);
    assert!((touching - at_point(&s1, &s2, n * r1)).norm() < 1e-15);
    let delta = 1e-3;
    s2.center = n * (r1 + r2 - delta);
    let deep = non_ratcheting_relative_velocity(&s1, r1, &s2, r2, &n, delta);
    let alpha = (r1 + r2) / (r1 + r2 - delta);
    let expected = (s2.velocity - s1.velocity) * alpha + s2.angular_velocity.cross(&(-n * r2))
        - s1.angular_velocity.cross(&(n * r1));
    assert!((deep - expected).norm() < 1e-15);
    assert!((deep - at_point(&s1, &s2, n * (r1 - 0.5 * delta))).norm() > 1e-4);
    // crossed skeletons (δ ≥ r₁ + r₂): α capped at 2, the velocity finite
    for delta in [0.5 * (r1 + r2), r1 + r2, 3.0 * (r1 + r2)] {
        let crossed = non_ratcheting_relative_velocity(&s1, r1, &s2, r2, &n, delta);
        let capped = (s2.velocity - s1.velocity) * 2.0 + s2.angular_velocity.cross(&(-n * r2))
            - s1.angular_velocity.cross(&(n * r1));
        assert!((crossed - capped).norm() < 1e-14, "{delta}: {crossed}");
    }
}
