//! Checks of single values, each giving a located error that names the key and what is
//! expected.

use crate::error::{Ctx, SceneError};
use crate::schema::{S, V3};
use flexdem_geom::{Real, Vec3};

impl Ctx<'_> {
    /// A finite number.
    pub fn finite(&self, v: &S<f64>, key: &str, unit: &str) -> Result<Real, SceneError> {
        let x = *v.get_ref();
        if x.is_finite() {
            Ok(x)
        } else {
            Err(self.at(v.span(), key, format!("is {x}: expected a finite number ({unit})")))
        }
    }

    /// A finite number > 0.
    pub fn positive(&self, v: &S<f64>, key: &str, unit: &str) -> Result<Real, SceneError> {
        let x = *v.get_ref();
        if x.is_finite() && x > 0.0 {
            Ok(x)
        } else {
            Err(self.at(v.span(), key, format!("is {x}: expected a finite number > 0 ({unit})")))
        }
    }

    /// A finite number ≥ 0.
    pub fn non_negative(&self, v: &S<f64>, key: &str, unit: &str) -> Result<Real, SceneError> {
        let x = *v.get_ref();
        if x.is_finite() && x >= 0.0 {
            Ok(x)
        } else {
            Err(self.at(v.span(), key, format!("is {x}: expected a finite number >= 0 ({unit})")))
        }
    }

    /// Three finite numbers.
    pub fn vec3(&self, v: &S<V3>, key: &str, unit: &str) -> Result<Vec3, SceneError> {
        let a = v.get_ref().0;
        if a.iter().all(|c| c.is_finite()) {
            Ok(Vec3::from(a))
        } else {
            Err(self.at(
                v.span(),
                key,
                format!("is {a:?}: expected three finite numbers [x, y, z] ({unit})"),
            ))
        }
    }

    /// Three finite numbers, not all zero (a direction; any length). As given when its
    /// squared length is a normal float; else (a length above ~1e154 or below ~1e-154,
    /// whose square overflows or underflows, so that `normalize` would give NaN) divided
    /// by its largest |component|, which keeps the direction.
    pub fn direction(&self, v: &S<V3>, key: &str) -> Result<Vec3, SceneError> {
        let d = self.vec3(v, key, "a direction, any length")?;
        let n2 = d.norm_squared();
        if n2.is_finite() && n2 >= Real::MIN_POSITIVE {
            return Ok(d);
        }
        let largest = d.amax();
        if largest > 0.0 {
            Ok(d / largest)
        } else {
            Err(self.at(v.span(), key, "is [0, 0, 0]: expected a non-zero direction [x, y, z]"))
        }
    }

    /// A whole number ≥ `min`, as usize.
    pub fn count(&self, v: &S<i64>, key: &str, min: i64) -> Result<usize, SceneError> {
        let n = *v.get_ref();
        match usize::try_from(n) {
            Ok(u) if n >= min => Ok(u),
            _ => Err(self.at(v.span(), key, format!("is {n}: expected a whole number >= {min}"))),
        }
    }

    /// A collision mask: a whole number in [1, 2³² − 1] (bits of the groups it belongs to).
    pub fn mask(&self, v: Option<&S<i64>>, key: &str) -> Result<u32, SceneError> {
        let Some(v) = v else { return Ok(1) };
        let n = *v.get_ref();
        match u32::try_from(n) {
            Ok(m) if m > 0 => Ok(m),
            _ => Err(self.at(
                v.span(),
                key,
                format!("is {n}: expected a collision mask, a whole number in [1, 4294967295]"),
            )),
        }
    }

    /// An error at `span` for a missing key of a table.
    pub fn missing(&self, span: std::ops::Range<usize>, key: &str, why: &str) -> SceneError {
        self.at(span, key, format!("missing: {why}"))
    }
}
