//! The four parts of a VTK frame, built from a simulation's public state: particles,
//! connections, PFacets and contacts (the data each holds is listed in the module doc of
//! [`crate::Output`]).

use crate::vtk::{CellKind, DataArray, PolyData};
use flexdem_contact::LinkStatus;
use flexdem_elements::virtual_sphere::{Feature, Site};
use flexdem_elements::{ParticleKind, NO_STRUCTURE};
use flexdem_geom::Vec3;
use flexdem_integrate::Simulation;

/// A vector as an array.
fn xyz(v: &Vec3) -> [f64; 3] {
    [v.x, v.y, v.z]
}

/// A structure id for VTK: −1 for none (free spheres).
fn structure_id(structure: u32) -> i32 {
    if structure == NO_STRUCTURE {
        -1
    } else {
        i32::try_from(structure).unwrap_or(i32::MAX)
    }
}

/// An id (material, particle) as a VTK Int32 (saturating; ids never get that large).
fn id32(id: u32) -> i32 {
    i32::try_from(id).unwrap_or(i32::MAX)
}

/// Every particle as a point with a vertex cell; point data `id`, `radius`, `velocity`,
/// `angular_velocity`, `force` (total force at the last step), `kind` (0 sphere, 1 node),
/// `structure` (−1 for free spheres), `material`.
pub fn particles_polydata(sim: &Simulation) -> PolyData {
    let p = &sim.model().particles;
    let n = p.pos.len();
    let forces = sim.forces();
    let force = (0..n).map(|i| forces.get(i).map_or([0.0; 3], xyz));
    let kind = p.kind.iter().map(|k| i32::from(*k == ParticleKind::Node)).collect();
    PolyData {
        points: p.pos.iter().map(xyz).collect(),
        cell_kind: CellKind::Verts,
        cell_size: 1,
        connectivity: (0..n as i64).collect(),
        point_data: vec![
            DataArray::integers("id", (0..n as u32).map(id32).collect()),
            DataArray::scalars("radius", p.radius.clone()),
            DataArray::vectors("velocity", p.vel.iter().map(xyz)),
            DataArray::vectors("angular_velocity", p.ang_vel.iter().map(xyz)),
            DataArray::vectors("force", force),
            DataArray::integers("kind", kind),
            DataArray::integers(
                "structure",
                p.structure.iter().map(|&s| structure_id(s)).collect(),
            ),
            DataArray::integers("material", p.material.iter().map(|&m| id32(m)).collect()),
        ],
        cell_data: vec![],
    }
}

/// The points of a part made of cells over particles: only the particles `cells` use, each
/// once, in order of first use. Returns the point coordinates, the particle id of each point
/// and the cells' connectivity in point indices.
fn compact_points(
    sim: &Simulation,
    cells: impl Iterator<Item = u32>,
) -> (Vec<[f64; 3]>, Vec<i32>, Vec<i64>) {
    let pos = &sim.model().particles.pos;
    let mut local = vec![u32::MAX; pos.len()];
    let (mut points, mut ids, mut connectivity) = (Vec::new(), Vec::new(), Vec::new());
    for particle in cells {
        let Some(slot) = local.get_mut(particle as usize) else {
            // Not a particle (a model that passed validation has none): a point of its own.
            connectivity.push(points.len() as i64);
            points.push([f64::NAN; 3]);
            ids.push(-1);
            continue;
        };
        if *slot == u32::MAX {
            *slot = points.len() as u32;
            points.push(xyz(&pos[particle as usize]));
            ids.push(id32(particle));
        }
        connectivity.push(i64::from(*slot));
    }
    (points, ids, connectivity)
}

/// Connections as line cells between their nodes; point data `id` (particle id); cell data
/// `radius`, `axial_force` (link normal force, compression positive, tension negative),
/// `shear_force`, `broken` (0/1), `status` (0 cohesive, 1 frictional, 2 broken), `structure`,
/// `material`.
pub fn connections_polydata(sim: &Simulation) -> PolyData {
    let connections = &sim.model().connections;
    let (points, ids, connectivity) = compact_points(sim, connections.iter().flat_map(|c| c.nodes));
    let links = sim.links();
    let status: Vec<i32> = (0..connections.len())
        .map(|i| match links.state.get(i).map(|s| s.status) {
            Some(LinkStatus::Cohesive) | None => 0,
            Some(LinkStatus::Frictional) => 1,
            Some(LinkStatus::Broken) => 2,
        })
        .collect();
    PolyData {
        points,
        cell_kind: CellKind::Lines,
        cell_size: 2,
        connectivity,
        point_data: vec![DataArray::integers("id", ids)],
        cell_data: vec![
            DataArray::scalars("radius", connections.iter().map(|c| c.radius).collect()),
            DataArray::scalars(
                "axial_force",
                (0..connections.len()).map(|i| links.normal_force(i)).collect(),
            ),
            DataArray::vectors(
                "shear_force",
                // the shear force the last update left (the link state's: a resumed run's
                // too, carried by the checkpoint)
                (0..connections.len())
                    .map(|i| links.state.get(i).map_or([0.0; 3], |s| xyz(&s.shear_force))),
            ),
            DataArray::flags("broken", status.iter().map(|&s| u8::from(s == 2)).collect()),
            DataArray::integers("status", status),
            DataArray::integers(
                "structure",
                connections.iter().map(|c| structure_id(c.structure)).collect(),
            ),
            DataArray::integers("material", connections.iter().map(|c| id32(c.material)).collect()),
        ],
    }
}

/// PFacets as triangles over their nodes; point data `id` (particle id); cell data `radius`,
/// `structure`, `material`.
pub fn pfacets_polydata(sim: &Simulation) -> PolyData {
    let pfacets = &sim.model().pfacets;
    let (points, ids, connectivity) = compact_points(sim, pfacets.iter().flat_map(|f| f.nodes));
    PolyData {
        points,
        cell_kind: CellKind::Polys,
        cell_size: 3,
        connectivity,
        point_data: vec![DataArray::integers("id", ids)],
        cell_data: vec![
            DataArray::scalars("radius", pfacets.iter().map(|f| f.radius).collect()),
            DataArray::integers(
                "structure",
                pfacets.iter().map(|f| structure_id(f.structure)).collect(),
            ),
            DataArray::integers("material", pfacets.iter().map(|f| id32(f.material)).collect()),
        ],
    }
}

/// The centre of a contact site: Σ weights·positions of its nodes, or `point` (the contact
/// point) for a wall site, which has no nodes.
pub fn site_centre(sim: &Simulation, site: &Site, point: &Vec3) -> Vec3 {
    let pos = &sim.model().particles.pos;
    let count = site.node_count();
    if count == 0 {
        return *point;
    }
    (0..count).fold(Vec3::zeros(), |sum, k| {
        sum + site.weights[k] * pos.get(site.nodes[k] as usize).copied().unwrap_or(*point)
    })
}

/// The kind of a contact site's feature: 0 particle, 1 edge, 2 face, 3 wall.
fn feature_kind(site: &Site) -> i32 {
    match site.feature {
        Feature::Particle(_) => 0,
        Feature::Edge(_) => 1,
        Feature::Face(_) => 2,
        Feature::Wall(_) => 3,
    }
}

/// Contacts as lines from the centre of site 1 to the centre of site 2 (see `site_centre`);
/// cell data `normal_force` (compression positive), `force` (total force on body 2),
/// `shear_force`, `point` (contact point), `kind1`, `kind2` (0 particle, 1 edge, 2 face,
/// 3 wall).
pub fn contacts_polydata(sim: &Simulation) -> PolyData {
    let list = sim.contacts();
    let mut points = Vec::with_capacity(2 * list.len());
    for c in &list {
        points.push(xyz(&site_centre(sim, &c.site1, &c.point)));
        points.push(xyz(&site_centre(sim, &c.site2, &c.point)));
    }
    PolyData {
        points,
        cell_kind: CellKind::Lines,
        cell_size: 2,
        connectivity: (0..2 * list.len() as i64).collect(),
        point_data: vec![],
        cell_data: vec![
            DataArray::scalars(
                "normal_force",
                list.iter().map(|c| c.forces.normal_force).collect(),
            ),
            DataArray::vectors("force", list.iter().map(|c| xyz(&c.forces.force_on_2))),
            DataArray::vectors("shear_force", list.iter().map(|c| xyz(&c.forces.shear_force))),
            DataArray::vectors("point", list.iter().map(|c| xyz(&c.point))),
            DataArray::integers("kind1", list.iter().map(|c| feature_kind(&c.site1)).collect()),
            DataArray::integers("kind2", list.iter().map(|c| feature_kind(&c.site2)).collect()),
        ],
    }
}
