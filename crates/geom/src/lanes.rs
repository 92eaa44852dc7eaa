//! Four 3-vectors or quaternions at once (`wide::f64x4` lanes), with nalgebra's formulas term
//! for term, so that a lane's result has the bits nalgebra gives for that lane alone (IEEE
//! additions, products, divisions and square roots round the same packed or alone; no fused
//! multiply–add is used). For the engine's vectorised loops (four links, four particles).

use crate::Vec3;
pub use wide::f64x4;

/// Four 3-vectors, one per lane, as three `f64x4` (x, y, z).
#[derive(Clone, Copy, Debug)]
pub struct V3 {
    /// The lanes' x.
    pub x: f64x4,
    /// The lanes' y.
    pub y: f64x4,
    /// The lanes' z.
    pub z: f64x4,
}

impl V3 {
    /// The lanes `f(0)` to `f(3)`.
    #[inline(always)]
    pub fn gather(f: impl Fn(usize) -> Vec3) -> V3 {
        let v: [Vec3; 4] = std::array::from_fn(f);
        V3 {
            x: f64x4::new(v.map(|v| v.x)),
            y: f64x4::new(v.map(|v| v.y)),
            z: f64x4::new(v.map(|v| v.z)),
        }
    }

    /// The four lanes as vectors (each coordinate taken out once).
    #[inline(always)]
    pub fn lanes(&self) -> [Vec3; 4] {
        let (x, y, z) = (self.x.to_array(), self.y.to_array(), self.z.to_array());
        std::array::from_fn(|j| Vec3::new(x[j], y[j], z[j]))
    }

    /// Lane `l` as a vector, read from the three coordinates where they are (no array of
    /// four vectors made on the stack: copying one out of it would read 16 bytes written as
    /// two 8-byte stores, which store forwarding cannot serve).
    #[inline(always)]
    pub fn lane(&self, l: usize) -> Vec3 {
        Vec3::new(self.x.as_array()[l], self.y.as_array()[l], self.z.as_array()[l])
    }

    /// Lane by lane sum.
    #[inline(always)]
    pub fn plus(self, o: V3) -> V3 {
        V3 { x: self.x + o.x, y: self.y + o.y, z: self.z + o.z }
    }

    /// Lane by lane difference.
    #[inline(always)]
    pub fn minus(self, o: V3) -> V3 {
        V3 { x: self.x - o.x, y: self.y - o.y, z: self.z - o.z }
    }

    /// Each lane times its scalar.
    #[inline(always)]
    pub fn scale(self, s: f64x4) -> V3 {
        V3 { x: self.x * s, y: self.y * s, z: self.z * s }
    }

    /// nalgebra's order: (x·x' + y·y') + z·z'.
    #[inline(always)]
    pub fn dot(self, o: V3) -> f64x4 {
        self.x * o.x + self.y * o.y + self.z * o.z
    }

    /// nalgebra's `norm_squared`: 0 + the dot product (the same bits: it is never −0).
    #[inline(always)]
    pub fn norm_squared(self) -> f64x4 {
        self.dot(self)
    }

    /// Lane by lane cross product, in nalgebra's order.
    #[inline(always)]
    pub fn cross(self, b: V3) -> V3 {
        V3 {
            x: self.y * b.z - self.z * b.y,
            y: self.z * b.x - self.x * b.z,
            z: self.x * b.y - self.y * b.x,
        }
    }

    /// `if mask { a } else { b }` lane by lane.
    #[inline(always)]
    pub fn select(mask: f64x4, a: V3, b: V3) -> V3 {
        V3 { x: mask.select(a.x, b.x), y: mask.select(a.y, b.y), z: mask.select(a.z, b.z) }
    }
}

/// Four quaternions (w, i, j, k), one per lane.
#[derive(Clone, Copy, Debug)]
pub struct Q4 {
    /// The lanes' w.
    pub w: f64x4,
    /// The lanes' i.
    pub i: f64x4,
    /// The lanes' j.
    pub j: f64x4,
    /// The lanes' k.
    pub k: f64x4,
}

impl Q4 {
    /// nalgebra's Hamilton product, term for term.
    #[inline(always)]
    pub fn times(self, r: Q4) -> Q4 {
        let s = self;
        Q4 {
            w: s.w * r.w - s.i * r.i - s.j * r.j - s.k * r.k,
            i: s.w * r.i + s.i * r.w + s.j * r.k - s.k * r.j,
            j: s.w * r.j - s.i * r.k + s.j * r.w + s.k * r.i,
            k: s.w * r.k + s.i * r.j - s.j * r.i + s.k * r.w,
        }
    }

    /// nalgebra's `norm_squared` of the coordinates (i, j, k, w): (i² + k²) + (j² + w²), its
    /// unrolled four-term dot product.
    #[inline(always)]
    pub fn norm_squared(self) -> f64x4 {
        let (mut a, mut b) = (self.i * self.i, self.j * self.j);
        a += self.k * self.k;
        b += self.w * self.w;
        a + b
    }

    /// Each lane's quaternion times its scalar.
    #[inline(always)]
    pub fn scale(self, s: f64x4) -> Q4 {
        Q4 { w: self.w * s, i: self.i * s, j: self.j * s, k: self.k * s }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Real;
    use nalgebra::{Quaternion, UnitQuaternion};

    /// Lane by lane, the lanes' products, sums and norms are nalgebra's to the bit.
    #[test]
    fn lanes_are_nalgebra_to_the_bit() {
        let mut state = 0x9E37_79B9_7F4A_7C15u64;
        let mut r = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            ((state >> 11) as Real / (1u64 << 53) as Real * 2.0 - 1.0) * 1e3
        };
        let bits = |v: Vec3| v.map(Real::to_bits);
        for _ in 0..200 {
            let a: [Vec3; 4] = std::array::from_fn(|_| Vec3::new(r(), r(), r()));
            let b: [Vec3; 4] = std::array::from_fn(|_| Vec3::new(r(), r(), r()));
            let s: [Real; 4] = std::array::from_fn(|_| r());
            let (la, lb) = (V3::gather(|l| a[l]), V3::gather(|l| b[l]));
            let sl = f64x4::new(s);
            let (dot, n2) = (la.dot(lb).to_array(), la.norm_squared().to_array());
            let (cross, sum) = (la.cross(lb).lanes(), la.plus(lb).lanes());
            let (diff, scaled) = (la.minus(lb).lanes(), la.scale(sl).lanes());
            let mask = la.x.simd_gt(lb.x);
            let chosen = V3::select(mask, la, lb).lanes();
            let q: [UnitQuaternion<Real>; 4] =
                std::array::from_fn(|_| UnitQuaternion::from_scaled_axis(Vec3::new(r(), r(), r())));
            let p: [Quaternion<Real>; 4] =
                std::array::from_fn(|_| Quaternion::new(r(), r(), r(), r()));
            let quat = |q: &[Quaternion<Real>; 4]| Q4 {
                w: f64x4::new(q.map(|q| q.w)),
                i: f64x4::new(q.map(|q| q.i)),
                j: f64x4::new(q.map(|q| q.j)),
                k: f64x4::new(q.map(|q| q.k)),
            };
            let (lq, lp) = (quat(&q.map(|q| q.into_inner())), quat(&p));
            let prod = lq.times(lp);
            let (pn2, pscaled) = (lp.norm_squared().to_array(), lp.scale(sl));
            for l in 0..4 {
                assert_eq!(dot[l].to_bits(), a[l].dot(&b[l]).to_bits());
                assert_eq!(n2[l].to_bits(), a[l].norm_squared().to_bits());
                assert_eq!(bits(cross[l]), bits(a[l].cross(&b[l])));
                assert_eq!(bits(sum[l]), bits(a[l] + b[l]));
                assert_eq!(bits(diff[l]), bits(a[l] - b[l]));
                assert_eq!(bits(scaled[l]), bits(a[l] * s[l]));
                let expected = if a[l].x > b[l].x { a[l] } else { b[l] };
                assert_eq!(bits(chosen[l]), bits(expected));
                let want = q[l].into_inner() * p[l];
                let got = [prod.w, prod.i, prod.j, prod.k].map(|c| c.to_array()[l].to_bits());
                assert_eq!(got, [want.w, want.i, want.j, want.k].map(Real::to_bits));
                assert_eq!(pn2[l].to_bits(), p[l].norm_squared().to_bits());
                let want = p[l] * s[l];
                let got = [pscaled.w, pscaled.i, pscaled.j, pscaled.k].map(|c| c.to_array()[l]);
                assert_eq!(
                    got.map(Real::to_bits),
                    [want.w, want.i, want.j, want.k].map(Real::to_bits)
                );
            }
        }
    }
}
