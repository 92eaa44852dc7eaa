//! Free-sphere packings in a box: a simple cubic lattice and a random packing without
//! overlaps (random sequential addition on a cell grid, deterministic for a seed).

use flexdem_geom::{Real, Vec3};
use std::collections::HashMap;

/// Largest number of spheres a packing may produce (memory guard against typos).
pub const MAX_PACKED_SPHERES: usize = 1_000_000;

/// Why a packing could not be made.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum PackingError {
    /// The box is inverted, flat or not finite.
    #[error("the box min {min:?} and max {max:?} must be finite with min < max on every axis")]
    BadBox {
        /// Lower corner.
        min: [Real; 3],
        /// Upper corner.
        max: [Real; 3],
    },
    /// A radius or the spacing is not usable.
    #[error("{what} is {value}: expected {expected}")]
    BadParameter {
        /// The parameter.
        what: &'static str,
        /// Its value.
        value: Real,
        /// What is expected.
        expected: &'static str,
    },
    /// The box cannot hold a single sphere.
    #[error("the box is smaller than one sphere (diameter {diameter}) along some axis")]
    BoxTooSmall {
        /// Largest sphere diameter.
        diameter: Real,
    },
    /// More spheres than [`MAX_PACKED_SPHERES`].
    #[error("{count} spheres requested: at most {MAX_PACKED_SPHERES} are allowed")]
    TooMany {
        /// The number asked for.
        count: usize,
    },
    /// Random sequential addition stalled before placing `requested` spheres.
    #[error(
        "only {placed} of {requested} spheres fit without overlap after {attempts} random tries: \
         use a larger box, fewer or smaller spheres (random packing saturates near 35% of the \
         box volume)"
    )]
    Saturated {
        /// Spheres placed.
        placed: usize,
        /// Spheres asked for.
        requested: usize,
        /// Tries made.
        attempts: usize,
    },
    /// A dense packing still overlaps after its relaxation sweeps.
    #[error(
        "the spheres still overlap by {overlap:.2e} of the smallest radius after {iterations} \
         minimisation iterations at solid fraction {fraction}: ask for a lower solid fraction, a wider \
         radius range or more iterations"
    )]
    Jammed {
        /// The solid fraction asked for.
        fraction: Real,
        /// Largest overlap left, relative to the smallest radius.
        overlap: Real,
        /// Iterations done.
        iterations: usize,
    },
}

fn check_box(min: Vec3, max: Vec3) -> Result<(), PackingError> {
    let ok = (0..3).all(|k| min[k].is_finite() && max[k].is_finite() && min[k] < max[k]);
    if ok {
        Ok(())
    } else {
        Err(PackingError::BadBox { min: min.into(), max: max.into() })
    }
}

fn positive(what: &'static str, value: Real) -> Result<Real, PackingError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(PackingError::BadParameter { what, value, expected: "a finite length > 0 (m)" })
    }
}

/// Centres of a simple cubic lattice of spheres of radius `radius`, spaced `spacing`
/// (≥ 2·radius, so that they do not overlap) from the corner `min + radius`, every sphere
/// wholly inside the box. Ordered x fastest, then y, then z.
pub fn lattice_packing(
    min: Vec3,
    max: Vec3,
    radius: Real,
    spacing: Real,
) -> Result<Vec<Vec3>, PackingError> {
    check_box(min, max)?;
    positive("radius", radius)?;
    if !(spacing.is_finite() && spacing >= 2.0 * radius) {
        return Err(PackingError::BadParameter {
            what: "spacing",
            value: spacing,
            expected: "a finite distance >= 2·radius (m), so that spheres do not overlap",
        });
    }
    let mut n = [0usize; 3];
    for k in 0..3 {
        let free = max[k] - min[k] - 2.0 * radius;
        if free < -1e-12 * (max[k] - min[k]) {
            return Err(PackingError::BoxTooSmall { diameter: 2.0 * radius });
        }
        // A relative slack so that a box of exactly n spacings holds n + 1 spheres.
        let steps = (free.max(0.0) / spacing * (1.0 + 1e-12)).floor();
        if steps >= MAX_PACKED_SPHERES as Real {
            return Err(PackingError::TooMany { count: usize::MAX });
        }
        n[k] = steps as usize + 1;
    }
    let count = n[0].checked_mul(n[1]).and_then(|c| c.checked_mul(n[2])).unwrap_or(usize::MAX);
    if count > MAX_PACKED_SPHERES {
        return Err(PackingError::TooMany { count });
    }
    let first = min.add_scalar(radius);
    let mut centers = Vec::with_capacity(count);
    for k in 0..n[2] {
        for j in 0..n[1] {
            for i in 0..n[0] {
                centers.push(first + Vec3::new(i as Real, j as Real, k as Real) * spacing);
            }
        }
    }
    Ok(centers)
}

/// SplitMix64: a small, fast, well-mixed generator, so that packings are reproducible
/// across platforms and releases.
#[derive(Clone, Debug)]
pub(crate) struct SplitMix64(pub(crate) u64);

impl SplitMix64 {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1).
    pub(crate) fn unit(&mut self) -> Real {
        (self.next_u64() >> 11) as Real / (1u64 << 53) as Real
    }
}

/// `count` spheres with radii uniform in `[r_min, r_max]`, wholly inside the box, none
/// overlapping another, by random sequential addition: each candidate (radius, centre) is
/// drawn at random and kept if it overlaps no sphere kept so far, found through a grid of
/// cells of size 2·r_max (27 cells checked per try, so the cost is linear in the tries). The
/// result depends only on the inputs and `seed`. Gives up with
/// [`PackingError::Saturated`] after `100·count + 10000` tries.
pub fn random_packing(
    min: Vec3,
    max: Vec3,
    r_min: Real,
    r_max: Real,
    count: usize,
    seed: u64,
) -> Result<Vec<(Vec3, Real)>, PackingError> {
    check_box(min, max)?;
    positive("smallest radius", r_min)?;
    positive("largest radius", r_max)?;
    if r_max < r_min {
        return Err(PackingError::BadParameter {
            what: "largest radius",
            value: r_max,
            expected: "a radius >= the smallest radius",
        });
    }
    if count > MAX_PACKED_SPHERES {
        return Err(PackingError::TooMany { count });
    }
    if (0..3).any(|k| max[k] - min[k] < 2.0 * r_max) {
        return Err(PackingError::BoxTooSmall { diameter: 2.0 * r_max });
    }
    // Random sequential addition jams near 38% of the volume: do not even try far above.
    let box_volume = (max - min).iter().product::<Real>();
    let least_volume = count as Real * 4.0 / 3.0 * std::f64::consts::PI * r_min.powi(3);
    if least_volume > 0.6 * box_volume {
        return Err(PackingError::Saturated { placed: 0, requested: count, attempts: 0 });
    }
    let cell = 2.0 * r_max;
    let cell_of = |p: &Vec3| -> [i64; 3] {
        [0, 1, 2].map(|k| ((p[k] - min[k]) / cell).floor().clamp(-1.0, 1e15) as i64)
    };
    let mut grid: HashMap<[i64; 3], Vec<u32>> = HashMap::new();
    let mut spheres: Vec<(Vec3, Real)> = Vec::with_capacity(count);
    let mut rng = SplitMix64(seed);
    let max_attempts = count.saturating_mul(100).saturating_add(10_000);
    let mut attempts = 0;
    while spheres.len() < count {
        if attempts == max_attempts {
            return Err(PackingError::Saturated {
                placed: spheres.len(),
                requested: count,
                attempts,
            });
        }
        attempts += 1;
        let r = r_min + (r_max - r_min) * rng.unit();
        let c = Vec3::from_fn(|k, _| min[k] + r + (max[k] - min[k] - 2.0 * r) * rng.unit());
        let home = cell_of(&c);
        let mut free = true;
        'search: for dz in -1..=1 {
            for dy in -1..=1 {
                for dx in -1..=1 {
                    let key = [home[0] + dx, home[1] + dy, home[2] + dz];
                    for &other in grid.get(&key).map_or(&[][..], |v| v.as_slice()) {
                        let (oc, or) = spheres[other as usize];
                        if (oc - c).norm_squared() < (or + r) * (or + r) {
                            free = false;
                            break 'search;
                        }
                    }
                }
            }
        }
        if free {
            grid.entry(home).or_default().push(spheres.len() as u32);
            spheres.push((c, r));
        }
    }
    Ok(spheres)
}
