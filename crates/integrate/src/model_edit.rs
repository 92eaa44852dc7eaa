//! What a model edit keeps of the contacts and links (`Simulation::edit_model`): all of
//! them when the bodies stay the same bodies (the same particles, of the same kinds and
//! structures, connections, faces and walls), and also when the edit only adds bodies apart
//! from the old ones (a rock put above a settled net, a sample into a membrane): every key
//! of an old contact or link then names what it named before, so their states (overlap
//! offsets, shear springs, the links' rest state, prestress and plastic strain) go on as if
//! no edit had been made. Any other change of the topology ends the contacts. The links go
//! on wherever their connection is still there (the same nodes, spring and class); the
//! others are made at rest ([`links_carried`]).

use crate::links::Links;
use flexdem_contact::{spring_energy, LinkKinematicsMode};
use flexdem_elements::{Connection, Model, PFacet, Particles, Wall};
use flexdem_geom::Real;
use std::collections::HashMap;

/// Whether `after` is `before` with bodies added after its own and apart from them: its
/// particles start with `before`'s (of the same kind and structure), its connections and
/// PFacets with `before`'s (the same nodes and edges), its walls with `before`'s (the same
/// planes, [`same_planes`]), and no
/// connection or PFacet it adds holds a particle or an edge of `before`. Then every feature
/// of `before` (particle, edge, face, wall) is the same feature in `after`, with the same
/// neighbours: its contacts can go on.
pub(crate) fn only_adds_bodies(before: &Model, after: &Model) -> bool {
    let (n, c) = (before.particles.len(), before.connections.len());
    let old = |node: u32| (node as usize) < n;
    same_old_particles(before, after)
        && after.walls.len() >= before.walls.len()
        && same_planes(&after.walls[..before.walls.len()], &before.walls)
        && after.connections.len() >= c
        && same_nodes(&after.connections[..c], &before.connections)
        && after.pfacets.len() >= before.pfacets.len()
        && same_faces(&after.pfacets[..before.pfacets.len()], &before.pfacets)
        && after.connections[c..].iter().all(|k| !k.nodes.iter().any(|&i| old(i)))
        && after.pfacets[before.pfacets.len()..].iter().all(|f| {
            !f.nodes.iter().any(|&i| old(i)) && f.connections.iter().all(|&e| e as usize >= c)
        })
}

/// The links of an edited model, and the elastic energy the edit moved.
pub(crate) struct LinksCarried {
    /// `after`'s links: those carried over with their state, the others new at rest.
    pub links: Links,
    /// Elastic energy the old links not carried over held (J): it leaves the system, as a
    /// breakage's does (`links_dissipated`).
    pub released: Real,
    /// Elastic energy the links made at rest hold at once (J): `½·kn·(L0 − L)²` each, their
    /// normal spring's (a rest length set by hand, or a connection between nodes apart from
    /// it); the user's work (`load_work`). Shear, bending and twist start at zero.
    pub made: Real,
}

/// The links of `after`'s connections, each old link whose connection is still there (the
/// same nodes, in the same order; the same spring: stiffnesses and rest length; the same
/// class) carried over with its state (shear force, reference rotations, status, broken or
/// not, plastic strain, last loads), the others made at rest in the current configuration.
/// The old particles (`before`'s) must still be the same particles (kinds and structures,
/// first in `after`): otherwise a node id no longer names the same node, and every link is
/// made at rest. Old links are matched by their nodes, not their index, so that removing or
/// changing one connection leaves the others as they were (a broken link of a net stays
/// broken when a connection is added).
pub(crate) fn links_carried(
    old: &Links,
    before: &Model,
    after: &Model,
    mode: LinkKinematicsMode,
) -> LinksCarried {
    let mut links = Links::from_model(after, mode);
    // the old links by their nodes, in order (two connections may join the same nodes)
    let mut by_nodes: HashMap<[u32; 2], Vec<usize>> = HashMap::new();
    if same_old_particles(before, after) {
        for (k, nodes) in old.nodes.iter().enumerate().rev() {
            by_nodes.entry(*nodes).or_default().push(k);
        }
    }
    let mut carried = vec![false; old.len()];
    let mut made = 0.0;
    for i in 0..links.len() {
        // the first old link on these nodes with the same spring and class (candidates are
        // kept last first)
        let same = |k: &usize| {
            old.spring_of(*k) == links.spring_of(i)
                && old.classes[old.class[*k] as usize] == links.classes[links.class[i] as usize]
        };
        let candidates = by_nodes.get_mut(&links.nodes[i]);
        let found = candidates.and_then(|c| c.iter().rposition(same).map(|at| c.remove(at)));
        let Some(k) = found else {
            made += normal_energy_at_rest(&links, i, &after.particles);
            continue;
        };
        carried[k] = true;
        links.state[i] = old.state[k].clone();
        if let Some(load) = old.loads.get(k) {
            // (the last update's loads, which output reads until the next step)
            links.loads[i] = *load;
        }
        if let (Some(to), Some(from)) = (links.plastic.get_mut(i), old.plastic.get(k)) {
            *to = *from;
        }
    }
    let released =
        (0..old.len()).filter(|&k| !carried[k]).map(|k| old.elastic_energy(k, &before.particles));
    let released = released.sum();
    LinksCarried { links, released, made }
}

/// `Fn²/2kn = ½·kn·(L0 − L)²`: the normal spring's energy of link `i`, at rest but for its
/// length `L` (its nodes' distance in `p`) against its rest length `L0` (eq 8's kn; the
/// link law's `Fn = kn·(L0 + e_p − L)` with no plastic elongation `e_p` yet).
fn normal_energy_at_rest(links: &Links, i: usize, p: &Particles) -> Real {
    let [a, b] = links.nodes[i].map(|n| n as usize);
    let spring = links.spring_of(i);
    let kn = spring.stiffness.kn;
    spring_energy(kn * (spring.rest_length - (p.pos[b] - p.pos[a]).norm()), kn)
}

/// Whether `after`'s first particles are `before`'s: as many at least, of the same kinds and
/// structures (so that an old particle id names the same body, node or sphere).
fn same_old_particles(before: &Model, after: &Model) -> bool {
    let (p, q) = (&before.particles, &after.particles);
    let n = p.len();
    q.len() >= n && q.kind[..n] == p.kind[..] && q.structure[..n] == p.structure[..]
}

/// Whether two lists of walls are the same walls: the same planes (point and normal, to the
/// bit), materials and collision groups (their velocities may differ: a wall set moving goes
/// on touching what it touched). A wall moved or turned by hand, or one removed and another
/// added in its place, is another feature, whose contacts' overlap offsets and shear springs
/// belong to the old plane.
fn same_planes(a: &[Wall], b: &[Wall]) -> bool {
    let same = |x: &Wall, y: &Wall| {
        x.point == y.point && x.normal == y.normal && x.material == y.material && x.mask == y.mask
    };
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| same(x, y))
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
    use flexdem_contact::{LinkStatus, Material};
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
    fn old_links_keep_their_state_while_their_connection_is_there() {
        let before = model();
        let mode = LinkKinematicsMode::default();
        let mut old = Links::from_model(&before, mode);
        old.state[0].shear_force = Vec3::new(0.0, 2.0, 0.0);
        old.state[1].shear_force = Vec3::new(0.0, 1.5, 0.0);
        old.state[2].status = LinkStatus::Broken;
        let mut after = before.clone();
        let mat = after.particles.material[0];
        let points = straight_line(Vec3::new(0.0, 3.0, 0.0), Vec3::new(1.0, 3.0, 0.0), 2);
        chain(&mut after, &points.unwrap(), &StructureOptions::new("new", 0.01, mat)).unwrap();
        let fresh = Links::from_model(&after, mode);
        let added = links_carried(&old, &before, &after, mode);
        assert_eq!(added.links.state.len(), 5);
        assert_eq!(added.links.state[..3], old.state[..]);
        assert_eq!(added.links.state[3..], fresh.state[3..]);
        assert_eq!((added.released, added.made), (0.0, 0.0));
        // a rest length changed by hand: that link is made at rest, the others (a broken one
        // too) go on; its old energy leaves, its normal spring's at the new length comes in
        after.connections[0].rest_length *= 1.01;
        let changed = links_carried(&old, &before, &after, mode);
        assert_eq!(changed.links.state[0], Links::from_model(&after, mode).state[0]);
        assert_eq!(changed.links.state[1..3], old.state[1..]);
        assert_eq!(changed.links.state[2].status, LinkStatus::Broken);
        assert_eq!(changed.released, old.elastic_energy(0, &before.particles));
        assert!(changed.released > 0.0);
        let spring = changed.links.spring_of(0);
        let stretch = spring.rest_length - (after.particles.pos[1] - after.particles.pos[0]).norm();
        let made = 0.5 * spring.stiffness.kn * stretch * stretch;
        assert!(made > 0.0 && (changed.made - made).abs() <= 1e-12 * made, "{}", changed.made);
        // a connection removed: the others are matched by their nodes, not their index
        let mut removed = before.clone();
        removed.connections.remove(1);
        let gone = links_carried(&old, &before, &removed, mode);
        assert_eq!(gone.links.state[..], [old.state[0].clone(), old.state[2].clone()]);
        assert_eq!(gone.released, old.elastic_energy(1, &before.particles));
        // old particles that are no longer the same: every link made at rest
        let mut kinds = before.clone();
        kinds.particles.kind.swap(0, 4);
        let anew = links_carried(&old, &before, &kinds, mode);
        assert_eq!(anew.links.state, Links::from_model(&kinds, mode).state);
    }

    #[test]
    fn a_wall_moved_by_hand_or_put_in_another_one_place_is_another_wall() {
        let before = model();
        let mut after = before.clone();
        after.walls[0].velocity = Vec3::new(0.0, 0.0, 0.1);
        assert!(only_adds_bodies(&before, &after), "a wall set moving is the same wall");
        after.walls[0].point.z += 1e-3;
        assert!(!only_adds_bodies(&before, &after));
        let mut swapped = before.clone();
        let w = swapped.walls[0];
        swapped.walls[0] = flexdem_elements::Wall { normal: Vec3::x(), ..w };
        assert!(!only_adds_bodies(&before, &swapped));
    }
}
