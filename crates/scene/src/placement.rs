//! Placement of a structure: `x' = translate + R·(scale·x)`: scaled about the origin of the
//! structure's own coordinates, then rotated about that origin, then translated (YADE's
//! `gmshPFacet` order).

use flexdem_geom::{Real, Vec3};
use nalgebra::{Unit, UnitQuaternion};

/// A similarity transform `x' = translate + rotation·(scale·x)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Placement {
    /// Translation (m), applied last.
    pub translate: Vec3,
    /// Rotation about the origin, applied after the scale.
    pub rotation: UnitQuaternion<Real>,
    /// Uniform scale factor (> 0), applied first.
    pub scale: Real,
}

impl Default for Placement {
    fn default() -> Self {
        Placement { translate: Vec3::zeros(), rotation: UnitQuaternion::identity(), scale: 1.0 }
    }
}

impl Placement {
    /// The rotation of `rotate_deg = [rx, ry, rz]`: about the fixed x axis by rx, then about
    /// the fixed y axis by ry, then about the fixed z axis by rz (degrees), i.e.
    /// R = Rz(rz)·Ry(ry)·Rx(rx).
    pub fn euler_deg(angles: [Real; 3]) -> UnitQuaternion<Real> {
        let [rx, ry, rz] = angles.map(Real::to_radians);
        UnitQuaternion::from_euler_angles(rx, ry, rz)
    }

    /// The rotation by `angle_deg` degrees about `axis` (right-hand rule), or `None` for a
    /// zero or non-finite axis.
    pub fn axis_angle_deg(axis: Vec3, angle_deg: Real) -> Option<UnitQuaternion<Real>> {
        if !(axis.iter().all(|c| c.is_finite()) && angle_deg.is_finite()) {
            return None;
        }
        let axis = Unit::try_new(axis, 0.0)?;
        Some(UnitQuaternion::from_axis_angle(&axis, angle_deg.to_radians()))
    }

    /// The placed position of a point `p` given in the structure's own coordinates.
    pub fn apply(&self, p: Vec3) -> Vec3 {
        self.translate + self.rotation * (p * self.scale)
    }

    /// The rigid part alone (`translate + R·p`), for points already scaled.
    pub fn apply_rigid(&self, p: Vec3) -> Vec3 {
        self.translate + self.rotation * p
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Vec3, b: Vec3) -> bool {
        (a - b).norm() < 1e-12 * (1.0 + b.norm())
    }

    #[test]
    fn euler_order_is_x_then_y_then_z_about_fixed_axes() {
        // x first: y -> z; then y by 90: z -> x.
        let r = Placement::euler_deg([90.0, 90.0, 0.0]);
        assert!(close(r * Vec3::y(), Vec3::x()));
        let r = Placement::euler_deg([0.0, 0.0, 90.0]);
        assert!(close(r * Vec3::x(), Vec3::y()));
    }

    #[test]
    fn apply_scales_then_rotates_then_translates() {
        let p = Placement {
            translate: Vec3::new(1.0, 2.0, 3.0),
            rotation: Placement::axis_angle_deg(Vec3::z(), 90.0).unwrap(),
            scale: 2.0,
        };
        assert!(close(p.apply(Vec3::x()), Vec3::new(1.0, 4.0, 3.0)));
        assert!(close(p.apply_rigid(Vec3::x()), Vec3::new(1.0, 3.0, 3.0)));
        assert!(Placement::axis_angle_deg(Vec3::zeros(), 10.0).is_none());
        assert!(Placement::axis_angle_deg(Vec3::x(), f64::NAN).is_none());
    }
}
