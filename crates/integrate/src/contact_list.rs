//! The contacts of a simulation, the part of its state a checkpoint keeps: the general ones
//! (those of structures, sorted by key) and the free spheres' neighbour list, with what reads
//! them all (energy sums, counts, the list made for output, the walks over the wall contacts
//! and over every contact in key order).

use crate::contact::Contact;
use crate::neighbours::{merged, sites, ContactKey, NeighbourList, Pick};
use crate::pair_passes::LastUpdate;
use flexdem_contact::FrictionalParams;
use flexdem_elements::virtual_sphere::{Feature, Site};
use flexdem_elements::Model;
use flexdem_geom::{Real, Vec3};
use serde::{Deserialize, Serialize};

/// The contacts with their history: the part of the simulation state a checkpoint keeps
/// (the buffers that find and update them are `ContactPipeline`'s).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Contacts {
    /// Current contacts that involve a structure (sorted by key); those of free spheres with
    /// free spheres and walls are in `pairs`.
    pub list: Vec<Contact>,
    /// The candidate pairs of free spheres with free spheres and walls, with their contacts
    /// (a neighbour list with history, `neighbours.rs`).
    pub pairs: NeighbourList,
    /// Friction dissipated by contacts that have ended (J).
    pub ended_dissipation: Real,
    /// Contacts found late (first touches with an overlap one step of approach does not
    /// explain) so far.
    pub born_deep: u64,
}

impl Contacts {
    /// Elastic energy stored in the contacts at the last update.
    pub fn elastic_energy(&self) -> Real {
        self.list.iter().map(|c| c.forces.elastic_energy).sum::<Real>()
            + self.pairs.elastic_energy()
    }

    /// Energy dissipated by contact friction since the start (the dashpots' is counted by
    /// the engine's energy account, `Energy::contact_damping`).
    pub fn dissipated(&self) -> Real {
        self.ended_dissipation
            + self.list.iter().map(|c| c.state.dissipated_friction).sum::<Real>()
            + self.pairs.dissipated()
    }

    /// [`Contacts::energy_sums`] with the general contacts' terms read from `general`, one
    /// `(elastic energy, friction dissipated)` per contact in list order (the update's
    /// `ContactPipeline::energies`): the same sums. Read from the contacts (320 bytes each,
    /// two passes), the sums of the 9 300 contacts of the membrane of 10⁵ PFacets took
    /// 148–165 µs a step on one thread; 16 bytes a contact are a few.
    pub(crate) fn energy_sums_from(&self, general: &[(Real, Real)]) -> (Real, Real) {
        debug_assert_eq!(general.len(), self.list.len());
        let (elastic, friction) = self.pairs.energy_sums();
        (
            general.iter().map(|e| e.0).sum::<Real>() + elastic,
            self.ended_dissipation + general.iter().map(|e| e.1).sum::<Real>() + friction,
        )
    }

    /// `(elastic_energy(), dissipated())`, the same sums in one pass over the free spheres'
    /// pairs (which live apart in memory: one visit each instead of two).
    pub(crate) fn energy_sums(&self) -> (Real, Real) {
        let (elastic, friction) = self.pairs.energy_sums();
        (
            self.list.iter().map(|c| c.forces.elastic_energy).sum::<Real>() + elastic,
            self.ended_dissipation
                + self.list.iter().map(|c| c.state.dissipated_friction).sum::<Real>()
                + friction,
        )
    }

    /// Number of contacts (both lists).
    pub fn len(&self) -> usize {
        self.list.len() + self.pairs.len()
    }

    /// Whether there is no contact.
    pub fn is_empty(&self) -> bool {
        self.list.is_empty() && self.pairs.is_empty()
    }

    /// Every contact, in key order, as a [`Contact`] (the free spheres' made from their
    /// neighbour list): for output and inspection, not for the step. From the state alone:
    /// a free spheres' pair's force is its springs' (the law's exactly without dashpots; the
    /// push of its dashpots at the last step is not part of the state, and
    /// `Simulation::contacts`, which has that step's records, adds it).
    pub fn all(&self, model: &Model) -> Vec<Contact> {
        self.all_after(model, None)
    }

    /// [`Contacts::all`] with the free spheres' forces of their last update, `last`.
    pub(crate) fn all_after(&self, model: &Model, last: Option<&LastUpdate<'_>>) -> Vec<Contact> {
        merged(&self.list, &self.pairs)
            .map(|pick| match pick {
                Pick::General(n) => self.list[n].clone(),
                Pick::Pair(n) => {
                    let c = self.pairs.contact_at(n).expect("merged yields touching pairs");
                    let applied = match last {
                        Some(last) => last.applied(c, n),
                        None => c.applied(None),
                    };
                    self.pairs.contact(model, n, &applied).expect("a touching pair")
                }
            })
            .collect()
    }

    /// Calls `f(wall, force on the body, normal force, kn)` on every wall contact, in key
    /// order (nothing made: the walls' loads are summed every step), the free spheres' with
    /// the force their last update (`last`) applied, as their law gave it. A free sphere's
    /// wall contact not updated since the candidates changed (a load, before its first step)
    /// is left out, as if it pushed with no force. The keys sort walls last: only the general
    /// list's tail is looked at.
    pub(crate) fn for_each_on_wall(
        &self,
        last: &LastUpdate<'_>,
        mut f: impl FnMut(u32, &Vec3, Real, Real),
    ) {
        let g = self.list.partition_point(|c| !matches!(c.key().0, Feature::Wall(_)));
        let mut general = self.list[g..].iter().peekable();
        let mut pairs = last.walls().map(|(n, applied)| {
            let (key, c) = self.pairs.get(*n as usize);
            (key, c.state.normal * applied.normal_force + applied.shear_force, applied, c)
        });
        let mut pair = pairs.next();
        loop {
            let take_general = match (general.peek(), &pair) {
                (Some(c), Some((key, ..))) => c.key() < *key,
                (Some(_), None) => true,
                (None, Some(_)) => false,
                (None, None) => return,
            };
            let (key, force, normal_force, kn) = if take_general {
                let c = general.next().expect("peeked");
                (c.key(), c.forces.force_on_2, c.forces.normal_force, c.params.kn)
            } else {
                let (key, force, applied, c) = pair.take().expect("a pair");
                pair = pairs.next();
                (key, force, applied.normal_force, c.params.kn)
            };
            if let Feature::Wall(w) = key.0 {
                f(w, &force, normal_force, kn);
            }
        }
    }

    /// Calls `f(site 1, site 2, law constants, normal)` on every contact in key order, none
    /// made (the time step's stiffness sums: a free sphere's contact is not cloned), but on
    /// the free spheres' pairs whose key is not `wanted` (their contact is then not read).
    pub(crate) fn for_each_law(
        &self,
        model: &Model,
        wanted: impl Fn(&ContactKey) -> bool,
        mut f: impl FnMut(&Site, &Site, &FrictionalParams, &Vec3),
    ) {
        for pick in merged(&self.list, &self.pairs) {
            match pick {
                Pick::General(n) => {
                    let c = &self.list[n];
                    f(&c.site1, &c.site2, &c.params, &c.state.normal);
                }
                Pick::Pair(n) => {
                    if !wanted(&self.pairs.keys.get(n)) {
                        continue;
                    }
                    let (key, c) = self.pairs.get(n);
                    let (site1, site2) = sites(model, &key);
                    f(&site1, &site2, &c.params, &c.state.normal);
                }
            }
        }
    }
}
