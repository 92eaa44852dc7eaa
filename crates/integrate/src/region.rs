//! Regions of space the measures of a sample are taken over (`measures.rs`): a box or a
//! cylinder.

use crate::SimulationError;
use flexdem_geom::{Real, Vec3};
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// A region of space: a particle is in it when its centre is (boundary included).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum Region {
    /// An axis-aligned box.
    Box {
        /// Lowest corner (m).
        min: Vec3,
        /// Highest corner (m).
        max: Vec3,
    },
    /// A solid cylinder, as the scene's `tube` is placed.
    Cylinder {
        /// Centre of its first disc (m).
        start: Vec3,
        /// Direction of its axis, from the first disc to the second (any length > 0).
        axis: Vec3,
        /// Radius (m).
        radius: Real,
        /// Length along the axis (m).
        length: Real,
    },
}

impl Region {
    /// Checks the numbers: finite, a box with `min < max` on every axis, a cylinder with an
    /// axis of length > 0 and a radius and a length > 0.
    pub fn validate(&self) -> Result<(), SimulationError> {
        let finite = |v: &Vec3| v.iter().all(|x| x.is_finite());
        let ok = match self {
            Region::Box { min, max } => {
                finite(min) && finite(max) && (0..3).all(|k| min[k] < max[k])
            }
            Region::Cylinder { start, axis, radius, length } => {
                finite(start)
                    && finite(axis)
                    && axis.norm() > 0.0
                    && axis.norm().is_finite()
                    && *radius > 0.0
                    && radius.is_finite()
                    && *length > 0.0
                    && length.is_finite()
            }
        };
        if ok {
            return Ok(());
        }
        Err(SimulationError::Setting {
            what: "region".into(),
            value: format!("{self:?}"),
            expected: "a box with min < max on every axis, or a cylinder with an axis ≠ 0, a \
                       radius and a length > 0 (finite numbers)"
                .into(),
        })
    }

    /// Whether point `x` is in the region (boundary included).
    pub fn contains(&self, x: &Vec3) -> bool {
        match self {
            Region::Box { min, max } => (0..3).all(|k| min[k] <= x[k] && x[k] <= max[k]),
            Region::Cylinder { start, axis, radius, length } => {
                let a = axis.normalize();
                let d = x - start;
                let along = d.dot(&a);
                let across = (d - a * along).norm_squared();
                (0.0..=*length).contains(&along) && across <= radius * radius
            }
        }
    }

    /// Volume (m³): `Π (max − min)` of a box, `π·r²·L` of a cylinder.
    pub fn volume(&self) -> Real {
        match self {
            Region::Box { min, max } => (max - min).iter().product(),
            Region::Cylinder { radius, length, .. } => PI * radius * radius * length,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn boxes_and_cylinders_hold_what_they_should() {
        let b = Region::Box { min: Vec3::zeros(), max: Vec3::new(1.0, 2.0, 3.0) };
        assert!(b.validate().is_ok());
        assert_eq!(b.volume(), 6.0);
        assert!(b.contains(&Vec3::new(1.0, 0.0, 3.0)));
        assert!(!b.contains(&Vec3::new(1.0, -1e-12, 3.0)));
        let c = Region::Cylinder {
            start: Vec3::new(1.0, 1.0, 0.0),
            axis: Vec3::new(0.0, 0.0, 2.0),
            radius: 0.5,
            length: 2.0,
        };
        assert!(c.validate().is_ok());
        assert!((c.volume() - PI * 0.5).abs() < 1e-15);
        assert!(c.contains(&Vec3::new(1.4, 1.0, 1.9)));
        assert!(!c.contains(&Vec3::new(1.4, 1.4, 1.0)));
        assert!(!c.contains(&Vec3::new(1.0, 1.0, 2.1)));
        assert!(!c.contains(&Vec3::new(1.0, 1.0, -0.1)));
    }

    #[test]
    fn empty_or_odd_regions_are_refused() {
        let flat = Region::Box { min: Vec3::zeros(), max: Vec3::new(1.0, 0.0, 1.0) };
        assert!(flat.validate().is_err());
        let nan = Region::Box { min: Vec3::zeros(), max: Vec3::new(1.0, Real::NAN, 1.0) };
        assert!(nan.validate().is_err());
        let cylinder = |axis: Vec3, radius: Real, length: Real| Region::Cylinder {
            start: Vec3::zeros(),
            axis,
            radius,
            length,
        };
        assert!(cylinder(Vec3::zeros(), 1.0, 1.0).validate().is_err());
        assert!(cylinder(Vec3::z(), 0.0, 1.0).validate().is_err());
        assert!(cylinder(Vec3::z(), 1.0, -1.0).validate().is_err());
        assert!(cylinder(Vec3::z(), 1.0, Real::INFINITY).validate().is_err());
    }
}
