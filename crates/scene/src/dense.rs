//! Dense random packings: polydisperse spheres filling a region to a chosen solid fraction
//! (0.60 and above), by collective rearrangement with growth.
//!
//! The radii are drawn uniform in `[r_min, r_max]` and scaled so that the spheres' volume is
//! exactly `φ·V` (φ the solid fraction asked for, V the region's volume). The centres are drawn
//! uniform in the region, overlapping, and moved to minimise the overlap energy
//! `E = ½ Σ_pairs δ_ij² + ½ Σ_i b_i²` (δ_ij = r_i + r_j − |x_j − x_i|, b_i how far sphere i
//! pokes out of the region; unit stiffness) by FIRE, the damped dynamics of jamming studies
//! (O'Hern et al., Phys. Rev. E 68, 011306, 2003, make packings this way). Below the jamming
//! fraction E can reach 0; the packing ends when the largest overlap is below
//! `tolerance × r_min`. There is no friction and no gravity, so the packing is isotropic and
//! has no fabric from a deposition direction; the residual overlaps are elastic energy the
//! first steps of a run give back.
//!
//! In a container the wall layer is looser than the bulk: 5 000 spheres in a cylinder of
//! height twice its diameter (about 14 diameters across) reach 0.60 in a few seconds (radius
//! ratio 1 to 2) and jam before 0.62; compaction under the confining stress of a run takes a
//! sample further.
//!
//! Everything is sequential and depends only on the inputs and the seed.

use crate::packing::{PackingError, SplitMix64, MAX_PACKED_SPHERES};
use crate::region::Region;
use flexdem_geom::{Real, Vec3};
use std::f64::consts::PI;

/// What a dense packing is asked for.
#[derive(Clone, Debug)]
pub struct DensePacking {
    /// The region filled.
    pub region: Region,
    /// Smallest and largest radius before scaling (their ratio is kept) (m).
    pub radius_range: (Real, Real),
    /// Number of spheres; `None`: as many as the radii given fill `φ·V` (then the radii are
    /// only scaled to round the count).
    pub count: Option<usize>,
    /// Solid fraction φ (0, 0.7].
    pub solid_fraction: Real,
    /// Seed of the random draws.
    pub seed: u64,
    /// Largest overlap left, as a fraction of the smallest radius.
    pub tolerance: Real,
    /// Minimisation iterations before giving up.
    pub max_iterations: usize,
}

/// A packing made: the spheres, and how tight it is.
#[derive(Clone, Debug)]
pub struct PackingResult {
    /// Centres and radii.
    pub spheres: Vec<(Vec3, Real)>,
    /// Largest overlap between two spheres or with the region's boundary, divided by the
    /// smallest radius.
    pub largest_overlap: Real,
    /// Minimisation iterations done.
    pub iterations: usize,
}

/// Fills the region (see the module's doc for the method).
pub fn dense_packing(spec: &DensePacking) -> Result<PackingResult, PackingError> {
    let (r_lo, r_hi) = spec.radius_range;
    let bad = |what, value, expected| Err(PackingError::BadParameter { what, value, expected });
    if !(r_lo.is_finite() && r_lo > 0.0) {
        return bad("smallest radius", r_lo, "a finite length > 0 (m)");
    }
    if !(r_hi.is_finite() && r_hi >= r_lo) {
        return bad("largest radius", r_hi, "a finite radius >= the smallest radius");
    }
    if !(spec.solid_fraction > 0.0 && spec.solid_fraction <= 0.7) {
        return bad(
            "solid fraction",
            spec.solid_fraction,
            "a fraction in (0, 0.7]: random packings of spheres jam near 0.64 (more when \
             polydisperse)",
        );
    }
    if !(spec.tolerance.is_finite() && spec.tolerance > 0.0) {
        return bad("overlap tolerance", spec.tolerance, "a fraction > 0 of the smallest radius");
    }
    let volume = spec.region.volume();
    if !(volume.is_finite() && volume > 0.0) {
        return bad("region volume", volume, "a finite volume > 0 (m³)");
    }
    let target = spec.solid_fraction * volume;
    let mut rng = SplitMix64(spec.seed);
    let mut radii = draw_radii(spec, target, &mut rng)?;
    let r_max = radii.iter().copied().fold(0.0, Real::max);
    let r_min = radii.iter().copied().fold(Real::INFINITY, Real::min);
    let (lo, hi) = spec.region.bounds();
    if (0..3).any(|k| hi[k] - lo[k] < 2.0 * r_max) {
        return Err(PackingError::BoxTooSmall { diameter: 2.0 * r_max });
    }
    // large spheres first: they are the hardest to place, and the order fixes the result
    radii.sort_by(|a, b| b.total_cmp(a));
    let mut centres = initial_centres(&spec.region, radii.len(), &mut rng)?;
    let mut relax = Relaxation::new(lo, hi, radii.len());
    let limit = spec.tolerance * r_min;
    let (largest, iterations) =
        relax.minimise(&spec.region, &mut centres, &radii, limit, spec.max_iterations);
    if largest > limit {
        return Err(PackingError::Jammed {
            fraction: spec.solid_fraction,
            overlap: largest / r_min,
            iterations,
        });
    }
    Ok(PackingResult {
        spheres: centres.into_iter().zip(radii).collect(),
        largest_overlap: largest / r_min,
        iterations,
    })
}

/// Radii uniform in the range, scaled (ratio kept) so that their volume is `target`.
fn draw_radii(
    spec: &DensePacking,
    target: Real,
    rng: &mut SplitMix64,
) -> Result<Vec<Real>, PackingError> {
    let (a, b) = spec.radius_range;
    let count = match spec.count {
        Some(n) => n,
        None => {
            // E[r³] for r uniform in [a, b]: (b⁴ − a⁴) / (4 (b − a)), or a³ when a = b
            let mean_cube =
                if b > a { (b.powi(4) - a.powi(4)) / (4.0 * (b - a)) } else { a.powi(3) };
            let n = (target / (4.0 / 3.0 * PI * mean_cube)).round();
            if n > MAX_PACKED_SPHERES as Real {
                return Err(PackingError::TooMany { count: n as usize });
            }
            n.max(1.0) as usize
        }
    };
    if count == 0 {
        return Err(PackingError::BadParameter {
            what: "count",
            value: 0.0,
            expected: "at least 1 sphere",
        });
    }
    if count > MAX_PACKED_SPHERES {
        return Err(PackingError::TooMany { count });
    }
    let mut radii: Vec<Real> = (0..count).map(|_| a + (b - a) * rng.unit()).collect();
    let solid: Real = radii.iter().map(|r| 4.0 / 3.0 * PI * r.powi(3)).sum();
    let scale = (target / solid).cbrt();
    radii.iter_mut().for_each(|r| *r *= scale);
    if let Some(&bad) = radii.iter().find(|r| !(r.is_finite() && **r > 0.0)) {
        return Err(PackingError::BadParameter {
            what: "scaled radius",
            value: bad,
            expected: "a finite radius > 0: the radius range is too small or too large to \
                       compute with (its cube under- or overflows)",
        });
    }
    Ok(radii)
}

/// Centres drawn uniformly in the region (rejection for a surface, up to 1000 tries each).
fn initial_centres(
    region: &Region,
    count: usize,
    rng: &mut SplitMix64,
) -> Result<Vec<Vec3>, PackingError> {
    let mut centres = Vec::with_capacity(count);
    let mut tries = 0usize;
    while centres.len() < count {
        if tries >= 1000usize.saturating_mul(count.max(1)) {
            return Err(PackingError::BadParameter {
                what: "region volume",
                value: region.volume(),
                expected: "a region that random points fall into (is the surface closed?)",
            });
        }
        tries += 1;
        if let Some(p) = region.sample([rng.unit(), rng.unit(), rng.unit()]) {
            centres.push(p);
        }
    }
    Ok(centres)
}

/// The relaxation's scratch: a grid of cells over the region and the moves of a sweep.
struct Relaxation {
    lo: Vec3,
    hi: Vec3,
    moves: Vec<Vec3>,
    cell_start: Vec<u32>,
    order: Vec<u32>,
    cell_of: Vec<u32>,
}

impl Relaxation {
    fn new(lo: Vec3, hi: Vec3, count: usize) -> Self {
        Relaxation {
            lo,
            hi,
            moves: vec![Vec3::zeros(); count],
            cell_start: Vec::new(),
            order: Vec::new(),
            cell_of: vec![0; count],
        }
    }

    /// The overlap "forces" at the current positions: on each sphere the sum of its overlaps
    /// `Σ_j δ_ij n_ji` (the gradient of `½ Σ δ_ij²`, unit stiffness) plus the displacement
    /// that would put it back inside the region (a boundary spring). Returns the largest
    /// overlap, pair or boundary.
    fn forces(&mut self, region: &Region, centres: &[Vec3], radii: &[Real]) -> Real {
        let r_max = radii.iter().copied().fold(0.0, Real::max);
        // cells of one diameter, but never more than about 4 per sphere (a grid of tiny
        // spheres in a large region would not fit in memory)
        let extent = self.hi - self.lo;
        let per_cell = (extent.x * extent.y * extent.z / (4.0 * radii.len() as Real)).cbrt();
        let cell = (2.0 * r_max).max(per_cell);
        let dims =
            [0, 1, 2].map(|k| ((self.hi[k] - self.lo[k]) / cell).floor().max(0.0) as usize + 1);
        self.bucket(centres, cell, dims);
        let mut largest: Real = 0.0;
        for ((f, c), r) in self.moves.iter_mut().zip(centres).zip(radii) {
            *f = region.push_inside(c, *r);
            largest = largest.max(f.norm());
        }
        let index = |x: usize, y: usize, z: usize| x + dims[0] * (y + dims[1] * z);
        for i in 0..centres.len() {
            let c = self.cell_of[i] as usize;
            let (cx, cy, cz) = (c % dims[0], (c / dims[0]) % dims[1], c / (dims[0] * dims[1]));
            for z in cz.saturating_sub(1)..(cz + 2).min(dims[2]) {
                for y in cy.saturating_sub(1)..(cy + 2).min(dims[1]) {
                    for x in cx.saturating_sub(1)..(cx + 2).min(dims[0]) {
                        let cell = index(x, y, z);
                        let range =
                            self.cell_start[cell] as usize..self.cell_start[cell + 1] as usize;
                        for &j in &self.order[range] {
                            let j = j as usize;
                            if j <= i {
                                continue;
                            }
                            let d = centres[j] - centres[i];
                            let reach = radii[i] + radii[j];
                            let dist2 = d.norm_squared();
                            if dist2 >= reach * reach {
                                continue;
                            }
                            let dist = dist2.sqrt();
                            let overlap = reach - dist;
                            largest = largest.max(overlap);
                            let n = if dist > 1e-12 * reach {
                                d / dist
                            } else {
                                // coincident centres: a direction fixed by the pair
                                unit_direction(i, j)
                            };
                            self.moves[i] -= n * overlap;
                            self.moves[j] += n * overlap;
                        }
                    }
                }
            }
        }
        largest
    }

    /// Minimises `½ Σ δ²` (pairs and boundary) by FIRE (Bitzek et al., Phys. Rev. Lett. 97,
    /// 170201, 2006: damped dynamics with unit masses whose velocity is turned toward the
    /// force and reset when the power turns negative) until the largest overlap is at most
    /// `limit`, or `max_iterations`. Returns the largest overlap at the positions returned and
    /// the iterations done.
    fn minimise(
        &mut self,
        region: &Region,
        centres: &mut [Vec3],
        radii: &[Real],
        limit: Real,
        max_iterations: usize,
    ) -> (Real, usize) {
        const DT_START: Real = 0.1;
        const DT_MAX: Real = 0.5;
        const ALPHA_START: Real = 0.1;
        let mut v = vec![Vec3::zeros(); centres.len()];
        let (mut dt, mut alpha, mut positive) = (DT_START, ALPHA_START, 0usize);
        for iteration in 0..max_iterations {
            let largest = self.forces(region, centres, radii);
            if largest <= limit {
                return (largest, iteration);
            }
            let power: Real = v.iter().zip(&self.moves).map(|(v, f)| v.dot(f)).sum();
            if power > 0.0 {
                let v_norm = v.iter().map(|v| v.norm_squared()).sum::<Real>().sqrt();
                let f_norm = self.moves.iter().map(|f| f.norm_squared()).sum::<Real>().sqrt();
                let turn = if f_norm > 0.0 { alpha * v_norm / f_norm } else { 0.0 };
                for (v, f) in v.iter_mut().zip(&self.moves) {
                    *v = *v * (1.0 - alpha) + f * turn;
                }
                positive += 1;
                if positive > 5 {
                    dt = (dt * 1.1).min(DT_MAX);
                    alpha *= 0.99;
                }
            } else {
                v.iter_mut().for_each(|v| *v = Vec3::zeros());
                dt *= 0.5;
                alpha = ALPHA_START;
                positive = 0;
            }
            for (((c, v), f), r) in centres.iter_mut().zip(v.iter_mut()).zip(&self.moves).zip(radii)
            {
                *v += f * dt;
                let step = *v * dt;
                let limit = region.largest_step(*r);
                let length = step.norm();
                *c += if length > limit { step * (limit / length) } else { step };
            }
        }
        (self.forces(region, centres, radii), max_iterations)
    }

    /// Sorts the spheres by cell (counting sort).
    fn bucket(&mut self, centres: &[Vec3], cell: Real, dims: [usize; 3]) {
        let n_cells = dims.iter().product::<usize>();
        self.cell_start.clear();
        self.cell_start.resize(n_cells + 1, 0);
        for (i, c) in centres.iter().enumerate() {
            let k = [0, 1, 2]
                .map(|a| (((c[a] - self.lo[a]) / cell).floor().max(0.0) as usize).min(dims[a] - 1));
            let idx = k[0] + dims[0] * (k[1] + dims[1] * k[2]);
            self.cell_of[i] = idx as u32;
            self.cell_start[idx + 1] += 1;
        }
        for k in 0..n_cells {
            self.cell_start[k + 1] += self.cell_start[k];
        }
        self.order.clear();
        self.order.resize(centres.len(), 0);
        let mut fill = self.cell_start.clone();
        for (i, &c) in self.cell_of.iter().enumerate() {
            self.order[fill[c as usize] as usize] = i as u32;
            fill[c as usize] += 1;
        }
    }
}

/// A unit direction that depends only on the pair (for spheres at the same centre).
fn unit_direction(i: usize, j: usize) -> Vec3 {
    let mut rng = SplitMix64((i as u64) << 32 | j as u64);
    let z = 2.0 * rng.unit() - 1.0;
    let phi = 2.0 * PI * rng.unit();
    let s = (1.0 - z * z).sqrt();
    Vec3::new(s * phi.cos(), s * phi.sin(), z)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::region::ClosedSurface;

    /// Checks the packing: every sphere inside, overlaps within the tolerance, the solid
    /// fraction as asked, radii in the scaled range.
    fn check(spec: &DensePacking, result: &PackingResult) {
        let s = &result.spheres;
        let r_min = s.iter().map(|x| x.1).fold(Real::INFINITY, Real::min);
        let limit = spec.tolerance * r_min * (1.0 + 1e-9);
        for (i, (c, r)) in s.iter().enumerate() {
            assert!(spec.region.holds(c, *r, 1.01 * limit), "sphere {i} outside");
            for (c2, r2) in &s[i + 1..] {
                let overlap = r + r2 - (c2 - c).norm();
                assert!(overlap <= 1.01 * limit, "overlap {overlap:e} > {limit:e}");
            }
        }
        let solid: Real = s.iter().map(|(_, r)| 4.0 / 3.0 * PI * r.powi(3)).sum();
        let phi = solid / spec.region.volume();
        assert!((phi - spec.solid_fraction).abs() < 1e-9, "phi = {phi}");
        let r_max = s.iter().map(|x| x.1).fold(0.0, Real::max);
        let (a, b) = spec.radius_range;
        assert!(r_max / r_min <= b / a * (1.0 + 1e-12));
    }

    fn cylinder_spec(count: usize, fraction: Real) -> DensePacking {
        DensePacking {
            region: Region::Cylinder {
                base: Vec3::zeros(),
                axis: Vec3::z(),
                radius: 0.05,
                height: 0.1,
            },
            radius_range: (1.0, 1.5),
            count: Some(count),
            solid_fraction: fraction,
            seed: 7,
            tolerance: 1e-3,
            max_iterations: 20_000,
        }
    }

    #[test]
    fn a_triaxial_sample_is_filled_to_sixty_percent_without_overlap() {
        // 5 000 spheres, radius ratio 2, height twice the diameter: the sample of the triaxial
        // example, about 14 mean diameters across
        let spec = DensePacking { radius_range: (1.0, 2.0), ..cylinder_spec(5000, 0.60) };
        let spec = DensePacking {
            region: Region::Cylinder {
                base: Vec3::zeros(),
                axis: Vec3::z(),
                radius: 0.05,
                height: 0.2,
            },
            ..spec
        };
        let result = dense_packing(&spec).unwrap();
        assert_eq!(result.spheres.len(), 5000);
        check(&spec, &result);
    }

    #[test]
    fn a_box_is_filled_to_the_count_its_radii_give() {
        let spec = DensePacking {
            region: Region::Box { min: Vec3::zeros(), max: Vec3::new(1.0, 1.0, 1.0) },
            radius_range: (0.025, 0.05),
            count: None,
            solid_fraction: 0.6,
            seed: 3,
            tolerance: 1e-3,
            max_iterations: 20_000,
        };
        let result = dense_packing(&spec).unwrap();
        // E[r³] = (b⁴ − a⁴)/(4(b − a)) = 5.859e-5 m³ → 0.6 m³ / (4/3 π 5.859e-5) = 2444.7
        assert_eq!(result.spheres.len(), 2445);
        check(&spec, &result);
    }

    #[test]
    fn the_inside_of_a_closed_surface_is_filled_away_from_it() {
        // an octahedron of half-diagonal 1: volume 4/3
        let v = [Vec3::x(), -Vec3::x(), Vec3::y(), -Vec3::y(), Vec3::z(), -Vec3::z()];
        let t = [
            [0, 2, 4],
            [2, 1, 4],
            [1, 3, 4],
            [3, 0, 4],
            [2, 0, 5],
            [1, 2, 5],
            [3, 1, 5],
            [0, 3, 5],
        ];
        let surface = ClosedSurface::new(&v, &t, 0.01, 0.1).unwrap();
        assert!((surface.enclosed_volume() - 4.0 / 3.0).abs() < 1e-14);
        let spec = DensePacking {
            region: Region::Surface(surface),
            radius_range: (0.04, 0.08),
            count: Some(300),
            solid_fraction: 0.45,
            seed: 11,
            tolerance: 1e-3,
            max_iterations: 20_000,
        };
        let result = dense_packing(&spec).unwrap();
        check(&spec, &result);
    }

    #[test]
    fn the_same_seed_gives_the_same_packing_and_another_seed_another() {
        let spec = cylinder_spec(100, 0.5);
        let a = dense_packing(&spec).unwrap().spheres;
        let b = dense_packing(&spec).unwrap().spheres;
        assert_eq!(a, b);
        let c = dense_packing(&DensePacking { seed: 8, ..spec }).unwrap().spheres;
        assert_ne!(a, c);
    }

    #[test]
    fn impossible_fractions_are_refused() {
        let spec = cylinder_spec(100, 0.75);
        assert!(matches!(dense_packing(&spec), Err(PackingError::BadParameter { .. })));
        let spec = DensePacking { max_iterations: 10, ..cylinder_spec(200, 0.69) };
        assert!(matches!(dense_packing(&spec), Err(PackingError::Jammed { .. })));
    }
}
