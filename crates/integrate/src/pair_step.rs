//! One step of a candidate pair of the neighbour list (`neighbours.rs`): whether two free
//! spheres are apart before anything else (`apart`), the hot case of a sphere–sphere contact
//! that goes on (`continuing_spheres`: one distance, the law, two loads), and the general
//! step (`step_pair`) that finds a first touch, an end, a wall's contact, with their energy
//! accounted for as the general pipeline (`contacts.rs`) accounts for them. The chunk pass
//! (`pair_chunk.rs`) calls these for the pairs its four-lane path does not take, and its
//! tests take `continuing_pair` and `step_pair` as the bits the lanes must give.

use crate::contact::{
    birth_jump, geometry_of, law_kinematics, new_contact, sphere_touching, wall_touching,
};
use crate::dashpots::account_ended_springs;
use crate::neighbours::{sites, AppliedForce, LawOut, PairContact, PairOutcome, Pushed};
use crate::pair_keys::ContactKey;
use crate::pair_store::{BlockContacts, NO_CONTACT};
use flexdem_contact::update_frictional_contact;
use flexdem_elements::virtual_sphere::{ContactGeometry, Feature, Kinematics, NodeLoad};
use flexdem_elements::{Model, Particles};
use flexdem_geom::{Real, Vec3};

/// Whether the pair of `key` is two spheres whose centres are farther apart than their radii
/// with 1e-9 to spare: most candidates do not touch, and this conservative test (the exact
/// one is `r_i + r_j − |d| > 0`) tells them first. False for a wall's pair.
#[inline(always)]
pub(crate) fn apart(p: &Particles, key: &ContactKey) -> bool {
    match *key {
        (Feature::Particle(i), Feature::Particle(j)) => spheres_apart(p, i as usize, j as usize),
        _ => false,
    }
}

/// Whether wall `w` and free sphere `i` do not touch: `wall_touching`'s test (r − gap > 0,
/// gap = (c − x_w)·n) fails. A wall's pair without a contact that does not touch has
/// nothing to do in its step.
#[inline(always)]
pub(crate) fn wall_apart(model: &Model, w: u32, i: u32) -> bool {
    let wall = &model.walls[w as usize];
    let p = &model.particles;
    let gap = (p.pos[i as usize] - wall.point).dot(&wall.normal);
    !(p.radius[i as usize] - gap > 0.0)
}

/// [`apart`] of the free spheres `i` and `j`.
#[inline(always)]
pub(crate) fn spheres_apart(p: &Particles, i: usize, j: usize) -> bool {
    centres_apart(&p.pos, &p.radius, i, j)
}

/// [`spheres_apart`] from the particles' positions and radii.
#[inline(always)]
fn centres_apart(pos: &[Vec3], radius: &[Real], i: usize, j: usize) -> bool {
    let reach = radius[i] + radius[j];
    (pos[j] - pos[i]).norm_squared() > reach * reach * (1.0 + 1e-9)
}

/// The first of the candidates `from..` (two free spheres each, `ids`, with their `slots`)
/// that is not a pair [`spheres_apart`] without a contact, or `ids.len()`: the runs of
/// candidates that do not touch (most of them) skipped in a loop of their own, whose few
/// values stay in registers (in the pass's loop, which holds the law's, they were reloaded
/// from the stack for each candidate: a fourth of a pair apart's instructions).
#[inline(always)]
pub(crate) fn first_not_apart(
    p: &Particles,
    ids: &[(u32, u32)],
    slots: &[u32],
    from: usize,
) -> usize {
    // (the slices once, of one length: one bounds check a particle)
    let pos = &p.pos[..];
    let radius = &p.radius[..pos.len()];
    let mut n = from;
    while n < ids.len() && n < slots.len() {
        let (i, j) = (ids[n].0 as usize, ids[n].1 as usize);
        if slots[n] != NO_CONTACT || !centres_apart(pos, radius, i, j) {
            break;
        }
        n += 1;
    }
    n
}

/// The hot case of [`step_pair`], a sphere–sphere contact that goes on: its law, and its
/// two node loads (`law` as `step_pair` fills it); None where `step_pair` has to decide (not
/// two spheres, not touching before, apart now, centres crossed). One distance, and no
/// candidate, sites or owners: the general path computes the same numbers (`Candidate`'s
/// overlap is r₁ + r₂ − |c₂ − c₁| too, and it then calls `sphere_geometry` alike). Nothing
/// of [`PairOutcome`] but its loads: a pair that goes on adds nothing to the births and ends.
#[inline(always)]
pub(crate) fn continuing_spheres(
    p: &Particles,
    key: &ContactKey,
    slot: &u32,
    block: &mut BlockContacts<PairContact>,
    dt: Real,
    law: &mut LawOut<'_>,
) -> Option<[NodeLoad; 2]> {
    let (Feature::Particle(i), Feature::Particle(j)) = *key else { return None };
    continuing_pair(p, i, j, *slot, block, dt, law)
}

/// [`continuing_spheres`] of the free spheres `i` and `j` (the key of a sphere pair).
#[inline(always)]
pub(crate) fn continuing_pair(
    p: &Particles,
    i: u32,
    j: u32,
    slot: u32,
    block: &mut BlockContacts<PairContact>,
    dt: Real,
    law: &mut LawOut<'_>,
) -> Option<[NodeLoad; 2]> {
    let c = block.get_mut(slot)?;
    let (i, j) = (i as usize, j as usize);
    let g = sphere_geometry(p, i, j, &c.state.normal).filter(|g| g.overlap > 0.0)?;
    Some(apply_law(c, &g, [i as u32, j as u32], [p.pos[i], p.pos[j]], dt, law).0)
}

/// One pair's step (see [`NeighbourList::update`]): `slot` is its index into `block`, the
/// contacts of its block of candidates (see `pair_store.rs`); what the law gave a pair that
/// touches after it goes to `law`.
#[allow(clippy::too_many_arguments, reason = "one pair's inputs and its two outputs")]
pub(crate) fn step_pair(
    model: &Model,
    k: &Kinematics<'_>,
    key: &ContactKey,
    slot: &mut u32,
    block: &mut BlockContacts<PairContact>,
    dt: Real,
    out: &mut PairOutcome,
    law: &mut LawOut<'_>,
) {
    if let Some(loads) = continuing_spheres(&model.particles, key, slot, block, dt, law) {
        out.loads = loads;
        return;
    }
    let touching = match *key {
        (Feature::Particle(i), Feature::Particle(j)) => {
            if *slot == NO_CONTACT && apart(&model.particles, key) {
                return;
            }
            sphere_touching(model, i, j)
        }
        (Feature::Wall(w), Feature::Particle(i)) => wall_touching(model, w, i),
        _ => None,
    };
    let (site1, site2) = sites(model, key);
    match (touching, block.get(*slot)) {
        (Some(t), None) => {
            // a first touch (a free sphere's contact can be neither handed over nor split):
            // on time or late, as `ContactPipeline::settle_births` says
            let c = new_contact(model, &t);
            let (_, _, g) = geometry_of(model, k, &site1, &site2, &c.state.normal);
            let approach = -g.relative_velocity.dot(&g.normal);
            let reach = site1.radius + site2.radius;
            out.born_energy = birth_jump(&c.params, &c.state, &g, dt);
            out.born_deep = g.overlap - approach * dt > 1e-12 * reach;
            out.fresh = true;
            let made = PairContact { params: c.params, state: c.state };
            *slot = block.insert(made);
        }
        (None, Some(c)) => {
            out.ended_dissipation = c.state.dissipated_friction;
            let (_, _, g) = geometry_of(model, k, &site1, &site2, &c.state.normal);
            let now = g.overlap - c.state.overlap_offset;
            // (from the outcome's zeros: the sums they go to are the same as if the first
            // term were assigned)
            let (params, state, v) = (&c.params, &c.state, &g.relative_velocity);
            let (put_in, released) = (&mut out.born_energy, &mut out.released);
            account_ended_springs(params, state, now, v, dt, put_in, released);
            block.remove(*slot);
            *slot = NO_CONTACT;
        }
        _ => {}
    }
    if let Some(c) = block.get_mut(*slot) {
        let p = &model.particles;
        let (g, center1, center2) = match *key {
            (Feature::Particle(i), Feature::Particle(j)) => {
                let (i, j) = (i as usize, j as usize);
                sphere_geometry(p, i, j, &c.state.normal)
                    .map(|g| (g, p.pos[i], p.pos[j]))
                    .unwrap_or_else(|| {
                        let (vs1, vs2, g) = geometry_of(model, k, &site1, &site2, &c.state.normal);
                        (g, vs1.center, vs2.center)
                    })
            }
            _ => {
                let (vs1, vs2, g) = geometry_of(model, k, &site1, &site2, &c.state.normal);
                (g, vs1.center, vs2.center)
            }
        };
        let nodes = [site1.nodes[0], site2.nodes[0]];
        (out.loads, out.applied) = apply_law(c, &g, nodes, [center1, center2], dt, law);
    }
}

/// The contact law of a pair in contact, at geometry `g`, and the loads on its two bodies
/// (`nodes`, with their `centers`): a particle's site takes the whole force, and its moment
/// about the centre (`distribute_force` with the weight 1); with the force applied (which a
/// wall's pair keeps, `PairOutcome::applied`). Its elastic energy goes to `law`, and when its
/// dashpots pushed, their force alone (−fd on body 1, fd on body 2) with its moments about
/// the centres.
#[inline(always)]
fn apply_law(
    c: &mut PairContact,
    g: &ContactGeometry,
    nodes: [u32; 2],
    centers: [Vec3; 2],
    dt: Real,
    law: &mut LawOut<'_>,
) -> ([NodeLoad; 2], AppliedForce) {
    let f = update_frictional_contact(&c.params, &mut c.state, &law_kinematics(g), dt);
    let on_1 = -f.force_on_2;
    let loads = [
        NodeLoad { node: nodes[0], force: on_1, torque: (g.point - centers[0]).cross(&on_1) },
        NodeLoad {
            node: nodes[1],
            force: f.force_on_2,
            torque: (g.point - centers[1]).cross(&f.force_on_2),
        },
    ];
    let fd = f.dashpot_force;
    law.elastic = f.elastic_energy;
    if fd != Vec3::zeros() {
        law.pushed.push(Pushed::default());
        let record = law.pushed.last_mut().expect("just pushed");
        record.index = law.index;
        record.force = fd;
        record.moments = [(g.point - centers[0]).cross(&(-fd)), (g.point - centers[1]).cross(&fd)];
        record.viscous = f.dissipated.viscous;
    }
    let applied = AppliedForce {
        normal_force: f.normal_force,
        shear_force: f.shear_force,
        sliding: f.sliding,
    };
    (loads, applied)
}

/// The geometry of touching free spheres `i` and `j` whose last normal was
/// `previous_normal`: `contact_geometry_crossing` of their centres, the same operations in the
/// same order, without the virtual spheres; None when the centres (nearly) coincide or have
/// crossed (`d·n₀ ≤ 0`), where the general function decides the normal.
#[inline(always)]
fn sphere_geometry(
    p: &flexdem_elements::Particles,
    i: usize,
    j: usize,
    previous_normal: &Vec3,
) -> Option<ContactGeometry> {
    let (c1, c2) = (p.pos[i], p.pos[j]);
    let (r1, r2) = (p.radius[i], p.radius[j]);
    let d = c2 - c1;
    let dist = d.norm();
    let scale = r1 + r2 + c1.abs().max() + c2.abs().max();
    if !(dist > 1e-14 * scale && d.dot(previous_normal) > 0.0) {
        return None;
    }
    let normal = d * (1.0 / dist);
    let overlap = r1 + r2 - dist;
    let point = c1 + normal * (r1 - 0.5 * overlap);
    let (w1, w2) = (p.ang_vel[i], p.ang_vel[j]);
    let v1 = p.vel[i] + w1.cross(&(point - c1));
    let v2 = p.vel[j] + w2.cross(&(point - c2));
    Some(ContactGeometry {
        normal,
        overlap,
        point,
        relative_velocity: v2 - v1,
        spin_about_normal: 0.5 * normal.dot(&(w1 + w2)),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use flexdem_contact::{FrictionalContact, FrictionalParams};

    #[test]
    fn the_forces_made_from_the_applied_force_are_the_laws() {
        let n = Vec3::new(0.6, 0.0, 0.8);
        // undamped and damped, sticking and sliding (a fast tangential motion)
        for (cn, ct, slip) in
            [(0.0, 0.0, 0.01), (0.0, 0.0, 50.0), (3.0, 2.0, 0.01), (3.0, 2.0, 50.0)]
        {
            let params = FrictionalParams { kn: 1e5, ks: 4e4, tan_phi: 0.4, cn, ct };
            let mut c = PairContact { params, state: FrictionalContact::new(n) };
            c.state.shear_force = Vec3::new(0.0, 3.0, 0.0);
            let mut reference = c.state;
            let g = ContactGeometry {
                normal: n,
                overlap: 1e-4,
                point: Vec3::new(0.1, 0.2, 0.3),
                relative_velocity: Vec3::new(-0.8 * slip, 0.3 * slip, 0.6 * slip - 0.2),
                spin_about_normal: 0.5,
            };
            let f = update_frictional_contact(&params, &mut reference, &law_kinematics(&g), 1e-4);
            let mut pushed = vec![];
            let mut law = LawOut::new(&mut pushed, 7);
            let (_, kept) = apply_law(&mut c, &g, [0, 1], [Vec3::zeros(), n * 0.2], 1e-4, &mut law);
            let elastic = law.elastic;
            let case = format!("cn {cn}, ct {ct}, slip {slip}");
            assert_eq!(c.state, reference, "{case}");
            assert_eq!(f.dashpot_force == Vec3::zeros(), pushed.is_empty(), "{case}");
            if let [record] = pushed[..] {
                assert_eq!(record.index, 7, "{case}");
                assert_eq!(record.force, f.dashpot_force, "{case}");
                assert_eq!(record.viscous, f.dissipated.viscous, "{case}");
            }
            assert_eq!(cn == 0.0, f.dashpot_force == Vec3::zeros(), "{case}");
            assert_eq!(elastic, f.elastic_energy, "{case}");
            // the force kept (a wall's pair), and the one made from the state and the
            // dashpots' record (a sphere pair's)
            let made = c.applied(pushed.first().map(|r| &r.force));
            for (applied, exact) in [(kept, true), (made, cn == 0.0)] {
                let forces = c.forces(&applied);
                let scale = f.force_on_2.norm();
                let near = |a: Vec3, b: Vec3| (a - b).norm() <= 1e-14 * scale;
                if exact {
                    assert_eq!(forces.normal_force, f.normal_force, "{case}");
                    assert_eq!(forces.shear_force, f.shear_force, "{case}");
                    assert_eq!(forces.force_on_2, f.force_on_2, "{case}");
                } else {
                    assert!((forces.normal_force - f.normal_force).abs() <= 1e-14 * scale);
                    assert!(near(forces.shear_force, f.shear_force), "{case}");
                    assert!(near(forces.force_on_2, f.force_on_2), "{case}");
                }
                assert!(near(forces.dashpot_force, f.dashpot_force), "{case}");
                assert_eq!(forces.elastic_energy, f.elastic_energy, "{case}");
                assert_eq!(forces.sliding, f.sliding, "{case}");
                assert_eq!(forces.sliding, slip > 1.0, "{case}");
            }
        }
    }
}
