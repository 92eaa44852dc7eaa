//! The four-lane update of sphere contacts is the scalar path's (`continuing_pair`) to the
//! bit, lane by lane, wherever it takes a lane; and it takes the ordinary ones.

use crate::neighbours::{LawOut, PairContact, PairOutcome, Pushed};
use crate::pair_step::{continuing_pair, step_pair};
use crate::pair_store::BlockContacts;
use flexdem_contact::frictional_lanes::{
    update_sphere_pair_lanes, update_wall_sphere_lanes, ContactLanesOut, SpherePairLanes,
    WallSphereLanes, LANES,
};
use flexdem_contact::{FrictionalContact, FrictionalParams, Material};
use flexdem_elements::virtual_sphere::{Feature, Kinematics, NodeLoad};
use flexdem_elements::{Model, Particles};
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

/// A contact's parameters and state, drawn to cover the law's branches (sliding or sticking,
/// damped or not, a shear force or none, a normal turned a little or flipped, an offset)
/// for spheres of radii `r1`, `r2` touching along `normal`.
fn draw_contact(r: &mut Draw, normal: Vec3, r1: Real, r2: Real) -> PairContact {
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
}

/// Four pairs of spheres (0–1, 2–3, 4–5, 6–7) and their contacts ([`draw_contact`]),
/// touching or not, fast or slow, with a small or large twist, or a NaN.
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
        draw_contact(r, normal, r1, r2)
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
            let after = block.get(slot).expect("still there").state;
            compare_lane(&out, j, &contact.state, &after, &loads, elastic, &records, &case);
            sliding += usize::from(after.dissipated_friction != contact.state.dissipated_friction);
            pushed += records.len();
        }
    }
    // the ordinary lanes take the path, over every branch: most of the 16 000 lanes (the
    // others are apart, flipped, offset beyond their overlap or NaN by construction)
    assert!(
        taken_lanes > 10_000 && sliding > 1_000 && pushed > 3_000,
        "{taken_lanes} {sliding} {pushed}"
    );
}

/// Lane `j` of `out` against the scalar path's loads, state, energy and dashpots' record.
fn compare_lane(
    out: &ContactLanesOut,
    j: usize,
    before: &FrictionalContact,
    after: &FrictionalContact,
    loads: &[NodeLoad; 2],
    elastic: Real,
    records: &[Pushed],
    case: &str,
) {
    let mut state = *before;
    out.write_state(j, &mut state);
    assert_eq!(bits(state.shear_force), bits(after.shear_force), "{case}");
    assert_eq!(bits(state.normal), bits(after.normal), "{case}");
    assert_eq!(state.normal_force.to_bits(), after.normal_force.to_bits(), "{case}");
    let friction = state.dissipated_friction.to_bits();
    assert_eq!(friction, after.dissipated_friction.to_bits(), "{case}");
    let f2 = out.force_on_2(j);
    assert_eq!(bits(-f2), bits(loads[0].force), "{case}");
    assert_eq!(bits(f2), bits(loads[1].force), "{case}");
    let torques = out.torques(j);
    assert_eq!(bits(torques[0]), bits(loads[0].torque), "{case}");
    assert_eq!(bits(torques[1]), bits(loads[1].torque), "{case}");
    assert_eq!(out.elastic_energy(j).to_bits(), elastic.to_bits(), "{case}");
    assert_eq!(out.pushed & (1 << j) != 0, records.len() == 1, "{case}");
    if let [record] = records[..] {
        let (force, moments, viscous) = out.dashpot(j);
        assert_eq!(bits(force), bits(record.force), "{case}");
        assert_eq!(bits(moments[0]), bits(record.moments[0]), "{case}");
        assert_eq!(bits(moments[1]), bits(record.moments[1]), "{case}");
        assert_eq!(viscous.to_bits(), record.viscous.to_bits(), "{case}");
    }
}

/// Four walls (tilted, moving) and a sphere on each, with their contacts, drawn as
/// [`draw_case`] draws sphere pairs.
fn draw_wall_case(r: &mut Draw) -> (Model, [PairContact; LANES]) {
    let mut model = Model::new();
    let m = model.add_material(Material::new(1e7, 0.3, 1000.0, 0.5).unwrap()).unwrap();
    let contacts = std::array::from_fn(|_| {
        let normal = r.vector(1.0).normalize();
        let w = model.add_wall(r.vector(2.0), normal, m).unwrap();
        model.walls[w as usize].velocity = if r.one_in(3) { r.vector(0.5) } else { Vec3::zeros() };
        let radius = r.within(0.005, 0.02);
        let overlap = if r.one_in(8) { -1e-4 } else { r.within(0.0, 0.04) * radius };
        let wall = &model.walls[w as usize];
        // a point of the plane, then the centre at the gap r − δ above it
        let q = wall.point + r.vector(0.3);
        let c = q - normal * (q - wall.point).dot(&normal) + normal * (radius - overlap);
        let nan = r.one_in(40);
        let i = model.add_sphere(c, radius, m).unwrap() as usize;
        if nan {
            model.particles.pos[i].x = Real::NAN;
        }
        let fast = if r.one_in(3) { 5.0 } else { 0.01 };
        model.particles.vel[i] = r.vector(fast);
        let spin = if r.one_in(4) { 400.0 } else { 2.0 };
        model.particles.ang_vel[i] = r.vector(spin);
        draw_contact(r, normal, radius, radius)
    });
    (model, contacts)
}

#[test]
fn four_wall_lanes_are_the_scalar_path_to_the_bit() {
    let mut r = Draw(0x9E37_79B9_7F4A_7C15);
    let dt = 2e-5;
    let (mut taken_lanes, mut sliding, mut pushed) = (0, 0, 0);
    for case in 0..3000 {
        let (model, contacts) = draw_wall_case(&mut r);
        let p = &model.particles;
        let walls = std::array::from_fn(|j| {
            let w = &model.walls[j];
            [w.point, w.normal, w.velocity]
        });
        let at = WallSphereLanes {
            pos: &p.pos,
            vel: &p.vel,
            ang_vel: &p.ang_vel,
            radius: &p.radius,
            walls,
            spheres: std::array::from_fn(|j| j),
        };
        let out = update_wall_sphere_lanes(
            contacts.each_ref().map(|c| &c.params),
            contacts.each_ref().map(|c| &c.state),
            &at,
            dt,
        );
        let k = Kinematics::of(p);
        for (j, contact) in contacts.iter().enumerate() {
            let mut block = BlockContacts::with_room(1);
            let mut slot = block.insert(*contact);
            let mut records: Vec<Pushed> = vec![];
            let mut law = LawOut::new(&mut records, 9);
            let key = (Feature::Wall(j as u32), Feature::Particle(j as u32));
            let mut o = PairOutcome::default();
            step_pair(&model, &k, &key, &mut slot, &mut block, dt, &mut o, &mut law);
            let elastic = law.elastic;
            if out.taken & (1 << j) == 0 {
                continue;
            }
            taken_lanes += 1;
            let case = format!("case {case} lane {j}");
            let after = block.get(slot).unwrap_or_else(|| panic!("{case}: the contact ended"));
            compare_lane(&out, j, &contact.state, &after.state, &o.loads, elastic, &records, &case);
            assert_eq!(o.loads[1].node, j as u32, "{case}");
            let (normal_force, shear_force) = out.applied(j);
            assert_eq!(normal_force.to_bits(), o.applied.normal_force.to_bits(), "{case}");
            assert_eq!(bits(shear_force), bits(o.applied.shear_force), "{case}");
            assert_eq!(out.sliding & (1 << j) != 0, o.applied.sliding, "{case}");
            sliding += usize::from(o.applied.sliding);
            pushed += records.len();
        }
    }
    assert!(
        taken_lanes > 8_000 && sliding > 1_000 && pushed > 3_000,
        "{taken_lanes} {sliding} {pushed}"
    );
}
