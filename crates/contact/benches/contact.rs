//! Criterion benchmarks of the contact-law kernels: one frictional-contact update and one
//! beam-link update (beam and yade kinematics), and four links at once by the lanes of
//! `link_lanes` against four scalar updates of the same links. Inputs are generated from a fixed seed outside
//! the timed closures; each iteration updates one contact of a pool so that the state and the
//! inputs vary from call to call.
use criterion::{criterion_group, criterion_main, Criterion};
use flexdem_contact::link_lanes::{update_link_lanes, LaneNodes, LANES};
use flexdem_contact::{
    update_frictional_contact, update_link, update_link_parts, ContactKinematics,
    FrictionalContact, FrictionalParams, LinkKinematics, LinkKinematicsMode, LinkParams,
    LinkPlastic, LinkState, Material,
};
use flexdem_geom::{Real, Vec3};
use nalgebra::UnitQuaternion;
use std::hint::black_box;

const POOL: usize = 1024;

/// Small deterministic generator (SplitMix64), uniform in [-1, 1).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> Real {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as Real / (1u64 << 52) as Real - 1.0
    }

    fn vec(&mut self, s: Real) -> Vec3 {
        Vec3::new(self.next(), self.next(), self.next()) * s
    }

    fn unit(&mut self) -> Vec3 {
        loop {
            let v = self.vec(1.0);
            if v.norm() > 0.1 {
                return v.normalize();
            }
        }
    }
}

fn material() -> Material {
    Material::new(1e8, 0.3, 1000.0, 0.5)
        .unwrap()
        .with_tensile_strength(Some(1e7))
        .with_shear_strength(Some(1e7))
}

fn frictional(c: &mut Criterion) {
    let mut rng = Rng(42);
    let p = FrictionalParams { kn: 1e6, ks: 3e5, tan_phi: 0.5, cn: 0.0, ct: 0.0 };
    let mut states: Vec<FrictionalContact> = Vec::with_capacity(POOL);
    let mut kins: Vec<ContactKinematics> = Vec::with_capacity(POOL);
    for _ in 0..POOL {
        let n0 = rng.unit();
        let mut s = FrictionalContact::new(n0);
        let t = rng.vec(1.0);
        s.shear_force = (t - n0 * n0.dot(&t)) * 10.0;
        states.push(s);
        kins.push(ContactKinematics {
            normal: (n0 + rng.vec(0.01)).normalize(),
            overlap: 1e-4 * (1.5 + rng.next()),
            relative_velocity: rng.vec(0.1),
            spin_about_normal: rng.next(),
        });
    }
    let mut i = 0;
    c.bench_function("frictional_contact_update", |b| {
        b.iter(|| {
            i = (i + 1) % POOL;
            let f = update_frictional_contact(
                black_box(&p),
                &mut states[i],
                black_box(&kins[i]),
                black_box(1e-5),
            );
            black_box(f)
        })
    });
}

/// A pool of links of `mode` (states and kinematics), loaded a little.
fn link_pool(mode: LinkKinematicsMode) -> (LinkParams, Vec<LinkState>, Vec<LinkKinematics>) {
    let mut rng = Rng(7);
    let m = material();
    let (l0, r) = (0.1, 0.01);
    let p = LinkParams::from_material(&m, r, l0, mode);
    let mut states: Vec<LinkState> = Vec::with_capacity(POOL);
    let mut kins: Vec<LinkKinematics> = Vec::with_capacity(POOL);
    for _ in 0..POOL {
        let dir = rng.unit();
        let x1 = rng.vec(1.0);
        let q1 = UnitQuaternion::from_scaled_axis(rng.vec(3.0));
        let q2 = UnitQuaternion::from_scaled_axis(rng.vec(3.0));
        let mut s = LinkState::new(x1, x1 + dir * l0, q1, q2);
        let t = rng.vec(1.0);
        s.shear_force = (t - dir * dir.dot(&t)) * 0.1;
        states.push(s);
        kins.push(LinkKinematics {
            x1,
            x2: x1 + dir * l0 + rng.vec(1e-5),
            v1: rng.vec(1e-3),
            v2: rng.vec(1e-3),
            w1: rng.vec(1e-2),
            w2: rng.vec(1e-2),
            q1: UnitQuaternion::from_scaled_axis(rng.vec(1e-3)) * q1,
            q2: UnitQuaternion::from_scaled_axis(rng.vec(1e-3)) * q2,
        });
    }
    (p, states, kins)
}

fn link(c: &mut Criterion, mode: LinkKinematicsMode, name: &str) {
    let (p, mut states, kins) = link_pool(mode);
    let mut plastic = vec![LinkPlastic::default(); POOL];
    let mut i = 0;
    c.bench_function(name, |b| {
        b.iter(|| {
            i = (i + 1) % POOL;
            let (s, pl) = (&mut states[i], &mut plastic[i]);
            let f = update_link(black_box(&p), s, pl, black_box(&kins[i]), black_box(1e-5));
            black_box(f)
        })
    });
}

/// Four consecutive links of the pool per iteration: by the lanes, and by four scalar updates.
fn four_links(c: &mut Criterion) {
    let (p, states, kins) = link_pool(LinkKinematicsMode::Beam);
    // node 2k and 2k + 1 of link k, in the particles' arrays
    let pos: Vec<Vec3> = kins.iter().flat_map(|k| [k.x1, k.x2]).collect();
    let vel: Vec<Vec3> = kins.iter().flat_map(|k| [k.v1, k.v2]).collect();
    let ang_vel: Vec<Vec3> = kins.iter().flat_map(|k| [k.w1, k.w2]).collect();
    let ori: Vec<UnitQuaternion<Real>> = kins.iter().flat_map(|k| [k.q1, k.q2]).collect();
    let mut lane_states = states.clone();
    let mut i = 0;
    c.bench_function("four_links_lanes", |b| {
        b.iter(|| {
            i = (i + LANES) % POOL;
            let nodes = std::array::from_fn(|j| [2 * (i + j), 2 * (i + j) + 1]);
            let at = LaneNodes { pos: &pos, vel: &vel, ang_vel: &ang_vel, ori: &ori, nodes };
            let four: &mut [LinkState; LANES] =
                (&mut lane_states[i..i + LANES]).try_into().expect("four links");
            let classes = [&p.class; LANES];
            let springs = [&p.spring; LANES];
            let mut e = 0.0;
            let taken = update_link_lanes(classes, springs, four, &at, black_box(1e-5), |_, l| {
                e += l.elastic_energy
            });
            black_box((taken, e))
        })
    });
    let mut scalar_states = states;
    let mut plastic = LinkPlastic::default();
    let mut i = 0;
    c.bench_function("four_links_scalar", |b| {
        b.iter(|| {
            i = (i + LANES) % POOL;
            let mut e = 0.0;
            for j in 0..LANES {
                let s = &mut scalar_states[i + j];
                let k = black_box(&kins[i + j]);
                e += update_link_parts(&p.class, &p.spring, s, &mut plastic, k, black_box(1e-5))
                    .elastic_energy;
            }
            black_box(e)
        })
    });
}

fn links(c: &mut Criterion) {
    link(c, LinkKinematicsMode::Beam, "link_update_beam");
    link(c, LinkKinematicsMode::Yade, "link_update_yade");
    four_links(c);
}

criterion_group!(benches, frictional, links);
criterion_main!(benches);
