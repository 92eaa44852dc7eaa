//! Where the energy of a run sits, in words, for the message of a run stopped by its energy
//! watch: the contact and the link holding the most elastic energy, and the fastest particle,
//! each with its bodies and their structures.

use crate::pair_passes::PairScratch;
use crate::state::State;
use flexdem_elements::virtual_sphere::Feature;
use flexdem_elements::Model;
use flexdem_elements::NO_STRUCTURE;
use flexdem_geom::Real;

/// The structure's name in quotes, or "a free sphere" for `NO_STRUCTURE`.
fn structure_name(model: &Model, structure: u32) -> String {
    match model.structures.get(structure as usize) {
        Some(s) if structure != NO_STRUCTURE => format!("structure \"{}\"", s.name),
        _ => "no structure".into(),
    }
}

/// A feature and its body in words: "PFacet 12 of structure \"tube\"".
fn feature(model: &Model, f: Feature) -> String {
    match f {
        Feature::Particle(i) => {
            let s = model.particles.structure.get(i as usize).copied().unwrap_or(NO_STRUCTURE);
            if s == NO_STRUCTURE {
                format!("sphere {i}")
            } else {
                format!("node {i} of {}", structure_name(model, s))
            }
        }
        Feature::Edge(c) => match model.connections.get(c as usize) {
            Some(k) => format!("connection {c} of {}", structure_name(model, k.structure)),
            None => format!("connection {c}"),
        },
        Feature::Face(f) => match model.pfacets.get(f as usize) {
            Some(k) => format!("PFacet {f} of {}", structure_name(model, k.structure)),
            None => format!("PFacet {f}"),
        },
        Feature::Wall(w) => format!("wall {w}"),
    }
}

/// The contact and the link holding the most elastic energy and the fastest particle (the
/// free spheres' contacts with the forces of their last update, in `pairs`).
pub(crate) fn describe(state: &State, pairs: &PairScratch) -> String {
    let model = &state.model;
    let mut parts = Vec::new();
    let last = state.contacts.pairs.last_update(pairs);
    let all = state.contacts.all_after(model, Some(&last));
    let contact =
        all.iter().max_by(|a, b| a.forces.elastic_energy.total_cmp(&b.forces.elastic_energy));
    match contact {
        Some(c) if c.forces.elastic_energy > 0.0 => parts.push(format!(
            "The contact holding the most elastic energy ({:.3e} J, normal force {:.3e} N, \
             of {} contacts) is between {} and {} at ({:.4}, {:.4}, {:.4})",
            c.forces.elastic_energy,
            c.forces.normal_force,
            all.len(),
            feature(model, c.site1.feature),
            feature(model, c.site2.feature),
            c.point.x,
            c.point.y,
            c.point.z
        )),
        _ => parts.push("No contact holds elastic energy".into()),
    }
    let links = &state.links;
    let link = (0..links.loads.len())
        .map(|l| (l, links.elastic_energy(l, &model.particles)))
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .filter(|&(_, e)| e > 0.0);
    if let Some((l, energy)) = link {
        let [a, b] = links.nodes[l];
        parts.push(format!(
            "the link holding the most ({energy:.3e} J) is connection {l} of {}, between nodes \
             {a} and {b}",
            structure_name(model, model.connections[l].structure)
        ));
    }
    let p = &model.particles;
    let fastest = (0..p.len()).max_by(|&a, &b| p.vel[a].norm().total_cmp(&p.vel[b].norm()));
    if let Some(i) = fastest {
        let kinetic: Real = 0.5 * p.mass[i] * p.vel[i].norm_squared();
        parts.push(format!(
            "the fastest particle is {} at {:.3e} m/s ({:.3e} J of kinetic energy)",
            feature(model, Feature::Particle(i as u32)),
            p.vel[i].norm(),
            kinetic
        ));
    }
    parts.join("; ")
}
