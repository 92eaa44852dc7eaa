//! What a geotechnical user measures on a sample (model.md §5): the normal stress on a wall,
//! the Love–Weber average stress tensor of the spheres in a region with its mean stress and
//! deviator, and the solid fraction of a region. Pure functions of the model and the
//! contacts of the last step; stresses are compression positive.

use crate::contact::Contact;
use crate::region::Region;
use flexdem_elements::virtual_sphere::{Feature, Site};
use flexdem_elements::{Model, ParticleKind, Particles, Wall};
use flexdem_geom::{Real, Vec3};
use nalgebra::Matrix3;
use std::f64::consts::PI;

/// The normal force `F_n = −F·n` (N, ≥ 0 in compression) of the force `force` the bodies put
/// on `wall`.
pub fn normal_force(wall: &Wall, force: &Vec3) -> Real {
    -force.dot(&wall.normal)
}

/// The normal stress on `wall` (Pa, compression positive) of the force `force` the bodies put
/// on it, over the area `area` (m²): `−F·n / A`.
pub fn wall_normal_stress(wall: &Wall, force: &Vec3, area: Real) -> Real {
    normal_force(wall, force) / area
}

/// Distance between the planes of two facing walls, `(x_b − x_a)·n_a` (m), or why there is
/// none.
pub fn wall_gap(model: &Model, a: u32, b: u32) -> Result<Real, String> {
    let wall = |w: u32| {
        model
            .walls
            .get(w as usize)
            .ok_or_else(|| format!("wall {w} does not exist (the model has {})", model.walls.len()))
    };
    let (wa, wb) = (wall(a)?, wall(b)?);
    Ok((wb.point - wa.point).dot(&wa.normal))
}

/// The volume of a membrane sample (m³): the volume enclosed by the PFacets of `structure`
/// closed by the planes of the walls `platens` (`flexdem_elements::structure_volume`), less
/// `Σ r_f·A_f` over its PFacets (radius times area: the half thickness between the
/// mid-surface and the grains, to first order in radius/curvature radius).
pub fn membrane_sample_volume(
    model: &Model,
    structure: u32,
    platens: [u32; 2],
) -> Result<Real, String> {
    let planes = platens
        .iter()
        .map(|&w| {
            model.walls.get(w as usize).map(|wall| wall.plane()).ok_or_else(|| {
                format!("wall {w} does not exist (the model has {})", model.walls.len())
            })
        })
        .collect::<Result<Vec<_>, _>>()?;
    let mid =
        flexdem_elements::structure_volume(model, structure, &planes).map_err(|e| e.to_string())?;
    let st = &model.structures[structure as usize];
    let pos = &model.particles.pos;
    let half_thickness: Real = model.pfacets[st.pfacets.start as usize..st.pfacets.end as usize]
        .iter()
        .map(|f| {
            let [a, b, c] = f.nodes.map(|n| pos[n as usize]);
            f.radius * 0.5 * (b - a).cross(&(c - a)).norm()
        })
        .sum();
    Ok(mid.abs() - half_thickness)
}

/// The free sphere a contact site is on, if it is on one.
fn sphere_of(site: &Site, p: &Particles) -> Option<usize> {
    match site.feature {
        Feature::Particle(i) if p.kind[i as usize] == ParticleKind::Sphere => Some(i as usize),
        _ => None,
    }
}

/// The Love–Weber average stress tensor of the free spheres whose centres are in `region`
/// (Pa, **compression positive**), from the contacts of the last step:
///
/// `σ_ij = −(1/V) Σ_p Σ_{c ∋ p} (x_c − x_p)_i f_j^c`
///
/// over the spheres `p` in the region and every contact `c` of `p` (with other spheres,
/// walls, structures): `x_c` the contact point, `x_p` the sphere's centre, `f^c` the force
/// of the contact on `p`. `V` is `volume` (m³, > 0), by default the region's volume. The
/// minus sign makes compression positive (a contact pushing on `p` points against
/// `x_c − x_p`). Between two spheres both in the region the two terms add up to the classic
/// branch-vector form `(x_2 − x_1)_i f_j`. The tensor is the full one: its antisymmetric part
/// is the sum of the contact moments on the spheres, zero at rest. Not counted: the inertia
/// of the spheres (a dynamic correction, nil at rest) and body forces (gravity). The contact
/// points are those of the last contact update, the centres those after the step's move: a
/// lag of `|v|·dt` in each branch, negligible in a quasi-static test.
pub fn love_weber_stress(
    model: &Model,
    contacts: &[Contact],
    region: &Region,
    volume: Option<Real>,
) -> Matrix3<Real> {
    let p = &model.particles;
    let mut sum = Matrix3::zeros();
    for c in contacts {
        for (site, sign) in [(&c.site1, -1.0), (&c.site2, 1.0)] {
            let Some(i) = sphere_of(site, p) else { continue };
            if !region.contains(&p.pos[i]) {
                continue;
            }
            let force = c.forces.force_on_2 * sign;
            sum += (c.point - p.pos[i]) * force.transpose();
        }
    }
    -sum / volume.unwrap_or_else(|| region.volume())
}

/// The mean stress `p = tr(σ)/3` (Pa).
pub fn mean_stress(stress: &Matrix3<Real>) -> Real {
    stress.trace() / 3.0
}

/// The deviator stress `q = sqrt(3/2 · s:s)` (Pa), `s = sym(σ) − p·I` the deviator of the
/// symmetric part of `σ`: `q = σ₁ − σ₃` under axisymmetric (triaxial) stress.
pub fn deviator_stress(stress: &Matrix3<Real>) -> Real {
    let sym = (stress + stress.transpose()) * 0.5;
    let s = sym - Matrix3::identity() * mean_stress(stress);
    (1.5 * s.component_mul(&s).sum()).sqrt()
}

/// The solid fraction of `region`: the volume `Σ 4/3·π·r³` of the free spheres whose centres
/// are in it over the region's volume. The centre-counting approximation: a sphere across
/// the boundary counts whole or not at all, an error of the order of the spheres cut by the
/// boundary, about `3·r/L` of the fraction for a region of size `L`.
pub fn solid_fraction(particles: &Particles, region: &Region) -> Real {
    let solid: Real = (0..particles.len())
        .filter(|&i| particles.kind[i] == ParticleKind::Sphere)
        .filter(|&i| region.contains(&particles.pos[i]))
        .map(|i| 4.0 / 3.0 * PI * particles.radius[i].powi(3))
        .sum();
    solid / region.volume()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mean_and_deviator_of_known_tensors() {
        let hydrostatic = Matrix3::identity() * 2e5;
        assert_eq!(mean_stress(&hydrostatic), 2e5);
        assert_eq!(deviator_stress(&hydrostatic), 0.0);
        // triaxial: σ₁ = 3e5 axial, σ₃ = 1e5 lateral: p = 5e5/3, q = σ₁ − σ₃
        let triaxial = Matrix3::from_diagonal(&Vec3::new(1e5, 1e5, 3e5));
        assert!((mean_stress(&triaxial) - 5e5 / 3.0).abs() < 1e-9);
        assert!((deviator_stress(&triaxial) - 2e5).abs() < 1e-9);
        // pure shear τ: q = √3·τ, and the antisymmetric part does not count
        let mut shear = Matrix3::zeros();
        shear[(0, 1)] = 1e4;
        shear[(1, 0)] = 1e4;
        assert!((deviator_stress(&shear) - 3f64.sqrt() * 1e4).abs() < 1e-9);
        shear[(0, 1)] = 3e4;
        shear[(1, 0)] = -1e4;
        assert!((deviator_stress(&shear) - 3f64.sqrt() * 1e4).abs() < 1e-9);
    }
}
