//! The release of overlap offsets (docs/model.md §2): a contact handed over with an offset δ₀
//! carries less force than its depth asks, `kn·(δ − δ₀)`. The offset keeps the force
//! continuous across the switch; kept for the contact's life it would let a touching sink
//! through a wall that does not push back. It is given back over some fifty steps, and the
//! energy that puts into the spring is booked (`contact_births`), not hidden in the error.
//! Also here: the incremental overlap of intersecting faces (docs/model.md §1) and how an
//! ended contact's overlap is continued ([`continued_overlap`]).

use crate::contact::{birth_jump, geometry, Contact};
use flexdem_contact::LinkKinematicsMode;
use flexdem_elements::virtual_sphere::{ContactGeometry, Feature, Kinematics};
use flexdem_elements::Model;
use flexdem_geom::Real;

/// Steps over which an overlap offset is given back: each step it shrinks by this fraction,
/// `δ₀ ← δ₀·(1 − 1/N)`. With the automatic step (a fraction of the stiffest mode's critical
/// step, so some 0.16 of its period at safety 0.5) N = 50 spreads the release over about 8
/// periods of the stiffest oscillator: the force grows without an impulse, and a touching
/// handed over deep is carried by its force again within a few periods. (Chosen on the
/// validation cases: the Brazier winding passes its checks with N from 25 to 400; in the
/// heavy-sphere impact the depth not yet carried by a force while offsets are given back
/// peaks at 1.28 mm with N = 200, 0.69 mm with 50 and 0.37 mm with 25.)
pub const OFFSET_RELEASE_STEPS: Real = 50.0;

/// Below this fraction of `r₁ + r₂` an offset is dropped (its energy booked the same way).
const NEGLIGIBLE_OFFSET: Real = 1e-9;

/// Shrinks the overlap offset of every contact that has one and was not made at this step's
/// detection (`fresh`, increasing indices into `contacts`: their offsets were just set, so
/// that their forces do not jump at the switch), and returns what that moves the energy
/// balance by (J), to book in the births. First, two faces that intersected at the last
/// update and still do have their overlap moved on by their approach (docs/model.md §1):
/// `δ₀ ← δ₀ + (v·n)·dt₀`. Then:
///
/// - a contact carrying no force (`δ ≤ δ₀`) has its offset lowered to `max(δ, 0)`: it still
///   carries none, and nothing moves;
/// - else `δ₀' = δ₀·(1 − 1/N)` ([`OFFSET_RELEASE_STEPS`]), 0 below 1e-9·(r₁ + r₂). The spring
///   with offset δ₀ leaves the balance as an ended contact does, `−½·F₋·(δ − δ₀)` (`F₋` its
///   force at the last step), and the spring with offset δ₀' enters it as a new one does,
///   `½·kn·(δ − δ₀')·(δ − δ₀' − u·dt)` ([`birth_jump`]): to first order the elastic energy
///   the release adds, `½·kn·((δ − δ₀')² − (δ − δ₀)²)`.
///
/// Serial: only contacts with an offset or intersecting faces do any work, and they are few.
pub(crate) fn release_offsets(
    contacts: &mut [Contact],
    fresh: &[usize],
    model: &Model,
    link_mode: LinkKinematicsMode,
    dt: Real,
) -> Real {
    let p = &model.particles;
    let k = Kinematics::of(p).with_link_mode(link_mode);
    let mut booked = 0.0;
    let mut fresh = fresh.iter().peekable();
    for (n, c) in contacts.iter_mut().enumerate() {
        if fresh.next_if_eq(&&n).is_some() {
            continue;
        }
        let was = was_intersecting(c);
        if !(c.state.overlap_offset != 0.0) && !was {
            continue;
        }
        let (_, _, g) = geometry(model, &k, c);
        if was && intersecting_faces(c, g.overlap) {
            // the overlap follows the faces' relative motion along n: δ₀ ← δ₀ + (v·n)·dt₀
            c.state.overlap_offset += g.relative_velocity.dot(&g.normal) * dt;
        }
        if !(c.state.overlap_offset != 0.0) {
            continue;
        }
        let offset = c.state.overlap_offset;
        let carried = g.overlap - offset;
        if !(carried > 0.0) {
            c.state.overlap_offset = g.overlap.max(0.0);
            continue;
        }
        let reach = c.site1.radius + c.site2.radius;
        let mut released = offset * (1.0 - 1.0 / OFFSET_RELEASE_STEPS);
        if released.abs() < NEGLIGIBLE_OFFSET * reach {
            released = 0.0;
        }
        let exit = -0.5 * c.state.normal_force * carried;
        c.state.overlap_offset = released;
        booked += exit + birth_jump(&c.params, &c.state, &g, dt);
    }
    booked
}

/// Whether both sites of `c` are PFacet faces.
fn faces(c: &Contact) -> bool {
    matches!((c.site1.feature, c.site2.feature), (Feature::Face(_), Feature::Face(_)))
}

/// Whether `c` was a face–face contact of intersecting triangles at its last update (read
/// from its force: `δ = F₋/kn + δ₀ = r₁ + r₂`).
fn was_intersecting(c: &Contact) -> bool {
    faces(c) && c.state.normal_force > 0.0 && {
        let last = c.state.normal_force / c.params.kn;
        intersecting_faces(c, last + c.state.overlap_offset)
    }
}

/// Whether `c` is a face–face contact whose triangles intersect: their closest points
/// coincide (to round-off), so that its geometric overlap is `r₁ + r₂` however deep they
/// are (model.md §1).
fn intersecting_faces(c: &Contact, overlap: Real) -> bool {
    let reach = c.site1.radius + c.site2.radius;
    faces(c) && (overlap - reach).abs() <= INTERSECTING * reach
}

/// The closest points of two triangles that intersect coincide to round-off: their overlap
/// is `r₁ + r₂` to this fraction.
const INTERSECTING: Real = 1e-9;

/// The overlap less its offset that contact `c` (as of its last update, force `F₋`) would
/// have now, `g` its geometry continued to the current positions on its last sites and `dt`
/// the step just done: `F₋/kn − (v·n₀)·dt`, its last overlap moved on by the approach over the
/// step along its last normal, which is what the leapfrog's trapezoidal work of its force
/// sees (model.md §3), so that its exit from the balance, `−½·F₋·(δ − δ₀)_now`, is exact to
/// the order of the step. Re-evaluating the closest points on the last sites is not: they lag
/// the motion by a second-order amount that two nearly parallel edges sliding along each other
/// make large, and for two faces that intersected (whose overlap is incremental,
/// [`release_offsets`]) they no longer coincide, so `g`'s overlap drops from `r₁ + r₂` by their
/// distance. A contact that carried no force has no last overlap to move on: `δ − δ₀` from `g`.
pub(crate) fn continued_overlap(c: &Contact, g: &ContactGeometry, dt: Real) -> Real {
    if c.state.normal_force > 0.0 {
        c.state.normal_force / c.params.kn - g.relative_velocity.dot(&c.state.normal) * dt
    } else {
        g.overlap - c.state.overlap_offset
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::{new_contact, sphere_touching};
    use flexdem_contact::Material;
    use flexdem_geom::Vec3;

    /// Two spheres overlapping by `overlap`, at rest, and their contact.
    fn pressed_pair(overlap: Real) -> (Model, Contact) {
        let mut model = Model::new();
        let m = model.add_material(Material::new(1e8, 0.3, 2650.0, 0.5).unwrap()).unwrap();
        model.add_sphere(Vec3::zeros(), 0.5, m).unwrap();
        model.add_sphere(Vec3::new(1.0 - overlap, 0.0, 0.0), 0.5, m).unwrap();
        let t = sphere_touching(&model, 0, 1).expect("they overlap");
        let c = new_contact(&model, &t);
        (model, c)
    }

    #[test]
    fn an_offset_is_given_back_geometrically_and_its_energy_booked_exactly() {
        let (delta, offset0) = (2e-3, 1.5e-3);
        let (model, mut c) = pressed_pair(delta);
        let kn = c.params.kn;
        c.state.overlap_offset = offset0;
        c.state.normal_force = kn * (delta - offset0);
        let mut list = vec![c];
        let mut booked = 0.0;
        let steps = 300;
        for _ in 0..steps {
            booked += release_offsets(&mut list, &[], &model, LinkKinematicsMode::Beam, 1e-6);
            // what the law does with it
            let c = &mut list[0];
            c.state.normal_force = kn * (delta - c.state.overlap_offset);
        }
        let expected = offset0 * (1.0 - 1.0 / OFFSET_RELEASE_STEPS).powi(steps);
        let offset = list[0].state.overlap_offset;
        assert!((offset - expected).abs() < 1e-12 * offset0, "{offset} against {expected}");
        // at rest the bookings telescope to the change of the spring's energy
        let energy = |d: Real| 0.5 * kn * (delta - d).powi(2);
        let gained = energy(offset) - energy(offset0);
        assert!(gained > 0.0 && (booked - gained).abs() < 1e-9 * gained, "{booked} vs {gained}");
    }

    #[test]
    fn a_fresh_contact_keeps_its_offset_and_one_carrying_nothing_gives_it_up_for_free() {
        let (model, mut c) = pressed_pair(1e-3);
        c.state.overlap_offset = 0.8e-3;
        let mut list = vec![c.clone()];
        assert_eq!(release_offsets(&mut list, &[0], &model, LinkKinematicsMode::Beam, 1e-6), 0.0);
        assert_eq!(list[0].state.overlap_offset, 0.8e-3);
        // deeper than the overlap: no force before, none after, nothing booked
        c.state.overlap_offset = 1.5e-3;
        c.state.normal_force = 0.0;
        let mut list = vec![c];
        assert_eq!(release_offsets(&mut list, &[], &model, LinkKinematicsMode::Beam, 1e-6), 0.0);
        assert!((list[0].state.overlap_offset - 1e-3).abs() < 1e-15);
    }
}
