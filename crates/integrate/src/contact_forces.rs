//! The contacts' forces at each step (`ContactPipeline::apply`): the law of every general
//! contact in parallel with its loads shared among the nodes of its sites, the free spheres'
//! pairs stepped by the neighbour list (`pair_passes.rs`), and every node load summed in the
//! order of the contacts' keys (in one pass on one thread, per particle in parallel with
//! more: `gather.rs`), so the same sums whatever the number of threads; then the power of
//! the dashpots' forces over the two halves of the kick (`dashpot_dissipation`). What the
//! contacts are comes from `contacts.rs` (detection, births, hand-overs).

use crate::contact::{geometry, law_kinematics, BirthReport, Contact};
use crate::contact_list::Contacts;
use crate::contacts::ContactPipeline;
use crate::dashpots::dashpot_power;
use crate::gather::{fits_codes, load_nodes, write_general_loads, NO_NODE};
use crate::home_loops::{by_runs, chunk_home_runs, shared};
use crate::homes::Homes;
use crate::neighbours::{merged, Pick, Sink};
use crate::pair_parts::PARTS_PER_THREAD;
use crate::parallel::{MIN_PARALLEL_CHEAP, MIN_PARALLEL_COSTLY};
use flexdem_contact::update_frictional_contact;
use flexdem_elements::virtual_sphere::{distribute_force_as, Kinematics, NodeLoad, VirtualSphere};
use flexdem_elements::Model;
use flexdem_geom::{Real, Vec3};
use rayon::prelude::*;

/// Contacts per chunk when the law's contacts are shared by home (the runs change home
/// between chunks).
const LAW_CHUNK: usize = 256;

/// Contacts, their loads, the loads' particles and their energy terms, cut by home.
type LawPiece<'a> =
    (&'a mut [Contact], (&'a mut [[NodeLoad; 6]], (&'a mut [[u32; 6]], &'a mut [(Real, Real)])));

/// A [`LawPiece`] with the dashpots' loads.
type DampedPiece<'a> = (
    &'a mut [Contact],
    (
        &'a mut [[NodeLoad; 6]],
        (&'a mut [[u32; 6]], (&'a mut [(Real, Real)], &'a mut [[NodeLoad; 6]])),
    ),
);

/// Below this many particles, force and torque are zeroed on one thread.
const MIN_PARALLEL_ZERO: usize = 8 * MIN_PARALLEL_CHEAP;

impl ContactPipeline {
    /// Updates every contact's forces (in parallel) and the free spheres' pairs (their
    /// births and ends too, see `neighbours.rs`), and makes `force` and `torque` anew as the
    /// sums of the node loads, each particle's in key order. Returns what the pairs' births
    /// and ends moved the energy balance by.
    pub(crate) fn apply(
        &mut self,
        contacts: &mut Contacts,
        model: &Model,
        dt: Real,
        force: &mut [Vec3],
        torque: &mut [Vec3],
        homes: &Homes,
    ) -> BirthReport {
        let p = &model.particles;
        // with more than one thread the loads' sums are written per particle (`gather.rs`),
        // every particle's; else they are added as they come, onto zeros
        let gathered = rayon::current_num_threads() > 1
            && fits_codes(contacts.list.len(), contacts.pairs.keys().len());
        if !gathered {
            let zero = |v: &mut [Vec3]| {
                v.par_iter_mut().with_min_len(MIN_PARALLEL_ZERO).for_each(|x| *x = Vec3::zeros())
            };
            zero(force);
            zero(torque);
        }
        let mode = self.link_mode;
        let k = Kinematics::of(p).with_link_mode(mode);
        let zero = [NodeLoad { node: 0, force: Vec3::zeros(), torque: Vec3::zeros() }; 6];
        self.loads.resize(contacts.list.len(), zero);
        self.load_nodes.resize(contacts.list.len(), [NO_NODE; 6]);
        self.energies.resize(contacts.list.len(), (0.0, 0.0));
        // the force on body 2 shared among the nodes of both sites (body 1 takes −f)
        let shares =
            |c: &Contact, (vs1, vs2): (&VirtualSphere, &VirtualSphere), at: &Vec3, f: &Vec3| {
                let l1 = distribute_force_as(mode, &c.site1, &p.pos, &vs1.center, at, &(-f));
                (l1, distribute_force_as(mode, &c.site2, &p.pos, &vs2.center, at, f))
            };
        let update = |c: &mut Contact,
                      loads: &mut [NodeLoad; 6],
                      nodes: &mut [u32; 6],
                      energy: &mut (Real, Real)| {
            let (vs1, vs2, g) = geometry(model, &k, c);
            let f = update_frictional_contact(&c.params, &mut c.state, &law_kinematics(&g), dt);
            let (l1, l2) = shares(c, (&vs1, &vs2), &g.point, &f.force_on_2);
            loads[..3].copy_from_slice(&l1);
            loads[3..].copy_from_slice(&l2);
            *nodes = load_nodes(c.site1.node_count(), c.site2.node_count(), loads);
            c.forces = f;
            c.point = g.point;
            *energy = (c.forces.elastic_energy, c.state.dissipated_friction);
            (vs1, vs2, g)
        };
        // by the home of each chunk's first contact's first particle (`home_loops.rs`)
        let shared_homes = shared(homes, model).then_some(homes);
        let len = contacts.list.len();
        let list = &contacts.list;
        let home = |c: usize| {
            let first = list[c * LAW_CHUNK].site1.nodes[0] as usize;
            shared_homes.map_or(0, |h| h.home_of(first))
        };
        let runs = chunk_home_runs(len, LAW_CHUNK, shared_homes, home);
        if self.damped {
            // the dashpots' force alone shared as the total is, for its power after the kick
            self.dashpot_loads.resize(contacts.list.len(), zero);
            let law =
                |_: usize, (list, (loads, (nodes, (energies, dashpots)))): DampedPiece<'_>| {
                    list.par_iter_mut()
                        .zip(loads.par_iter_mut())
                        .zip(nodes.par_iter_mut())
                        .zip(energies.par_iter_mut())
                        .zip(dashpots.par_iter_mut())
                        .with_min_len(MIN_PARALLEL_COSTLY)
                        .for_each(|((((c, loads), nodes), energy), dashpot)| {
                            let (vs1, vs2, g) = update(c, loads, nodes, energy);
                            let f = c.forces.dashpot_force;
                            if f == Vec3::zeros() {
                                *dashpot = zero;
                                return;
                            }
                            let (l1, l2) = shares(c, (&vs1, &vs2), &g.point, &f);
                            dashpot[..3].copy_from_slice(&l1);
                            dashpot[3..].copy_from_slice(&l2);
                        });
                };
            let all = (
                &mut contacts.list[..],
                (
                    &mut self.loads[..],
                    (
                        &mut self.load_nodes[..],
                        (&mut self.energies[..], &mut self.dashpot_loads[..]),
                    ),
                ),
            );
            by_runs(all, len, runs, &law);
        } else {
            let law = |_: usize, (list, (loads, (nodes, energies))): LawPiece<'_>| {
                list.par_iter_mut()
                    .zip(loads.par_iter_mut())
                    .zip(nodes.par_iter_mut())
                    .zip(energies.par_iter_mut())
                    .with_min_len(MIN_PARALLEL_COSTLY)
                    .for_each(|(((c, loads), nodes), energy)| {
                        update(c, loads, nodes, energy);
                    });
            };
            let all = (
                &mut contacts.list[..],
                (&mut self.loads[..], (&mut self.load_nodes[..], &mut self.energies[..])),
            );
            by_runs(all, len, runs, &law);
        }
        // in key order, the free spheres' contacts among the others
        let mut add = |l: &NodeLoad| {
            force[l.node as usize] += l.force;
            torque[l.node as usize] += l.torque;
        };
        let general_loads = |n: usize| {
            let (c, loads) = (&contacts.list[n], &self.loads[n]);
            let (n1, n2) = (c.site1.node_count(), c.site2.node_count());
            loads[..n1].iter().chain(&loads[3..3 + n2])
        };
        let ended = &mut contacts.ended_dissipation;
        self.pair_parts.set_in_use(false);
        if rayon::current_num_threads() == 1 && contacts.list.is_empty() {
            // one pass with no general contact to put among the pairs (a granular scene): the
            // keys are not looked at (their sink was a call per touching pair, 2.5 % of the
            // LAMMPS twin's instructions)
            return contacts.pairs.update_in_order(model, dt, &mut self.pairs, ended, |e| {
                if let Sink::Load(l) = e {
                    add(l);
                }
            });
        }
        if rayon::current_num_threads() == 1 {
            // one pass: each pair's loads added as soon as they are known, after the general
            // contacts of smaller keys (the same sums, in the same order, as below)
            let general = &contacts.list;
            let mut g = 0;
            let report =
                contacts.pairs.update_in_order(model, dt, &mut self.pairs, ended, |e| match e {
                    Sink::Before(key) => {
                        while g < general.len() && general[g].key() < *key {
                            general_loads(g).for_each(&mut add);
                            g += 1;
                        }
                    }
                    Sink::Load(l) => add(l),
                });
            (g..general.len()).for_each(|n| general_loads(n).for_each(&mut add));
            return report;
        }
        if gathered && contacts.pairs.keys().len() >= p.len() {
            // the pairs in parts, each summing the loads of the particles it alone loads and
            // keeping the others' (`pair_parts.rs`, `part_step.rs`); those of the particles
            // general contacts load summed per particle (`gather.rs`)
            let (index, parts) = (&mut self.load_index, &mut self.pair_parts);
            index.index_general(&self.load_nodes, p.len());
            let count = PARTS_PER_THREAD * rayon::current_num_threads();
            // the pairs' table is read by a new split and by the gather of the general
            // contacts' particles: made for a split with none, it is freed (and made again,
            // once per neighbour list at most, if general contacts come)
            let stale = !parts.is_split_for(&contacts.pairs, p.len(), count);
            if stale || index.has_general() {
                index.index_pairs(&contacts.pairs, p.len());
            }
            parts.split(&contacts.pairs, p.len(), count, |i| index.pair_entries(i));
            if stale && !index.has_general() {
                index.release_pairs();
            }
            parts.with_general(index.has_general(), |i| !index.general_entries(i).is_empty());
            parts.set_in_use(true);
            let scratch = &mut self.pairs;
            let room = &mut self.part_inputs;
            let report = contacts.pairs.update_in_parts(
                model,
                dt,
                scratch,
                ended,
                (parts, room),
                force,
                torque,
            );
            if index.has_general() {
                let (list, loads) = (&contacts.list, &self.loads);
                let sum_by = Some(parts.sum_by());
                index.write_loads(force, torque, list, loads, &contacts.pairs, scratch, sum_by);
            }
            return report;
        }
        let report = contacts.pairs.update(model, dt, &mut self.pairs, ended);
        if gathered && contacts.pairs.is_empty() {
            // no pair touches, the general contacts' loads alone: summed per range of
            // particles (`gather.rs`)
            write_general_loads(force, torque, &self.loads, &self.load_nodes, homes);
            return report;
        }
        if gathered {
            // each particle's loads in key order, in parallel over the particles (`gather.rs`)
            let index = &mut self.load_index;
            index.index_pairs(&contacts.pairs, p.len());
            index.index_general(&self.load_nodes, p.len());
            index.write_loads(
                force,
                torque,
                &contacts.list,
                &self.loads,
                &contacts.pairs,
                &self.pairs,
                None,
            );
            return report;
        }
        // the touching pairs' loads come in the order `merged` picks them
        let mut pair_loads = contacts.pairs.touching_loads(&self.pairs);
        for pick in merged(&contacts.list, &contacts.pairs) {
            match pick {
                Pick::General(n) => general_loads(n).for_each(&mut add),
                Pick::Pair(n) => {
                    let (m, loads) = pair_loads.next().expect("a touching pair's loads");
                    debug_assert_eq!(m, n);
                    loads.for_each(|l| add(&l));
                }
            }
        }
        report
    }
}

impl ContactPipeline {
    /// The dissipation of the contacts' dashpots at the last update, split as the leapfrog's
    /// kinetic energy sees it (model.md §7): `(before, after)`, the work of the dashpot forces
    /// at t over the half kick before, `−Σ F_d·v_rel(t − dt₀/2)·h/2`, and over the half kick
    /// after, `−Σ F_d·v_rel(t + dt/2)·h/2` with the velocities the kick has just given (J);
    /// `h = (dt₀ + dt)/2` is the kick, `dt₀ = previous` the step the law was given (its own
    /// count, `dissipated.viscous`, is `−F_d·v_rel(t − dt₀/2)·dt₀`). To call after the
    /// leapfrog; both 0 without dashpots.
    pub(crate) fn dashpot_dissipation(
        &self,
        contacts: &Contacts,
        model: &Model,
        previous: Real,
        dt: Real,
    ) -> (Real, Real) {
        if !self.damped {
            return (0.0, 0.0);
        }
        let (mut law, mut power) = (0.0, 0.0);
        for (c, loads) in contacts.list.iter().zip(&self.dashpot_loads) {
            let f = &c.forces.dashpot_force;
            if *f == Vec3::zeros() {
                continue;
            }
            law += c.forces.dissipated.viscous;
            power += dashpot_power(&c.site1, &c.site2, f, loads, model);
        }
        let (pair_law, pair_power) = contacts.pairs.dashpot_dissipation(&self.pairs, model);
        law += pair_law;
        power += pair_power;
        // with a constant step, h/(2·dt₀) is 0.5 exactly
        let kick = 0.5 * (previous + dt);
        (law * (kick / (2.0 * previous)), -0.5 * kick * power)
    }
}
