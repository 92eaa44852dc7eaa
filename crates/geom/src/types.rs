//! The number types of every computation.

/// Scalar type of every computation.
pub type Real = f64;
/// A 3-vector (positions are vectors too).
pub type Vec3 = nalgebra::Vector3<Real>;
