//! Regions a packing fills: a box, a cylinder, or the inside of a closed triangle surface,
//! each answering where a sphere must move to lie wholly inside.

use flexdem_geom::{closed_surface_volume, project_point_triangle, Real, Vec3};
use std::f64::consts::PI;

/// A region of space that spheres fill.
#[derive(Clone, Debug)]
pub enum Region {
    /// An axis-aligned box.
    Box {
        /// Lower corner (m).
        min: Vec3,
        /// Upper corner (m).
        max: Vec3,
    },
    /// A right circular cylinder.
    Cylinder {
        /// Centre of the bottom disc (m).
        base: Vec3,
        /// Unit vector from the bottom disc to the top one.
        axis: Vec3,
        /// Radius (m).
        radius: Real,
        /// Height (m).
        height: Real,
    },
    /// The inside of a closed, consistently oriented triangle surface, kept `inset` away from
    /// it (a PFacet surface's own radius).
    Surface(ClosedSurface),
}

impl Region {
    /// Volume available to the spheres (m³): `Π (max − min)` for a box, `π R² h` for a
    /// cylinder, and for a surface its enclosed volume less `inset × area` (first order in
    /// the inset).
    pub fn volume(&self) -> Real {
        match self {
            Region::Box { min, max } => (max - min).iter().product(),
            Region::Cylinder { radius, height, .. } => PI * radius * radius * height,
            Region::Surface(s) => s.volume - s.inset * s.area,
        }
    }

    /// Lower and upper corners of a box around the region.
    pub fn bounds(&self) -> (Vec3, Vec3) {
        match self {
            Region::Box { min, max } => (*min, *max),
            Region::Cylinder { base, axis, radius, height } => {
                let top = base + axis * *height;
                // the disc of radius R normal to `axis` spans R·sqrt(1 − a_k²) along axis k
                let half = Vec3::from_fn(|k, _| radius * (1.0 - axis[k] * axis[k]).max(0.0).sqrt());
                (base.inf(&top) - half, base.sup(&top) + half)
            }
            Region::Surface(s) => (s.min, s.max),
        }
    }

    /// Whether a sphere of radius `r` centred at `c` lies wholly inside (to `slack`).
    pub fn holds(&self, c: &Vec3, r: Real, slack: Real) -> bool {
        let inside = match self {
            Region::Surface(s) => s.contains(c),
            _ => true,
        };
        inside && self.push_inside(c, r).norm() <= slack
    }

    /// The largest move a sphere of radius `r` may make in one step of a packing so that the
    /// region still sees it: a surface finds only the triangles within `r + inset` of a
    /// centre, and a sphere moving further in one step could pass through it unseen (a box
    /// and a cylinder clamp any centre, however far out).
    pub fn largest_step(&self, r: Real) -> Real {
        match self {
            Region::Surface(_) => 0.25 * r,
            _ => Real::INFINITY,
        }
    }

    /// The displacement that brings a sphere of radius `r` centred at `c` wholly inside the
    /// region (zero if it is): the centre clamped to the box shrunk by `r`; to the cylinder
    /// shrunk by `r` axially and radially; for a surface, moved along the direction from the
    /// closest surface point to the centre until it is `r + inset` away (the closest triangle
    /// only; the sweeps of the packing settle corners).
    pub fn push_inside(&self, c: &Vec3, r: Real) -> Vec3 {
        match self {
            Region::Box { min, max } => {
                let lo = min.add_scalar(r);
                let hi = max.add_scalar(-r);
                let clamped = Vec3::from_fn(|k, _| {
                    if lo[k] > hi[k] {
                        0.5 * (min[k] + max[k])
                    } else {
                        c[k].clamp(lo[k], hi[k])
                    }
                });
                clamped - c
            }
            Region::Cylinder { base, axis, radius, height } => {
                let rel = c - base;
                let a = rel.dot(axis);
                let radial = rel - axis * a;
                let a_new = if 2.0 * r > *height { 0.5 * height } else { a.clamp(r, height - r) };
                let room = (radius - r).max(0.0);
                let rho = radial.norm();
                let radial_new = if rho > room { radial * (room / rho) } else { radial };
                base + axis * a_new + radial_new - c
            }
            Region::Surface(s) => s.push_inside(c, r),
        }
    }

    /// A point drawn uniformly inside the region from two sources of uniform numbers in
    /// [0, 1) (rejection from the bounding box for a surface; `None` when the draw fell
    /// outside).
    pub fn sample(&self, u: [Real; 3]) -> Option<Vec3> {
        match self {
            Region::Box { min, max } => {
                Some(Vec3::from_fn(|k, _| min[k] + (max[k] - min[k]) * u[k]))
            }
            Region::Cylinder { base, axis, radius, height } => {
                let (e1, e2) = perpendicular_frame(axis);
                let rho = radius * u[0].sqrt();
                let phi = 2.0 * PI * u[1];
                Some(base + axis * (height * u[2]) + (e1 * phi.cos() + e2 * phi.sin()) * rho)
            }
            Region::Surface(s) => {
                let p = Vec3::from_fn(|k, _| s.min[k] + (s.max[k] - s.min[k]) * u[k]);
                s.contains(&p).then_some(p)
            }
        }
    }
}

/// Two unit vectors that make a right-handed orthonormal frame with `axis`.
fn perpendicular_frame(axis: &Vec3) -> (Vec3, Vec3) {
    let helper = if axis.x.abs() < 0.9 { Vec3::x() } else { Vec3::y() };
    let e1 = axis.cross(&helper).normalize();
    let e2 = axis.cross(&e1);
    (e1, e2)
}

/// A closed triangle surface, its triangles bucketed in a grid so that the triangles near a
/// sphere are found without visiting all of them.
#[derive(Clone, Debug)]
pub struct ClosedSurface {
    triangles: Vec<[Vec3; 3]>,
    /// Outward unit normals (the orientation of the triangles, flipped if they enclose a
    /// negative volume).
    normals: Vec<Vec3>,
    inset: Real,
    volume: Real,
    area: Real,
    min: Vec3,
    max: Vec3,
    cell: Real,
    dims: [usize; 3],
    /// Triangles of each cell (x fastest), as ranges of `cell_triangles`.
    cell_start: Vec<u32>,
    cell_triangles: Vec<u32>,
}

/// Why a surface cannot bound a packing.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SurfaceError {
    /// No triangles, or they enclose no volume.
    #[error("the surface encloses no volume ({volume} m³): it must be a closed surface")]
    Empty {
        /// The enclosed volume found.
        volume: Real,
    },
    /// An edge is not shared by exactly two triangles.
    #[error("the surface is not closed: {open} edges are used by one triangle only")]
    Open {
        /// Number of edges used once.
        open: usize,
    },
}

impl ClosedSurface {
    /// A surface from vertices and triangles (by vertex index; each edge must be shared by
    /// two triangles), kept `inset` away from the spheres. The enclosed volume is
    /// `V = (1/6) Σ a·(b × c)` (divergence theorem); the triangles are reoriented outward if
    /// it is negative. `max_reach` is the largest sphere radius plus inset queried (sets the
    /// grid's cell size).
    pub fn new(
        vertices: &[Vec3],
        triangles: &[[usize; 3]],
        inset: Real,
        max_reach: Real,
    ) -> Result<Self, SurfaceError> {
        let open = open_edges(triangles);
        if open > 0 {
            return Err(SurfaceError::Open { open });
        }
        let mut tris: Vec<[Vec3; 3]> =
            triangles.iter().map(|t| [vertices[t[0]], vertices[t[1]], vertices[t[2]]]).collect();
        let volume = closed_surface_volume(vertices, triangles);
        if !(volume.abs() > 0.0) {
            return Err(SurfaceError::Empty { volume });
        }
        if volume < 0.0 {
            tris.iter_mut().for_each(|t| t.swap(1, 2));
        }
        let normals: Vec<Vec3> = tris
            .iter()
            .map(|[a, b, c]| (b - a).cross(&(c - a)).try_normalize(0.0).unwrap_or_else(Vec3::zeros))
            .collect();
        let area = tris.iter().map(|[a, b, c]| 0.5 * (b - a).cross(&(c - a)).norm()).sum();
        let mut min = Vec3::repeat(Real::INFINITY);
        let mut max = Vec3::repeat(Real::NEG_INFINITY);
        for t in &tris {
            for v in t {
                min = min.inf(v);
                max = max.sup(v);
            }
        }
        let extent = (max - min).max();
        let cell = (2.0 * max_reach).max(extent / 64.0).max(Real::MIN_POSITIVE);
        let dims =
            [0, 1, 2].map(|k| (((max[k] - min[k]) / cell).floor() as usize + 1).min(1 << 10));
        let mut surface = ClosedSurface {
            triangles: tris,
            normals,
            inset,
            volume: volume.abs(),
            area,
            min,
            max,
            cell,
            dims,
            cell_start: Vec::new(),
            cell_triangles: Vec::new(),
        };
        surface.bucket_triangles();
        Ok(surface)
    }

    /// Enclosed volume (m³).
    pub fn enclosed_volume(&self) -> Real {
        self.volume
    }

    fn cell_coords(&self, p: &Vec3) -> [usize; 3] {
        [0, 1, 2].map(|k| {
            (((p[k] - self.min[k]) / self.cell).floor().max(0.0) as usize).min(self.dims[k] - 1)
        })
    }

    fn cell_index(&self, c: [usize; 3]) -> usize {
        c[0] + self.dims[0] * (c[1] + self.dims[1] * c[2])
    }

    /// Lists each triangle in every cell its bounding box touches (counting sort).
    fn bucket_triangles(&mut self) {
        let n_cells = self.dims.iter().product::<usize>();
        let mut lists: Vec<Vec<u32>> = vec![Vec::new(); n_cells];
        for (i, t) in self.triangles.iter().enumerate() {
            let lo = self.cell_coords(&t[0].inf(&t[1]).inf(&t[2]));
            let hi = self.cell_coords(&t[0].sup(&t[1]).sup(&t[2]));
            for z in lo[2]..=hi[2] {
                for y in lo[1]..=hi[1] {
                    for x in lo[0]..=hi[0] {
                        lists[self.cell_index([x, y, z])].push(i as u32);
                    }
                }
            }
        }
        self.cell_start = Vec::with_capacity(n_cells + 1);
        self.cell_start.push(0);
        for l in &lists {
            self.cell_triangles.extend_from_slice(l);
            self.cell_start.push(self.cell_triangles.len() as u32);
        }
    }

    /// Whether `p` is inside: the winding number `Σ Ω_f / 4π` (solid angles of the triangles
    /// seen from `p`, Van Oosterom and Strackee's formula) is near 1.
    pub fn contains(&self, p: &Vec3) -> bool {
        let omega: Real = self
            .triangles
            .iter()
            .map(|[a, b, c]| {
                let (a, b, c) = (a - p, b - p, c - p);
                let (la, lb, lc) = (a.norm(), b.norm(), c.norm());
                let num = a.dot(&b.cross(&c));
                let den = la * lb * lc + a.dot(&b) * lc + a.dot(&c) * lb + b.dot(&c) * la;
                2.0 * num.atan2(den)
            })
            .sum();
        omega / (4.0 * PI) > 0.5
    }

    /// See [`Region::push_inside`].
    fn push_inside(&self, c: &Vec3, r: Real) -> Vec3 {
        let reach = r + self.inset;
        let lo = self.cell_coords(&c.add_scalar(-reach));
        let hi = self.cell_coords(&c.add_scalar(reach));
        let mut closest: Option<(Real, Vec3, usize)> = None;
        for z in lo[2]..=hi[2] {
            for y in lo[1]..=hi[1] {
                for x in lo[0]..=hi[0] {
                    let cell = self.cell_index([x, y, z]);
                    let range = self.cell_start[cell] as usize..self.cell_start[cell + 1] as usize;
                    for &t in &self.cell_triangles[range] {
                        let [a, b, tc] = &self.triangles[t as usize];
                        let q = project_point_triangle(c, a, b, tc).point;
                        let d2 = (c - q).norm_squared();
                        if d2 < reach * reach && closest.is_none_or(|(best, _, _)| d2 < best) {
                            closest = Some((d2, q, t as usize));
                        }
                    }
                }
            }
        }
        let Some((d2, q, t)) = closest else {
            return Vec3::zeros();
        };
        let d = d2.sqrt();
        let normal = self.normals[t];
        // inward direction: from the surface point to the centre when the centre is inside,
        // the inward normal when it sits on the surface
        let inward =
            if d > 1e-12 * reach && (c - q).dot(&normal) < 0.0 { (c - q) / d } else { -normal };
        let depth = if (c - q).dot(&normal) < 0.0 { reach - d } else { reach + d };
        inward * depth
    }
}

/// Number of edges used by exactly one triangle (a closed surface has none).
fn open_edges(triangles: &[[usize; 3]]) -> usize {
    let mut edges: Vec<(usize, usize)> = triangles
        .iter()
        .flat_map(|t| (0..3).map(move |e| (t[e].min(t[(e + 1) % 3]), t[e].max(t[(e + 1) % 3]))))
        .collect();
    edges.sort_unstable();
    let mut open = 0;
    let mut i = 0;
    while i < edges.len() {
        let mut j = i + 1;
        while j < edges.len() && edges[j] == edges[i] {
            j += 1;
        }
        open += usize::from(j - i == 1);
        i = j;
    }
    open
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cube(side: Real) -> (Vec<Vec3>, Vec<[usize; 3]>) {
        let v: Vec<Vec3> = (0..8)
            .map(|i| {
                Vec3::new((i & 1) as Real, ((i >> 1) & 1) as Real, ((i >> 2) & 1) as Real) * side
            })
            .collect();
        // outward-oriented faces, two triangles each
        let quads =
            [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]];
        let t = quads.iter().flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]]).collect();
        (v, t)
    }

    #[test]
    fn a_cube_encloses_its_volume_and_contains_its_centre() {
        let (v, t) = cube(2.0);
        let s = ClosedSurface::new(&v, &t, 0.0, 0.1).unwrap();
        assert!((s.enclosed_volume() - 8.0).abs() < 1e-12);
        assert!(s.contains(&Vec3::new(1.0, 1.0, 1.0)));
        assert!(s.contains(&Vec3::new(0.1, 1.9, 0.2)));
        assert!(!s.contains(&Vec3::new(2.1, 1.0, 1.0)));
        assert!(!s.contains(&Vec3::new(-5.0, 0.0, 0.0)));
        // reversed orientation: same volume, same inside
        let rev: Vec<[usize; 3]> = t.iter().map(|&[a, b, c]| [a, c, b]).collect();
        let s = ClosedSurface::new(&v, &rev, 0.0, 0.1).unwrap();
        assert!((s.enclosed_volume() - 8.0).abs() < 1e-12);
        let region = Region::Surface(s);
        assert_eq!(region.push_inside(&Vec3::new(1.0, 1.0, 1.0), 0.5), Vec3::zeros());
        // a sphere poking through the face x = 2 is pushed back by its overlap
        let push = region.push_inside(&Vec3::new(1.8, 1.0, 1.0), 0.5);
        assert!((push - Vec3::new(-0.3, 0.0, 0.0)).norm() < 1e-12, "{push:?}");
    }

    #[test]
    fn an_open_surface_is_refused() {
        let (v, mut t) = cube(1.0);
        t.pop();
        assert_eq!(
            ClosedSurface::new(&v, &t, 0.0, 0.1).unwrap_err(),
            SurfaceError::Open { open: 3 }
        );
    }

    #[test]
    fn box_and_cylinder_push_spheres_inside() {
        let b = Region::Box { min: Vec3::zeros(), max: Vec3::new(1.0, 2.0, 3.0) };
        let p = b.push_inside(&Vec3::new(0.05, 1.0, 2.99), 0.1);
        assert!((p - Vec3::new(0.05, 0.0, -0.09)).norm() < 1e-15, "{p:?}");
        assert!((b.volume() - 6.0).abs() < 1e-15);
        let c = Region::Cylinder { base: Vec3::zeros(), axis: Vec3::z(), radius: 1.0, height: 2.0 };
        let p = c.push_inside(&Vec3::new(2.0, 0.0, 1.0), 0.5);
        assert!((p - Vec3::new(-1.5, 0.0, 0.0)).norm() < 1e-15);
        assert!(c.holds(&Vec3::new(0.4, 0.0, 1.0), 0.5, 0.0));
        assert!((c.volume() - 2.0 * PI).abs() < 1e-14);
        let (lo, hi) = c.bounds();
        assert!((lo - Vec3::new(-1.0, -1.0, 0.0)).norm() < 1e-15);
        assert!((hi - Vec3::new(1.0, 1.0, 2.0)).norm() < 1e-15);
    }

    #[test]
    fn cylinder_samples_fall_inside() {
        let axis = Vec3::new(1.0, 1.0, 0.0).normalize();
        let c = Region::Cylinder { base: Vec3::new(1.0, 0.0, 0.0), axis, radius: 0.3, height: 1.0 };
        for i in 0..50 {
            let u = [(i as Real * 0.37) % 1.0, (i as Real * 0.61) % 1.0, (i as Real * 0.13) % 1.0];
            let p = c.sample(u).unwrap();
            assert!(c.holds(&p, 0.0, 1e-12), "{p:?}");
        }
    }
}
