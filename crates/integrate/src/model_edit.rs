//! What a model edit keeps of the contacts and links (`Simulation::edit_model`): all of
//! them when the bodies stay the same bodies (the same particles, of the same kinds and
//! structures, connections, faces and walls), and also when the edit only adds bodies apart
//! from the old ones (a rock put above a settled net, a sample into a membrane): every key
//! of an old contact or link then names what it named before, so their states (overlap
//! offsets, shear springs, the links' rest state, prestress and plastic strain) go on as if
//! no edit had been made. Any other change of the topology ends the contacts; the links are
//! made anew at rest when an old connection changed (its nodes, spring or class).

use crate::links::Links;
use flexdem_contact::LinkKinematicsMode;
use flexdem_elements::{Connection, Model, PFacet};

/// Whether `after` is `before` with bodies added after its own and apart from them: its
/// particles start with `before`'s (of the same kind and structure), its connections and
/// PFacets with `before`'s (the same nodes and edges), its walls with as many, and no
/// connection or PFacet it adds holds a particle or an edge of `before`. Then every feature
/// of `before` (particle, edge, face, wall) is the same feature in `after`, with the same
/// neighbours: its contacts can go on.
pub(crate) fn only_adds_bodies(before: &Model, after: &Model) -> bool {
    let (p, q) = (&before.particles, &after.particles);
    let (n, c) = (p.len(), before.connections.len());
    let old = |node: u32| (node as usize) < n;
    q.len() >= n
        && q.kind[..n] == p.kind[..]
        && q.structure[..n] == p.structure[..]
        && after.walls.len() >= before.walls.len()
        && after.connections.len() >= c
        && same_nodes(&after.connections[..c], &before.connections)
        && after.pfacets.len() >= before.pfacets.len()
        && same_faces(&after.pfacets[..before.pfacets.len()], &before.pfacets)
        && after.connections[c..].iter().all(|k| !k.nodes.iter().any(|&i| old(i)))
        && after.pfacets[before.pfacets.len()..].iter().all(|f| {
            !f.nodes.iter().any(|&i| old(i)) && f.connections.iter().all(|&e| e as usize >= c)
        })
}

/// The links of `after`'s connections when its first ones are `old`'s (the same nodes,
/// material constants and rest lengths, so the same springs and classes): the old links keep
/// their state (shear force, reference rotations, status, plastic strain), the added ones
/// start at rest in the current configuration. None when an old connection changed: then
/// every link is made anew ([`Links::from_model`]).
pub(crate) fn links_kept(old: &Links, after: &Model, mode: LinkKinematicsMode) -> Option<Links> {
    let n = old.nodes.len();
    let mut links = Links::from_model(after, mode);
    let same = links.nodes.len() >= n
        && links.nodes[..n] == old.nodes[..]
        && (0..n).all(|i| {
            let (a, b) = (old.spring[i] as usize, links.spring[i] as usize);
            let (ca, cb) = (old.class[i] as usize, links.class[i] as usize);
            old.springs[a] == links.springs[b] && old.classes[ca] == links.classes[cb]
        });
    if !same || (!old.plastic.is_empty() && links.plastic.len() < n) {
        return None;
    }
    links.state[..n].clone_from_slice(&old.state);
    if old.loads.len() == n {
        // (the last update's loads, which output reads until the next step)
        links.loads[..n].clone_from_slice(&old.loads);
    }
    if !old.plastic.is_empty() {
        links.plastic[..n].copy_from_slice(&old.plastic);
    }
    Some(links)
}

/// Whether two lists of connections have the same nodes and structures, in the same order.
fn same_nodes(a: &[Connection], b: &[Connection]) -> bool {
    a.len() == b.len()
        && a.iter().zip(b).all(|(x, y)| x.nodes == y.nodes && x.structure == y.structure)
}

/// Whether two lists of PFacets have the same nodes, edges and structures.
fn same_faces(a: &[PFacet], b: &[PFacet]) -> bool {
    let same = |x: &PFacet, y: &PFacet| {
        x.nodes == y.nodes && x.connections == y.connections && x.structure == y.structure
    };
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| same(x, y))
}

#[cfg(test)]
mod tests {
    use super::*;
    use flexdem_contact::Material;
    use flexdem_elements::builders::{chain, straight_line};
    use flexdem_elements::StructureOptions;
    use flexdem_geom::Vec3;

    fn model() -> Model {
        let mut m = Model::new();
        let mat = m.add_material(Material::new(1e7, 0.3, 1000.0, 0.5).unwrap()).unwrap();
        let points = straight_line(Vec3::zeros(), Vec3::x(), 3).unwrap();
        chain(&mut m, &points, &StructureOptions::new("c", 0.01, mat)).unwrap();
        m.add_sphere(Vec3::new(0.0, 1.0, 0.0), 0.05, mat).unwrap();
        m.add_wall(Vec3::zeros(), Vec3::z(), mat).unwrap();
        m
    }

    #[test]
    fn bodies_added_apart_keep_the_old_features_and_others_do_not() {
        let before = model();
        let mat = before.particles.material[0];
        let edited = |edit: &dyn Fn(&mut Model)| {
            let mut m = before.clone();
            edit(&mut m);
            only_adds_bodies(&before, &m)
        };
        assert!(edited(&|_| ()));
        let sphere = |m: &mut Model| {
            m.add_sphere(Vec3::new(3.0, 0.0, 0.0), 0.05, mat).unwrap();
        };
        assert!(edited(&sphere));
        let net = |m: &mut Model| {
            let points = straight_line(Vec3::new(0.0, 3.0, 0.0), Vec3::new(1.0, 3.0, 0.0), 2);
            chain(m, &points.unwrap(), &StructureOptions::new("new", 0.01, mat)).unwrap();
            m.add_wall(Vec3::new(0.0, 0.0, 5.0), -Vec3::z(), mat).unwrap();
        };
        assert!(edited(&net));
        // a new connection that holds an old node changes that node's neighbours
        let joined = |m: &mut Model| {
            let s = m.add_structure("joined").unwrap();
            let node = m.add_node(s, Vec3::new(2.0, 0.0, 0.0), 0.01, mat, 1).unwrap();
            m.add_connection(s, [3, node], 0.01, mat, 1).unwrap();
        };
        assert!(!edited(&joined));
        assert!(!edited(&|m| m.walls.truncate(0)));
        assert!(!edited(&|m| m.connections.swap(0, 1)));
        // a free sphere made a node (its pairs are no longer free spheres' pairs)
        let kind = |m: &mut Model| m.particles.kind[4] = flexdem_elements::ParticleKind::Node;
        assert!(!edited(&kind));
        let moved = |m: &mut Model| m.connections[1].structure = 1;
        assert!(!edited(&moved));
    }

    #[test]
    fn old_links_keep_their_state_unless_their_connection_changed() {
        let before = model();
        let mode = LinkKinematicsMode::default();
        let mut old = Links::from_model(&before, mode);
        old.state[1].shear_force = Vec3::new(0.0, 1.5, 0.0);
        let mut after = before.clone();
        let mat = after.particles.material[0];
        let points = straight_line(Vec3::new(0.0, 3.0, 0.0), Vec3::new(1.0, 3.0, 0.0), 2);
        chain(&mut after, &points.unwrap(), &StructureOptions::new("new", 0.01, mat)).unwrap();
        let kept = links_kept(&old, &after, mode).expect("connections added after the old");
        assert_eq!(kept.state.len(), 5);
        assert_eq!(kept.state[..3], old.state[..]);
        assert_eq!(kept.state[3], Links::from_model(&after, mode).state[3]);
        after.connections[0].rest_length *= 1.01;
        assert!(links_kept(&old, &after, mode).is_none(), "a changed spring: made anew");
    }
}
