//! One contact: its type, how a touching found by the pipelines becomes a contact (its
//! constants and birth normal), its geometry at a step, and what its birth moves the energy
//! balance by. Shared by the general pipeline (`contacts.rs`) and the free spheres' neighbour
//! list (`neighbours.rs`).

use crate::dashpots::site_mass;
use flexdem_contact::{
    effective_mass, ContactDamping, ContactForces, ContactKinematics, FrictionalContact,
    FrictionalParams, LinkKinematicsMode,
};
use flexdem_elements::pairs::{self, Candidate, SphereRef};
use flexdem_elements::touching::Element;
use flexdem_elements::virtual_sphere::{
    contact_geometry_crossing, crossing_normal, non_ratcheting_relative_velocity, virtual_sphere,
    ContactGeometry, Feature, Kinematics, Site, VirtualSphere,
};
use flexdem_elements::Model;
use flexdem_geom::{Real, Vec3};
use serde::{Deserialize, Serialize};

/// One contact: where it sits on each body, its constants and its state.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Contact {
    /// Site on body 1 (a wall, or the body with the smaller (owner, feature): a free sphere
    /// before a structure, a structure before one of higher id, and in a structure touching
    /// itself the smaller feature).
    pub site1: Site,
    /// Site on body 2.
    pub site2: Site,
    /// Owners of the two sites (a free sphere, a structure or a wall), for handovers.
    pub owners: (u64, u64),
    /// Stiffnesses, friction and dashpots.
    pub params: FrictionalParams,
    /// Shear force, last normal, dissipation.
    pub state: FrictionalContact,
    /// Forces of the last update.
    #[serde(skip)]
    pub forces: ContactForces,
    /// Contact point at the last update.
    pub point: Vec3,
}

impl Contact {
    /// The key contacts are sorted and matched by: the two features.
    pub fn key(&self) -> (Feature, Feature) {
        (self.site1.feature, self.site2.feature)
    }
}

/// What the contacts made at one detection added to or took from the energy balance (see
/// [`ContactPipeline::settle_births`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct BirthReport {
    /// First touches found with more overlap than one step of approach explains.
    pub born_deep: u64,
    /// Energy put in by contacts that started or ended within the step before (J): see
    /// [`ContactPipeline::settle_births`]; positive for contacts found late.
    pub born_energy: Real,
    /// The part of `born_energy` put in by the first touches found late (`born_deep`):
    /// `½·kn·δ·δ₋` each, `δ₋ = δ − u·dt₀ > 0` the overlap one step before (J).
    pub late_energy: Real,
    /// Elastic energy given up by contacts that ended while holding it (J).
    pub released: Real,
}

/// A touching found this step, before it is matched with the contacts of the last step.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Touching {
    pub(crate) candidate: Candidate,
    pub(crate) materials: (u32, u32),
    pub(crate) owners: (u64, u64),
}

pub(crate) const SPHERE_OWNER: u64 = 0;
pub(crate) const STRUCTURE_OWNER: u64 = 1 << 32;
pub(crate) const WALL_OWNER: u64 = 2 << 32;

pub(crate) fn owner(model: &Model, e: Element) -> u64 {
    match e {
        Element::Particle(i) => SPHERE_OWNER | u64::from(i),
        Element::Connection(k) => {
            STRUCTURE_OWNER | u64::from(model.connections[k as usize].structure)
        }
        Element::PFacet(k) => STRUCTURE_OWNER | u64::from(model.pfacets[k as usize].structure),
    }
}

pub(crate) fn material(model: &Model, e: Element) -> u32 {
    match e {
        Element::Particle(i) => model.particles.material[i as usize],
        Element::Connection(k) => model.connections[k as usize].material,
        Element::PFacet(k) => model.pfacets[k as usize].material,
    }
}

/// What a contact entering the balance at this step moves it by (see
/// [`ContactPipeline::settle_births`]): `½·kn·δ·δ₋`, `δ` its overlap (less its offset) with geometry
/// `g`, `δ₋ = δ − u·dt` the overlap one step before from its approach speed `u` over the step
/// `dt` just done.
pub(crate) fn birth_jump(
    params: &FrictionalParams,
    state: &FrictionalContact,
    g: &ContactGeometry,
    dt: Real,
) -> Real {
    let overlap = g.overlap - state.overlap_offset;
    if !(overlap > 0.0) {
        return 0.0;
    }
    let approach = -g.relative_velocity.dot(&g.normal);
    0.5 * params.kn * overlap * (overlap - approach * dt)
}

/// The touching of free spheres `i` and `j` (`i < j`), if they overlap: the general
/// pipeline's closest points of the pair (`pairs::sphere_sphere`).
pub(crate) fn sphere_touching(model: &Model, i: u32, j: u32) -> Option<Touching> {
    let p = &model.particles;
    let sphere =
        |i: u32| SphereRef { id: i, center: p.pos[i as usize], radius: p.radius[i as usize] };
    let candidate = pairs::sphere_sphere(&sphere(i), &sphere(j));
    (candidate.overlap() > 0.0).then(|| Touching {
        candidate,
        materials: (p.material[i as usize], p.material[j as usize]),
        owners: (owner(model, Element::Particle(i)), owner(model, Element::Particle(j))),
    })
}

/// The touching of wall `w` and particle `i`, if it reaches through the wall's plane (a
/// wall touches every particle on its side once).
pub(crate) fn wall_touching(model: &Model, w: u32, i: u32) -> Option<Touching> {
    let p = &model.particles;
    let wall = &model.walls[w as usize];
    let x = p.pos[i as usize];
    let r = p.radius[i as usize];
    let gap = (x - wall.point).dot(&wall.normal);
    (r - gap > 0.0).then(|| {
        let on_plane = x - wall.normal * gap;
        Touching {
            candidate: Candidate {
                site1: Site::wall(w),
                site2: Site::particle(i, r),
                center1: on_plane,
                center2: x,
                distance: gap,
            },
            materials: (wall.material, p.material[i as usize]),
            owners: (WALL_OWNER | u64::from(w), owner(model, Element::Particle(i))),
        }
    })
}

pub(crate) fn new_contact(model: &Model, t: &Touching) -> Contact {
    let m1 = &model.materials[t.materials.0 as usize];
    let m2 = &model.materials[t.materials.1 as usize];
    let c = &t.candidate;
    let (r1, r2) = match c.site1.feature {
        // a wall has the particle's radius in eq 3 and 4 (YADE)
        Feature::Wall(_) => (c.site2.radius, c.site2.radius),
        _ => (c.site1.radius, c.site2.radius),
    };
    let normal = birth_normal(model, c);
    // the pair's effective mass, for the dashpots (model.md §7)
    let p = &model.particles;
    let m_eff = if m1.damping == ContactDamping::None && m2.damping == ContactDamping::None {
        Real::INFINITY
    } else {
        effective_mass(site_mass(&c.site1, p), site_mass(&c.site2, p))
    };
    Contact {
        site1: c.site1,
        site2: c.site2,
        owners: t.owners,
        params: FrictionalParams::from_materials(m1, r1, m2, r2, m_eff),
        state: FrictionalContact::new(normal),
        forces: ContactForces::default(),
        point: c.center1 + normal * c.site1.radius,
    }
}

/// The normal a new contact is made with: from centre 1 to centre 2 (eq 1's geometry). Where
/// the centres coincide (the skeletons met or crossed before the contact was found) that
/// direction does not exist; then the face normal of a PFacet site, or the common normal of
/// two edges, or the relative velocity, turned against the approach (`n·(v2 − v1) ≤ 0`), so
/// that the force pushes each body back the way it came.
fn birth_normal(model: &Model, c: &Candidate) -> Vec3 {
    let d = c.center2 - c.center1;
    let scale = c.site1.radius + c.site2.radius + c.center1.abs().max() + c.center2.abs().max();
    if d.norm() > 1e-14 * scale {
        return d.normalize();
    }
    let p = &model.particles;
    let k = Kinematics::of(p);
    let v = virtual_sphere(&c.site2, &k).velocity - virtual_sphere(&c.site1, &k).velocity;
    let axis = |site: &Site| -> Vec3 {
        match site.feature {
            Feature::Edge(_) => p.pos[site.nodes[1] as usize] - p.pos[site.nodes[0] as usize],
            _ => Vec3::zeros(),
        }
    };
    let face = |site: &Site| -> Vec3 {
        match site.feature {
            Feature::Face(_) => {
                let [a, b, c] = site.nodes.map(|i| p.pos[i as usize]);
                (b - a).cross(&(c - a))
            }
            _ => Vec3::zeros(),
        }
    };
    let tiny = |x: &Vec3| x.norm() <= 1e-14 * scale * scale;
    let mut n = face(&c.site1);
    if tiny(&n) {
        n = face(&c.site2);
    }
    if tiny(&n) {
        n = axis(&c.site1).cross(&axis(&c.site2));
    }
    if tiny(&n) {
        n = -v;
    }
    if n.norm() == 0.0 || !n.iter().all(|x| x.is_finite()) {
        return Vec3::z();
    }
    let n = n.normalize();
    if n.dot(&v) > 0.0 {
        -n
    } else {
        n
    }
}

/// What the contact law reads of a contact geometry.
pub(crate) fn law_kinematics(g: &ContactGeometry) -> ContactKinematics {
    ContactKinematics {
        normal: g.normal,
        overlap: g.overlap,
        relative_velocity: g.relative_velocity,
        spin_about_normal: g.spin_about_normal,
    }
}

/// Virtual spheres and contact geometry of a contact from the current state.
pub(crate) fn geometry(
    model: &Model,
    k: &Kinematics<'_>,
    c: &Contact,
) -> (VirtualSphere, VirtualSphere, ContactGeometry) {
    geometry_of(model, k, &c.site1, &c.site2, &c.state.normal)
}

/// Virtual spheres and contact geometry of the contact of `site1` and `site2` whose last
/// normal was `previous_normal`, from the current state.
pub(crate) fn geometry_of(
    model: &Model,
    k: &Kinematics<'_>,
    site1: &Site,
    site2: &Site,
    previous_normal: &Vec3,
) -> (VirtualSphere, VirtualSphere, ContactGeometry) {
    let vs2 = virtual_sphere(site2, k);
    match site1.feature {
        Feature::Wall(w) => {
            let wall = &model.walls[w as usize];
            let gap = (vs2.center - wall.point).dot(&wall.normal);
            let on_plane = vs2.center - wall.normal * gap;
            let vs1 = VirtualSphere {
                center: on_plane,
                velocity: wall.velocity,
                angular_velocity: Vec3::zeros(),
            };
            let r = site2.radius;
            let overlap = r - gap;
            let point = on_plane - wall.normal * (0.5 * overlap);
            let v2 = vs2.velocity + vs2.angular_velocity.cross(&(point - vs2.center));
            let g = ContactGeometry {
                normal: wall.normal,
                overlap,
                point,
                relative_velocity: v2 - wall.velocity,
                spin_about_normal: 0.5 * wall.normal.dot(&vs2.angular_velocity),
            };
            (vs1, vs2, g)
        }
        _ => {
            let vs1 = virtual_sphere(site1, k);
            let mut g = contact_geometry_crossing(
                &vs1,
                site1.radius,
                &vs2,
                site2.radius,
                previous_normal,
                || crossing_normal(site1, site2, k.pos, previous_normal),
            );
            // YADE's grid and PFacet functors take the non-ratcheting relative velocity
            let on_element = |s: &Site| matches!(s.feature, Feature::Edge(_) | Feature::Face(_));
            if k.link_mode == LinkKinematicsMode::Yade && (on_element(site1) || on_element(site2)) {
                g.relative_velocity = non_ratcheting_relative_velocity(
                    &vs1,
                    site1.radius,
                    &vs2,
                    site2.radius,
                    &g.normal,
                    g.overlap,
                );
            }
            (vs1, vs2, g)
        }
    }
}

/// The largest distance from a site's centre to its nodes: 0 on a particle, up to the length
/// of an edge or the size of a face.
pub(crate) fn extent(site: &Site, pos: &[Vec3]) -> Real {
    let n = site.node_count();
    if n < 2 {
        return 0.0;
    }
    let nodes = &site.nodes[..n];
    let centre: Vec3 = nodes.iter().zip(&site.weights).map(|(&i, &w)| pos[i as usize] * w).sum();
    nodes.iter().map(|&i| (pos[i as usize] - centre).norm()).fold(0.0, Real::max)
}

/// Whether contact `new` sees the touching of `old` (same owners) from the other side: its
/// body 1 on the other's body 2. Only a structure touching itself can be seen so (bodies are
/// ordered by owner, see `contacts::oriented`); the sides are matched by the nodes the sites
/// share, then by the nearer site centres.
pub(crate) fn mirrored(new: &Contact, old: &Contact, pos: &[Vec3]) -> bool {
    if new.owners.0 != new.owners.1 {
        return false;
    }
    fn nodes(s: &Site) -> &[u32] {
        &s.nodes[..s.node_count()]
    }
    let shared = |a: &Site, b: &Site| nodes(a).iter().filter(|n| nodes(b).contains(n)).count();
    let same = shared(&new.site1, &old.site1) + shared(&new.site2, &old.site2);
    let cross = shared(&new.site1, &old.site2) + shared(&new.site2, &old.site1);
    if same != cross {
        return cross > same;
    }
    let centre = |s: &Site| -> Vec3 {
        nodes(s).iter().zip(&s.weights).map(|(&i, &w)| pos[i as usize] * w).sum()
    };
    let (n1, n2, o1, o2) =
        (centre(&new.site1), centre(&new.site2), centre(&old.site1), centre(&old.site2));
    (n1 - o2).norm() + (n2 - o1).norm() < (n1 - o1).norm() + (n2 - o2).norm()
}
