//! The four-lane update of sphere contacts is the scalar path's (`continuing_pair`) to the
//! bit, lane by lane, wherever it takes a lane; and it takes the ordinary ones.

use crate::neighbours::{LawOut, PairContact, Pushed};
use crate::pair_step::continuing_pair;
use crate::pair_store::BlockContacts;
use flexdem_contact::frictional_lanes::{update_sphere_pair_lanes, SpherePairLanes, LANES};
use flexdem_contact::{FrictionalContact, FrictionalParams};
use flexdem_elements::Particles;
use flexdem_geom::{Real, Vec3};

/// A small deterministic generator (xorshift), uniform in [0, 1).
struct Draw(u64);

impl Draw {
    fn next(&mut self) -> Real {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as Real / (1u64 << 53) as Real
    }
    fn within(&mut self, a: Real, b: Real) -> Real {
        a + (b - a) * self.next()
    }
    fn vector(&mut self, scale: Real) -> Vec3 {
        Vec3::new(self.within(-1.0, 1.0), self.within(-1.0, 1.0), self.within(-1.0, 1.0)) * scale
    }
    fn one_in(&mut self, n: u32) -> bool {
        self.next() * Real::from(n) < 1.0
    }
}

/// Four pairs of spheres (0–1, 2–3, 4–5, 6–7) and their contacts, drawn to cover the law's
/// branches: touching or not, sliding or sticking, damped or not, a shear force or none, a
/// small or large twist, a normal turned a little or flipped, an offset, a NaN.
fn draw_case(r: &mut Draw) -> (Particles, [PairContact; LANES]) {
    let mut p = Particles::default();
    let contacts = std::array::from_fn(|_| {
        let (r1, r2) = (r.within(0.005, 0.02), r.within(0.005, 0.02));
        let c1 = r.vector(2.0);
        let normal = r.vector(1.0).normalize();
        let overlap = if r.one_in(8) { -1e-4 } else { r.within(0.0, 0.02) * (r1 + r2) };
        let mut c2 = c1 + normal * (r1 + r2 - overlap);
        if r.one_in(40) {
            c2.y = Real::NAN;
        }
        let fast = if r.one_in(3) { 5.0 } else { 0.01 };
        let spin = if r.one_in(4) { 400.0 } else { 2.0 };
        for (c, radius) in [(c1, r1), (c2, r2)] {
            p.pos.push(c);
            p.radius.push(radius);
            p.vel.push(r.vector(fast));
            p.ang_vel.push(r.vector(spin));
        }
        let damped = r.one_in(2);
        let params = FrictionalParams {
            kn: r.within(1e4, 1e6),
            ks: if r.one_in(20) { 0.0 } else { r.within(1e3, 1e6) },
            tan_phi: r.within(0.0, 0.8),
            cn: if damped && !r.one_in(4) { r.within(0.0, 30.0) } else { 0.0 },
            ct: if damped && !r.one_in(4) { r.within(0.0, 30.0) } else { 0.0 },
        };
        let previous = if r.one_in(30) {
            -normal
        } else {
            let turn = if r.one_in(2) { 1e-3 } else { 0.2 };
            (normal + r.vector(turn)).normalize()
        };
        let mut state = FrictionalContact::new(previous);
        if !r.one_in(5) {
            let t = r.vector(1.0);
            state.shear_force = (t - previous * previous.dot(&t)) * r.within(0.0, 50.0);
        }
        if r.one_in(10) {
            state.overlap_offset = r.within(0.0, 0.03) * (r1 + r2);
        }
        state.dissipated_friction = r.within(0.0, 1.0);
        PairContact { params, state }
    });
    (p, contacts)
}

fn bits(v: Vec3) -> [u64; 3] {
    v.map(Real::to_bits).into()
}

#[test]
fn four_lanes_are_the_scalar_path_to_the_bit() {
    let mut r = Draw(0x2545_F491_4F6C_DD1D);
    let dt = 2e-5;
    let (mut taken_lanes, mut sliding, mut pushed) = (0, 0, 0);
    for case in 0..4000 {
        let (p, contacts) = draw_case(&mut r);
        let pairs: [[usize; 2]; LANES] = std::array::from_fn(|j| [2 * j, 2 * j + 1]);
        let at = SpherePairLanes {
            pos: &p.pos,
            vel: &p.vel,
            ang_vel: &p.ang_vel,
            radius: &p.radius,
            pairs,
        };
        let out = update_sphere_pair_lanes(
            contacts.each_ref().map(|c| &c.params),
            contacts.each_ref().map(|c| &c.state),
            &at,
            dt,
        );
        for (j, contact) in contacts.iter().enumerate() {
            let mut block = BlockContacts::with_room(1);
            let slot = block.insert(*contact);
            let mut records: Vec<Pushed> = vec![];
            let mut law = LawOut::new(&mut records, 9);
            let [i1, i2] = pairs[j].map(|i| i as u32);
            let scalar = continuing_pair(&p, i1, i2, slot, &mut block, dt, &mut law);
            let elastic = law.elastic;
            if out.taken & (1 << j) == 0 {
                continue;
            }
            taken_lanes += 1;
            let case = format!("case {case} lane {j}");
            let loads = scalar.unwrap_or_else(|| panic!("{case}: the scalar path left it"));
            let mut state = contact.state;
            out.write_state(j, &mut state);
            let after = block.get(slot).expect("still there").state;
            assert_eq!(bits(state.shear_force), bits(after.shear_force), "{case}");
            assert_eq!(bits(state.normal), bits(after.normal), "{case}");
            assert_eq!(state.normal_force.to_bits(), after.normal_force.to_bits(), "{case}");
            let friction = state.dissipated_friction.to_bits();
            assert_eq!(friction, after.dissipated_friction.to_bits(), "{case}");
            assert_eq!(state.overlap_offset.to_bits(), after.overlap_offset.to_bits());
            sliding += usize::from(after.dissipated_friction != contact.state.dissipated_friction);
            let f2 = out.force_on_2(j);
            assert_eq!(bits(-f2), bits(loads[0].force), "{case}");
            assert_eq!(bits(f2), bits(loads[1].force), "{case}");
            let torques = out.torques(j);
            assert_eq!(bits(torques[0]), bits(loads[0].torque), "{case}");
            assert_eq!(bits(torques[1]), bits(loads[1].torque), "{case}");
            assert_eq!(out.elastic_energy(j).to_bits(), elastic.to_bits(), "{case}");
            assert_eq!(out.pushed & (1 << j) != 0, records.len() == 1, "{case}");
            if let [record] = records[..] {
                pushed += 1;
                let (force, moments, viscous) = out.dashpot(j);
                assert_eq!(bits(force), bits(record.force), "{case}");
                assert_eq!(bits(moments[0]), bits(record.moments[0]), "{case}");
                assert_eq!(bits(moments[1]), bits(record.moments[1]), "{case}");
                assert_eq!(viscous.to_bits(), record.viscous.to_bits(), "{case}");
            }
        }
    }
    // the ordinary lanes take the path, over every branch: most of the 16 000 lanes (the
    // others are apart, flipped, offset beyond their overlap or NaN by construction)
    assert!(
        taken_lanes > 10_000 && sliding > 1_000 && pushed > 3_000,
        "{taken_lanes} {sliding} {pushed}"
    );
}
