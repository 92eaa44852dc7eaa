//! Criterion benchmarks of one contact per pair kind, end to end: closest features
//! (geometry), the contact law, and the distribution of the force to the nodes; and of one
//! beam link update. `cargo bench -p flexdem-integrate --bench kernels`.
//!
//! Inputs are generated once from a fixed seed (touching configurations with random
//! orientations and offsets) and cycled through inside the timed closure.

use criterion::{criterion_group, criterion_main, Criterion};
use flexdem_contact::{
    update_frictional_contact, update_link, ContactKinematics, FrictionalContact, FrictionalParams,
    LinkKinematics, LinkKinematicsMode, LinkParams, LinkPlastic, LinkState, Material,
};
use flexdem_elements::pairs::{self, Candidate, ConnectionRef, PFacetRef, SphereRef};
use flexdem_elements::virtual_sphere::{
    contact_geometry, distribute_force, virtual_sphere, Kinematics,
};
use flexdem_geom::Vec3;
use nalgebra::UnitQuaternion;
use std::hint::black_box;

const N: usize = 256;

/// xorshift64*: a small deterministic generator for the inputs.
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    }
    fn v(&mut self, s: f64) -> Vec3 {
        Vec3::new(self.next() - 0.5, self.next() - 0.5, self.next() - 0.5) * s
    }
}

/// Positions, velocities, spins of 8 particles: 0..3 carry body 1, 3..6 body 2 (up to
/// three nodes each).
struct Scene {
    pos: Vec<Vec3>,
    vel: Vec<Vec3>,
    ang: Vec<Vec3>,
}

fn scene(rng: &mut Rng, body1: &[Vec3], body2: &[Vec3]) -> Scene {
    let mut pos = vec![Vec3::zeros(); 6];
    pos[..body1.len()].copy_from_slice(body1);
    pos[3..3 + body2.len()].copy_from_slice(body2);
    Scene {
        pos,
        vel: (0..6).map(|_| rng.v(0.1)).collect(),
        ang: (0..6).map(|_| rng.v(1.0)).collect(),
    }
}

/// A triangle of size about 1 around `c`, lying roughly in the plane z = c.z.
fn triangle(rng: &mut Rng, c: Vec3) -> [Vec3; 3] {
    [
        c + Vec3::new(-0.5, -0.4, 0.0) + rng.v(0.1),
        c + Vec3::new(0.5, -0.4, 0.0) + rng.v(0.1),
        c + Vec3::new(0.0, 0.6, 0.0) + rng.v(0.1),
    ]
}

/// One contact step: law and distribution of an already found candidate.
fn contact_step(
    c: &Candidate,
    s: &Scene,
    params: &FrictionalParams,
    state: &mut FrictionalContact,
) -> Vec3 {
    let k = Kinematics { pos: &s.pos, vel: &s.vel, ang_vel: &s.ang, link_mode: Default::default() };
    let vs1 = virtual_sphere(&c.site1, &k);
    let vs2 = virtual_sphere(&c.site2, &k);
    let g = contact_geometry(&vs1, c.site1.radius, &vs2, c.site2.radius, &state.normal);
    let f = update_frictional_contact(
        params,
        state,
        &ContactKinematics {
            normal: g.normal,
            overlap: g.overlap,
            relative_velocity: g.relative_velocity,
            spin_about_normal: g.spin_about_normal,
        },
        1e-5,
    );
    let l1 = distribute_force(&c.site1, &s.pos, &vs1.center, &g.point, &(-f.force_on_2));
    let l2 = distribute_force(&c.site2, &s.pos, &vs2.center, &g.point, &f.force_on_2);
    l1[0].force + l2[0].force + l1[0].torque + l2[0].torque
}

fn kernels(crit: &mut Criterion) {
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    let m = Material::new(1e8, 0.3, 2600.0, 0.5).unwrap();
    // the material has no damping: the effective mass (here two 0.1 m spheres) makes no dashpot
    let params = FrictionalParams::from_materials(&m, 0.1, &m, 0.1, 5.4);
    let (r, rs) = (0.1, 0.3);
    // pair builders: (name, closure producing the candidate from a scene)
    type Maker = fn(&Scene, f64, f64) -> Candidate;
    let sphere =
        |s: &Scene, i: usize, r: f64| SphereRef { id: i as u32, center: s.pos[i], radius: r };
    let _ = sphere;
    let cases: Vec<(&str, Vec<Scene>, Maker)> = vec![
        (
            "sphere_sphere",
            (0..N)
                .map(|_| {
                    let a = rng.v(1.0);
                    let d = rng.v(1.0).normalize() * 0.55;
                    scene(&mut rng, &[a], &[a + d])
                })
                .collect(),
            |s, _r, rs| {
                pairs::sphere_sphere(
                    &SphereRef { id: 0, center: s.pos[0], radius: rs },
                    &SphereRef { id: 3, center: s.pos[3], radius: rs },
                )
            },
        ),
        (
            "sphere_connection",
            (0..N)
                .map(|_| {
                    let a = rng.v(1.0);
                    let b = a + Vec3::new(1.0, 0.0, 0.0) + rng.v(0.2);
                    let p = a.lerp(&b, rng.next()) + Vec3::new(0.0, 0.0, 0.35);
                    scene(&mut rng, &[p], &[a, b])
                })
                .collect(),
            |s, r, rs| {
                pairs::sphere_connection(
                    &SphereRef { id: 0, center: s.pos[0], radius: rs },
                    &ConnectionRef { id: 0, nodes: [3, 4], ends: [s.pos[3], s.pos[4]], radius: r },
                )
            },
        ),
        (
            "connection_connection",
            (0..N)
                .map(|_| {
                    let a = rng.v(1.0);
                    let b = a + Vec3::new(1.0, 0.0, 0.0) + rng.v(0.2);
                    let m = a.lerp(&b, rng.next()) + Vec3::new(0.0, 0.0, 0.19);
                    let d = Vec3::new(0.0, 0.5, 0.0) + rng.v(0.3);
                    scene(&mut rng, &[a, b], &[m - d, m + d])
                })
                .collect(),
            |s, r, _| {
                pairs::connection_connection(
                    &ConnectionRef { id: 0, nodes: [0, 1], ends: [s.pos[0], s.pos[1]], radius: r },
                    &ConnectionRef { id: 1, nodes: [3, 4], ends: [s.pos[3], s.pos[4]], radius: r },
                )
            },
        ),
        (
            "sphere_pfacet",
            (0..N)
                .map(|_| {
                    let c = rng.v(1.0);
                    let t = triangle(&mut rng, c);
                    let p = c
                        + rng.v(0.6).component_mul(&Vec3::new(1.0, 1.0, 0.0))
                        + Vec3::new(0.0, 0.0, 0.35);
                    scene(&mut rng, &[p], &t)
                })
                .collect(),
            |s, r, rs| {
                pairs::sphere_pfacet(
                    &SphereRef { id: 0, center: s.pos[0], radius: rs },
                    &PFacetRef {
                        id: 0,
                        nodes: [3, 4, 5],
                        connections: [0, 1, 2],
                        corners: [s.pos[3], s.pos[4], s.pos[5]],
                        radius: r,
                    },
                )
            },
        ),
        (
            "connection_pfacet",
            (0..N)
                .map(|_| {
                    let c = rng.v(1.0);
                    let t = triangle(&mut rng, c);
                    let d = Vec3::new(0.6, 0.2, 0.0) + rng.v(0.2);
                    let m = c + Vec3::new(0.0, 0.0, 0.19);
                    scene(&mut rng, &[m - d, m + d], &t)
                })
                .collect(),
            |s, r, _| {
                pairs::connection_pfacet(
                    &ConnectionRef { id: 0, nodes: [0, 1], ends: [s.pos[0], s.pos[1]], radius: r },
                    &PFacetRef {
                        id: 0,
                        nodes: [3, 4, 5],
                        connections: [0, 1, 2],
                        corners: [s.pos[3], s.pos[4], s.pos[5]],
                        radius: r,
                    },
                )
            },
        ),
        (
            "pfacet_pfacet",
            (0..N)
                .map(|_| {
                    let c = rng.v(1.0);
                    let t1 = triangle(&mut rng, c);
                    let t2 = triangle(&mut rng, c + Vec3::new(0.3, 0.2, 0.19))
                        .map(|p| p + Vec3::new(0.0, 0.0, 0.0));
                    scene(&mut rng, &t1, &t2)
                })
                .collect(),
            |s, r, _| {
                pairs::pfacet_pfacet(
                    &PFacetRef {
                        id: 0,
                        nodes: [0, 1, 2],
                        connections: [0, 1, 2],
                        corners: [s.pos[0], s.pos[1], s.pos[2]],
                        radius: r,
                    },
                    &PFacetRef {
                        id: 1,
                        nodes: [3, 4, 5],
                        connections: [3, 4, 5],
                        corners: [s.pos[3], s.pos[4], s.pos[5]],
                        radius: r,
                    },
                )
            },
        ),
    ];
    for (name, scenes, make) in &cases {
        let touching = scenes.iter().filter(|s| make(s, r, rs).overlap() > 0.0).count();
        assert!(touching > N / 2, "{name}: only {touching} of {N} inputs touch");
        let mut states: Vec<FrictionalContact> =
            scenes.iter().map(|_| FrictionalContact::new(Vec3::z())).collect();
        let mut i = 0;
        crit.bench_function(&format!("contact/{name}"), |b| {
            b.iter(|| {
                i = (i + 1) % N;
                let s = &scenes[i];
                let c = make(black_box(s), r, rs);
                black_box(contact_step(&c, s, &params, &mut states[i]))
            })
        });
    }

    // one beam link update (both kinematics)
    let steel = Material::new(2e11, 0.3, 7850.0, 0.5).unwrap();
    for (label, mode) in [("beam", LinkKinematicsMode::Beam), ("yade", LinkKinematicsMode::Yade)] {
        let params = LinkParams::from_material(&steel, 0.01, 0.1, mode);
        let inputs: Vec<LinkKinematics> = (0..N)
            .map(|_| LinkKinematics {
                x1: rng.v(1e-4),
                x2: Vec3::new(0.1, 0.0, 0.0) + rng.v(1e-4),
                v1: rng.v(1e-3),
                v2: rng.v(1e-3),
                w1: rng.v(1e-2),
                w2: rng.v(1e-2),
                q1: UnitQuaternion::from_scaled_axis(rng.v(1e-3)),
                q2: UnitQuaternion::from_scaled_axis(rng.v(1e-3)),
            })
            .collect();
        let mut states: Vec<LinkState> = inputs
            .iter()
            .map(|_| {
                LinkState::new(
                    Vec3::zeros(),
                    Vec3::new(0.1, 0.0, 0.0),
                    UnitQuaternion::identity(),
                    UnitQuaternion::identity(),
                )
            })
            .collect();
        let mut plastic = vec![LinkPlastic::default(); N];
        let mut i = 0;
        crit.bench_function(&format!("link/{label}"), |b| {
            b.iter(|| {
                i = (i + 1) % N;
                let (s, p) = (&mut states[i], &mut plastic[i]);
                black_box(update_link(&params, s, p, black_box(&inputs[i]), 1e-6))
            })
        });
    }
}

criterion_group!(benches, kernels);
criterion_main!(benches);
