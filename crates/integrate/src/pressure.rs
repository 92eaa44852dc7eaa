//! Pressure on PFacets (docs/model.md §6): a follower load that acts on each loaded PFacet's
//! current mid-surface triangle, normal to it, in proportion to its current area.
//!
//! On a PFacet with nodes `(a, b, c)` at `x_a, x_b, x_c`, area `A_f` and unit normal
//! `n̂_f = (x_b − x_a) × (x_c − x_a)/|…|` (the side the builders call outside), a pressure `p`
//! gives the force `p·A_f·n̂_f = (p/2)·(x_b − x_a) × (x_c − x_a)`, shared by the weights of a
//! contact at the triangle's centroid, 1/3 to each node:
//!
//! ```text
//! F_a = F_b = F_c = (p/6)·(x_b − x_a) × (x_c − x_a)
//! ```
//!
//! (no torque: the centroid is the centre of the virtual sphere there). `p > 0` pushes
//! towards the normals' side (out of a builder's closed shell: an internal pressure that
//! inflates it); `flip` pushes the other way.
//!
//! **Conservative on a closed surface.** With `V = Σ_f (1/6)·x_a·(x_b × x_c)` the enclosed
//! volume (`flexdem_geom::closed_surface_volume`), `∂V/∂x_a = Σ_{f ∋ a} (1/6)·x_b × x_c`,
//! while `F_a/p = Σ_{f ∋ a} (1/6)·(x_b × x_c + x_a × (x_b − x_c))`: around a node of a
//! closed, consistently oriented surface the `x_b − x_c` of its PFacets chain around it and
//! sum to zero, so `F_a = p·∂V/∂x_a` exactly: the pressure derives from the potential
//! `−p·V`, its nodal forces sum to zero (`Σ_a ∂V/∂x_a = 0`, a translation keeps `V`) and so
//! do their moments, and its work over any motion is `p·ΔV` at constant `p` (`∫ p dV` under
//! a ramp). On an open surface (a membrane, a tube between platens) it is the same force,
//! but the rest of the enclosure (the platens) carries the rest of the pressure.
//!
//! **Energy.** The nodal forces are added to the imposed loads' forces (`external_force`),
//! so their work goes to `Energy::load_work` (trapezoidal, as every work: model.md §3),
//! and the balance closes with no new term.

use crate::settings::Ramp;
use crate::SimulationError;
use flexdem_elements::{Model, PFacetId};
use flexdem_geom::{Real, Vec3};
use serde::{Deserialize, Serialize};

/// A pressure on a set of PFacets: a follower load normal to each, `p·A_f` on its current
/// area (see the module documentation).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Pressure {
    /// The PFacets loaded.
    pub pfacets: Vec<PFacetId>,
    /// Pressure (Pa): positive pushes each PFacet towards the side its normal
    /// `(x₁ − x₀) × (x₂ − x₀)` points to (out of a builder's closed shell).
    pub pressure: Real,
    /// Push against the normals instead.
    pub flip: bool,
    /// Growth in time (the pressure is `ramp.factor(t)·pressure`).
    pub ramp: Ramp,
}

impl Pressure {
    /// The signed pressure at time `t` (Pa), positive along the normals: `±ramp(t)·p`.
    pub fn at(&self, t: Real) -> Real {
        let sign = if self.flip { -1.0 } else { 1.0 };
        sign * self.ramp.factor(t) * self.pressure
    }
}

/// The force a pressure `p` puts on each node of the triangle `(a, b, c)`: a third of
/// `p·A·n̂`, that is `(p/6)·(b − a) × (c − a)`.
pub fn pressure_node_force(p: Real, a: &Vec3, b: &Vec3, c: &Vec3) -> Vec3 {
    (b - a).cross(&(c - a)) * (p / 6.0)
}

/// Adds the nodal forces of `pressure` at time `t` to `force` (indexed by particle), from
/// the current node positions of `model`. The PFacet ids must exist ([`check_pressure`]).
pub fn add_pressure_forces(pressure: &Pressure, model: &Model, t: Real, force: &mut [Vec3]) {
    let p = pressure.at(t);
    if p == 0.0 {
        return;
    }
    let pos = &model.particles.pos;
    for &f in &pressure.pfacets {
        let nodes = model.pfacets[f as usize].nodes;
        let [a, b, c] = nodes.map(|n| pos[n as usize]);
        let share = pressure_node_force(p, &a, &b, &c);
        for n in nodes {
            force[n as usize] += share;
        }
    }
}

/// Checks a pressure against a model of `n_pfacets` PFacets: at least one PFacet, ids in
/// range, a finite pressure, a finite ramp of non-negative duration.
pub(crate) fn check_pressure(pressure: &Pressure, n_pfacets: usize) -> Result<(), SimulationError> {
    let bad = |what: &str, value: String, expected: String| {
        Err(SimulationError::Setting { what: what.into(), value, expected })
    };
    if pressure.pfacets.is_empty() {
        return bad("pressure PFacets", "an empty list".into(), "at least one PFacet id".into());
    }
    if let Some(&f) = pressure.pfacets.iter().find(|&&f| f as usize >= n_pfacets) {
        return bad(
            "pressure PFacet",
            f.to_string(),
            format!("a PFacet id below {n_pfacets} (the model has {n_pfacets} PFacets)"),
        );
    }
    if !pressure.pressure.is_finite() {
        return bad("pressure", pressure.pressure.to_string(), "a finite number (Pa)".into());
    }
    if let Ramp::Linear { start, duration } = pressure.ramp {
        if !(start.is_finite() && duration.is_finite() && duration >= 0.0) {
            return bad(
                "pressure ramp",
                format!("start {start}, duration {duration}"),
                "a finite start time and a finite, non-negative duration (s)".into(),
            );
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn node_force_is_a_third_of_pressure_times_area_along_the_normal() {
        let (a, b, c) =
            (Vec3::new(1.0, 1.0, 2.0), Vec3::new(3.0, 1.0, 2.0), Vec3::new(1.0, 4.0, 2.0));
        // area 3, normal +z
        let f = pressure_node_force(600.0, &a, &b, &c);
        assert!((f - Vec3::new(0.0, 0.0, 600.0)).norm() < 1e-12);
    }

    #[test]
    fn flip_and_ramp_scale_the_pressure() {
        let mut p = Pressure {
            pfacets: vec![0],
            pressure: 1e5,
            flip: false,
            ramp: Ramp::Linear { start: 1.0, duration: 2.0 },
        };
        assert_eq!(p.at(0.5), 0.0);
        assert!((p.at(2.0) - 0.5e5).abs() < 1e-9);
        p.flip = true;
        assert_eq!(p.at(5.0), -1e5);
    }

    #[test]
    fn bad_pressures_are_refused() {
        let good =
            Pressure { pfacets: vec![0, 2], pressure: 1.0, flip: false, ramp: Ramp::Constant };
        assert!(check_pressure(&good, 3).is_ok());
        let err = check_pressure(&good, 2).unwrap_err().to_string();
        assert!(err.contains("pressure PFacet") && err.contains("below 2"), "{err}");
        let nan = Pressure { pressure: Real::NAN, ..good.clone() };
        assert!(check_pressure(&nan, 3).unwrap_err().to_string().contains("finite number"));
        let empty = Pressure { pfacets: vec![], ..good.clone() };
        assert!(check_pressure(&empty, 3).is_err());
        let ramp = Pressure { ramp: Ramp::Linear { start: 0.0, duration: -1.0 }, ..good };
        assert!(check_pressure(&ramp, 3).unwrap_err().to_string().contains("pressure ramp"));
    }
}
