//! The one-contact-per-touching rule, and validation.md cases 7, 8, 9 and 13 at the level of
//! contact geometry and force distribution.

use super::*;
use crate::pairs::*;
use crate::virtual_sphere::{distribute_force, Feature, Site};
use crate::{Connection, PFacet};
use flexdem_geom::Vec3;

/// A small mesh: node positions, connections, PFacets and their radius. [`Fan::new`] makes a
/// planar fan of `k` triangles around node 0 (at the origin), radius `rho`, in z = 0:
/// ring nodes 1..=k, spokes = connections 0..k (0–i), rim = connections k..2k (i–i+1).
struct Fan {
    pos: Vec<Vec3>,
    conn_nodes: Vec<[u32; 2]>,
    pf_nodes: Vec<[u32; 3]>,
    pf_conns: Vec<[u32; 3]>,
    radius: f64,
    /// The same lists as a model's connections and PFacets (what [`Topology`] reads).
    connections: Vec<Connection>,
    pfacets: Vec<PFacet>,
}

impl Fan {
    fn new(k: u32, rho: f64, radius: f64) -> Self {
        let mut pos = vec![Vec3::zeros()];
        for i in 0..k {
            let a = std::f64::consts::TAU * f64::from(i) / f64::from(k) + 0.1;
            pos.push(Vec3::new(rho * a.cos(), rho * a.sin(), 0.0));
        }
        let ring = |i: u32| 1 + i % k;
        let mut conn_nodes: Vec<[u32; 2]> = (0..k).map(|i| [0, ring(i)]).collect();
        conn_nodes.extend((0..k).map(|i| [ring(i), ring(i + 1)]));
        let pf_nodes = (0..k).map(|i| [0, ring(i), ring(i + 1)]).collect();
        // connections: [0] joins nodes 0-1 (spoke i), [1] joins 1-2 (rim i), [2] joins 2-0 (spoke i+1)
        let pf_conns = (0..k).map(|i| [i, k + i, (i + 1) % k]).collect();
        Fan::from_lists(pos, conn_nodes, pf_nodes, pf_conns, radius)
    }

    /// A mesh of these nodes, connections and PFacets (one material, structure 0).
    fn from_lists(
        pos: Vec<Vec3>,
        conn_nodes: Vec<[u32; 2]>,
        pf_nodes: Vec<[u32; 3]>,
        pf_conns: Vec<[u32; 3]>,
        radius: f64,
    ) -> Self {
        let connections = conn_nodes
            .iter()
            .map(|&nodes| Connection {
                nodes,
                radius,
                material: 0,
                mask: 1,
                structure: 0,
                rest_length: 1.0,
            })
            .collect();
        let pfacets = pf_nodes
            .iter()
            .zip(&pf_conns)
            .map(|(&nodes, &connections)| PFacet {
                nodes,
                connections,
                radius,
                material: 0,
                mask: 1,
                structure: 0,
            })
            .collect();
        Fan { pos, conn_nodes, pf_nodes, pf_conns, radius, connections, pfacets }
    }

    fn topology(&self) -> Topology<'_> {
        Topology { connections: &self.connections, pfacets: &self.pfacets }
    }

    fn pfacet(&self, f: usize) -> PFacetRef {
        let n = self.pf_nodes[f];
        PFacetRef {
            id: f as u32,
            nodes: n,
            connections: self.pf_conns[f],
            corners: n.map(|i| self.pos[i as usize]),
            radius: self.radius,
        }
    }

    fn connection(&self, c: usize) -> ConnectionRef {
        let n = self.conn_nodes[c];
        ConnectionRef {
            id: c as u32,
            nodes: n,
            ends: n.map(|i| self.pos[i as usize]),
            radius: self.radius,
        }
    }

    /// Candidates of sphere `s` against every PFacet of the fan.
    fn sphere_against_pfacets(&self, s: &SphereRef) -> Vec<ElementCandidate> {
        (0..self.pf_nodes.len())
            .map(|f| ElementCandidate {
                element1: Element::Particle(s.id),
                element2: Element::PFacet(f as u32),
                candidate: sphere_pfacet(s, &self.pfacet(f)),
            })
            .collect()
    }

    /// Candidates of sphere `s` against the spokes only (a star of connections).
    fn sphere_against_spokes(&self, s: &SphereRef) -> Vec<ElementCandidate> {
        (0..self.pf_nodes.len())
            .map(|c| ElementCandidate {
                element1: Element::Particle(s.id),
                element2: Element::Connection(c as u32),
                candidate: sphere_connection(s, &self.connection(c)),
            })
            .collect()
    }
}

fn touchings(c: &[ElementCandidate], t: &Topology<'_>) -> Vec<usize> {
    let mut out = Vec::new();
    resolve_touchings(c, t, &mut out);
    out
}

const SPHERE: u32 = 1000;

/// validation.md case 9: a sphere exactly above a node shared by k PFacets (or k
/// connections) has one contact, on the node.
#[test]
fn one_contact_at_a_node_shared_by_k_elements() {
    for k in [3, 5, 6, 8] {
        let fan = Fan::new(k, 1.0, 0.01);
        let s = SphereRef { id: SPHERE, center: Vec3::new(0.0, 0.0, 0.05), radius: 0.045 };
        let c = fan.sphere_against_pfacets(&s);
        assert!(c.iter().all(|e| e.candidate.site2.feature == Feature::Particle(0)));
        let t = touchings(&c, &fan.topology());
        assert_eq!(t.len(), 1, "k = {k}: {t:?}");
        let c = fan.sphere_against_spokes(&s);
        let t = touchings(&c, &fan.topology());
        assert_eq!(t.len(), 1, "k = {k} spokes: {t:?}");
        assert_eq!(c[t[0]].candidate.site2.feature, Feature::Particle(0));
    }
}

/// The same with the sphere off the node by round-off (1e-14): the elements compute the point
/// with different round-off, and snapping makes them all report the node.
#[test]
fn one_contact_near_a_node_despite_round_off() {
    for k in [4, 6, 7] {
        let fan = Fan::new(k, 1.0, 0.01);
        for off in [
            Vec3::new(1e-14, 0.0, 0.0),
            Vec3::new(-3e-15, 2e-14, 0.0),
            Vec3::new(1e-13, 1e-13, 0.0),
        ] {
            let s =
                SphereRef { id: SPHERE, center: Vec3::new(0.0, 0.0, 0.05) + off, radius: 0.045 };
            let t = touchings(&fan.sphere_against_pfacets(&s), &fan.topology());
            assert_eq!(t.len(), 1, "k = {k}, offset {off}: {t:?}");
        }
    }
}

/// A sphere sliding over a flat fan at constant height always has exactly one contact, with
/// the same overlap, whatever element, edge or node it is over (validation.md case 10 at the
/// geometry level).
#[test]
fn sliding_over_a_flat_mesh_keeps_one_contact_of_constant_overlap() {
    let fan = Fan::new(6, 1.0, 0.01);
    let topo = fan.topology();
    let h = 0.05;
    let r = 0.045; // overlap r + 0.01 - h = 0.005
    let mut features = std::collections::BTreeSet::new();
    for i in 0..=400 {
        // a line through the node, across spokes, and an offset line across faces and edges
        for (y0, dx) in [(0.0, 0.0), (0.0123, 0.0), (0.3, 0.2)] {
            let x = f64::from(i - 200) * 0.0025 + dx; // exactly 0 at i = 200, inside the rim
            let s = SphereRef { id: SPHERE, center: Vec3::new(x, y0, h), radius: r };
            let c = fan.sphere_against_pfacets(&s);
            let t = touchings(&c, &topo);
            assert_eq!(t.len(), 1, "x = {x}, y = {y0}: {t:?}");
            let cand = &c[t[0]].candidate;
            assert!((cand.overlap() - 0.005).abs() < 1e-12, "overlap {}", cand.overlap());
            features.insert(cand.site2.feature);
        }
    }
    // along a spoke: the sphere is over a shared edge (reported as edge or face by the two
    // PFacets, depending on round-off): still one contact
    let (c, s) = (0.1f64.cos(), 0.1f64.sin());
    for i in 1..=300 {
        let d = f64::from(i) * 0.0025;
        let sphere = SphereRef { id: SPHERE, center: Vec3::new(d * c, d * s, h), radius: r };
        let cands = fan.sphere_against_pfacets(&sphere);
        let t = touchings(&cands, &topo);
        assert_eq!(t.len(), 1, "along the spoke at {d}: {t:?}");
        assert!((cands[t[0]].candidate.overlap() - 0.005).abs() < 1e-12);
    }
    // the paths cross faces and the node
    assert!(features.iter().any(|f| matches!(f, Feature::Face(_))));
    assert!(features.contains(&Feature::Particle(0)));
}

/// A sphere sitting in a concave valley between two faces touches both: two contacts.
#[test]
fn concave_valley_gives_one_contact_per_face() {
    // two triangles sharing edge (0,1) along x, folded up like a V
    let pos = [
        Vec3::new(-1.0, 0.0, 0.0),
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(0.0, 1.0, 1.0),
        Vec3::new(0.0, -1.0, 1.0),
    ];
    let mesh = Fan::from_lists(
        pos.to_vec(),
        vec![[0, 1], [1, 2], [2, 0], [1, 3], [3, 0]],
        vec![[0, 1, 2], [1, 0, 3]],
        vec![[0, 1, 2], [0, 4, 3]],
        0.01,
    );
    let topo = mesh.topology();
    let pf = |f: usize| mesh.pfacet(f);
    // the walls are at 45 degrees: a sphere on the axis at height z touches both at z/sqrt(2)
    let s = SphereRef { id: SPHERE, center: Vec3::new(0.0, 0.0, 0.3), radius: 0.25 };
    let c: Vec<_> = (0..2)
        .map(|f| ElementCandidate {
            element1: Element::Particle(SPHERE),
            element2: Element::PFacet(f as u32),
            candidate: sphere_pfacet(&s, &pf(f)),
        })
        .collect();
    let t = touchings(&c, &topo);
    assert_eq!(t, vec![0, 1]);
    for &i in &t {
        assert!(matches!(c[i].candidate.site2.feature, Feature::Face(_)));
        assert!((c[i].candidate.distance - 0.3 / 2f64.sqrt()).abs() < 1e-12);
    }
}

/// Two folds of one structure pressed together at two places (the Brazier winding): the upper
/// fold's node 3 sits on face 0 (PFacet 1's closest feature), and PFacet 2, which contains
/// node 3, reaches deeper into face 0 along its far edge, a whole element away. PFacet 2's
/// elements contain both features of node 3's touching, and it is closer, but it is not at
/// the same place: both touchings are contacts, else node 3 would sink through face 0.
#[test]
fn folds_pressed_together_at_two_places_get_a_contact_at_each() {
    let r = 0.01;
    let pos = [
        // the lower fold: face 0
        Vec3::new(-1.0, -1.0, 0.0),
        Vec3::new(3.0, -1.0, 0.0),
        Vec3::new(-1.0, 3.0, 0.0),
        // node 3, overlapping face 0 by 0.2 r
        Vec3::new(0.0, 0.0, 1.8 * r),
        // PFacet 1 rises from node 3
        Vec3::new(-0.5, 0.0, 0.5),
        Vec3::new(-0.5, 0.5, 0.5),
        // PFacet 2 goes down to node 7, overlapping face 0 by 0.5 r, 1 m away
        Vec3::new(1.0, -0.1, 1.6 * r),
        Vec3::new(1.0, 0.1, 1.5 * r),
    ];
    let mesh = Fan::from_lists(
        pos.to_vec(),
        vec![[0, 1], [1, 2], [2, 0], [3, 4], [4, 5], [5, 3], [3, 6], [6, 7], [7, 3]],
        vec![[0, 1, 2], [3, 4, 5], [3, 6, 7]],
        vec![[0, 1, 2], [3, 4, 5], [6, 7, 8]],
        r,
    );
    let topo = mesh.topology();
    let pf = |f: usize| mesh.pfacet(f);
    let c: Vec<_> = [1, 2]
        .map(|f| ElementCandidate {
            element1: Element::PFacet(f as u32),
            element2: Element::PFacet(0),
            candidate: pfacet_pfacet(&pf(f), &pf(0)),
        })
        .into();
    assert_eq!(c[0].candidate.site1.feature, Feature::Particle(3));
    assert_eq!(c[1].candidate.site1.feature, Feature::Particle(7));
    assert!((c[0].candidate.overlap() - 0.2 * r).abs() < 1e-12);
    assert!((c[1].candidate.overlap() - 0.5 * r).abs() < 1e-12);
    // PFacet 2 saw node 3 and is closer: without the place test it would dominate
    assert!(topo.element_contains(c[1].element1, Feature::Particle(3)));
    assert!(!same_place(&c[1].candidate, &c[0].candidate));
    assert_eq!(touchings(&c, &topo), vec![0, 1]);
}

/// validation.md case 7: a sphere on a horizontal connection at parameter t: the nodes carry
/// (1 − t, t) of the contact force, exactly.
#[test]
fn sphere_on_cylinder_splits_force_one_minus_t_t() {
    for t in [0.0, 0.1, 0.25, 0.5, 0.9, 1.0] {
        let c = ConnectionRef {
            id: 0,
            nodes: [0, 1],
            ends: [Vec3::zeros(), Vec3::new(2.0, 0.0, 0.0)],
            radius: 0.01,
        };
        let s = SphereRef { id: 2, center: Vec3::new(2.0 * t, 0.0, 0.05), radius: 0.045 };
        let cand = sphere_connection(&s, &c);
        // weight of the sphere, carried by the contact: force on the connection, downwards
        let f = Vec3::new(0.0, 0.0, -9.81);
        let point = cand.center2 + Vec3::z() * 0.01;
        let loads = distribute_force(
            &cand.site2,
            &[Vec3::zeros(), Vec3::new(2.0, 0.0, 0.0)],
            &cand.center2,
            &point,
            &f,
        );
        let on = |node: u32| {
            loads
                .iter()
                .filter(|l| l.node == node && l.force != Vec3::zeros())
                .map(|l| l.force)
                .sum::<Vec3>()
        };
        assert!((on(0) - f * (1.0 - t)).norm() <= 1e-15 * 9.81, "t = {t}");
        assert!((on(1) - f * t).norm() <= 1e-15 * 9.81, "t = {t}");
        // a vertical force at the axis point has no moment about it: no node torques
        assert!(loads.iter().all(|l| l.torque.norm() < 1e-15));
    }
}

/// validation.md case 8: a sphere above (0.1, 0.1) on the triangle (0,0,0), (1,0,0),
/// (0,1,0) puts 80 %, 10 %, 10 % of the force on the three nodes (YADE before its fix put
/// 80 % on the third node).
#[test]
fn sphere_on_pfacet_splits_force_by_barycentric_weights() {
    let f = PFacetRef {
        id: 0,
        nodes: [10, 11, 12],
        connections: [0, 1, 2],
        corners: [Vec3::zeros(), Vec3::x(), Vec3::y()],
        radius: 0.01,
    };
    let s = SphereRef { id: 3, center: Vec3::new(0.1, 0.1, 0.05), radius: 0.045 };
    let cand = sphere_pfacet(&s, &f);
    assert_eq!(cand.site2.feature, Feature::Face(0));
    let force = Vec3::new(0.0, 0.0, -1.0);
    let loads = distribute_force(
        &cand.site2,
        &[Vec3::zeros(); 13],
        &cand.center2,
        &(cand.center2 + Vec3::z() * 0.01),
        &force,
    );
    let expected = [0.8, 0.1, 0.1];
    for (l, (node, w)) in loads.iter().zip([10u32, 11, 12].iter().zip(expected)) {
        assert_eq!(l.node, *node);
        assert!((l.force - force * w).norm() < 1e-15, "{:?}", l);
    }
}

/// validation.md case 13: two connections crossing at 90 degrees, one on the other: one
/// contact at the crossing point. Two parallel connections, one along the other: one contact
/// at the middle of the overlap.
#[test]
fn crossed_and_parallel_cylinders_touch_once_at_the_right_point() {
    let r = 0.01;
    let lower = ConnectionRef {
        id: 0,
        nodes: [0, 1],
        ends: [Vec3::zeros(), Vec3::new(1.0, 0.0, 0.0)],
        radius: r,
    };
    // crossed at x = 0.3, resting at 2r - overlap 1e-4
    let upper = ConnectionRef {
        id: 1,
        nodes: [2, 3],
        ends: [Vec3::new(0.3, -0.5, 2.0 * r - 1e-4), Vec3::new(0.3, 0.5, 2.0 * r - 1e-4)],
        radius: r,
    };
    let c = connection_connection(&lower, &upper);
    assert!((c.center1 - Vec3::new(0.3, 0.0, 0.0)).norm() < 1e-14);
    assert!((c.center2 - Vec3::new(0.3, 0.0, 2.0 * r - 1e-4)).norm() < 1e-14);
    assert!((c.overlap() - 1e-4).abs() < 1e-15);
    assert!(
        matches!(c.site1.feature, Feature::Edge(0)) && matches!(c.site2.feature, Feature::Edge(1))
    );
    // parallel, shifted by 0.4 along x: overlap of the axes is [0.4, 1.0] on the lower one
    let upper = ConnectionRef {
        id: 1,
        nodes: [2, 3],
        ends: [Vec3::new(0.4, 0.0, 2.0 * r - 1e-4), Vec3::new(1.4, 0.0, 2.0 * r - 1e-4)],
        radius: r,
    };
    let c = connection_connection(&lower, &upper);
    assert!((c.center1 - Vec3::new(0.7, 0.0, 0.0)).norm() < 1e-12, "{}", c.center1);
    assert!((c.center2 - Vec3::new(0.7, 0.0, 2.0 * r - 1e-4)).norm() < 1e-12, "{}", c.center2);
    // the weight splits evenly between the two ends of the upper one around the middle
    let w = c.site2.weights;
    assert!((w[0] - 0.7).abs() < 1e-12 && (w[1] - 0.3).abs() < 1e-12, "{w:?}");
}

/// A cylinder lying across a PFacet's interior, both ends outside the triangle, is found
/// (YADE misses it).
#[test]
fn cylinder_across_face_interior_is_a_face_contact() {
    let f = PFacetRef {
        id: 0,
        nodes: [0, 1, 2],
        connections: [0, 1, 2],
        corners: [Vec3::zeros(), Vec3::new(2.0, 0.0, 0.0), Vec3::new(0.0, 2.0, 0.0)],
        radius: 0.01,
    };
    let c = ConnectionRef {
        id: 5,
        nodes: [3, 4],
        ends: [Vec3::new(0.5, -1.0, 0.015), Vec3::new(0.5, 3.0, 0.015)],
        radius: 0.01,
    };
    let cand = connection_pfacet(&c, &f);
    assert!((cand.overlap() - 0.005).abs() < 1e-12, "{}", cand.overlap());
    assert_eq!(cand.site2.feature, Feature::Face(0));
    assert!(matches!(cand.site1.feature, Feature::Edge(5)));
}

#[test]
fn features_incidence_follows_topology() {
    let fan = Fan::new(4, 1.0, 0.01);
    let t = fan.topology();
    assert!(t.features_incident(Feature::Particle(0), Feature::Edge(0)));
    assert!(t.features_incident(Feature::Face(0), Feature::Edge(4)));
    assert!(t.features_incident(Feature::Particle(2), Feature::Face(1)));
    assert!(!t.features_incident(Feature::Face(0), Feature::Face(1)));
    assert!(!t.features_incident(Feature::Edge(4), Feature::Edge(5)));
    assert!(t.element_contains(Element::PFacet(0), Feature::Edge(1)));
    assert!(!t.element_contains(Element::PFacet(0), Feature::Edge(2)));
    assert!(t.element_contains(Element::Particle(7), Feature::Particle(7)));
    let _ = Site::wall(0);
}
