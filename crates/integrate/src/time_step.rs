//! The critical time step (model.md §4): from the stiffness each particle feels from its
//! links and contacts, translational and rotational,
//! `dt_crit = min over particles of √(2·min(m/K_trans, J/K_rot))` (YADE's
//! GlobalStiffnessTimeStepper), counting links at rest (YADE skips them) and contacts on the
//! nodes that carry them (YADE does not). A P-wave estimate `r/√(E/ρ)` is the answer when no
//! particle feels any stiffness yet (free spheres in flight before their first contact).

use crate::parallel::MIN_PARALLEL_CHEAP;
use flexdem_elements::{Model, Particles};
use flexdem_geom::{Real, Vec3};
use rayon::prelude::*;

/// Per-particle stiffness sums, per axis, translational and rotational.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct StiffnessSums {
    /// Translational stiffness per axis (N/m).
    pub translational: Vec<Vec3>,
    /// Rotational stiffness per axis (N·m/rad).
    pub rotational: Vec<Vec3>,
}

impl StiffnessSums {
    /// Zero sums for `n` particles.
    pub fn new(n: usize) -> Self {
        StiffnessSums { translational: vec![Vec3::zeros(); n], rotational: vec![Vec3::zeros(); n] }
    }

    /// Zero sums for `n` particles, in the memory these sums already hold.
    pub fn reset(&mut self, n: usize) {
        for sums in [&mut self.translational, &mut self.rotational] {
            sums.clear();
            sums.resize(n, Vec3::zeros());
        }
    }

    /// Adds a spring pair of normal stiffness `kn` and shear stiffness `ks` along unit normal
    /// `n`, with lever arm `lever` from the particle to the spring, and rotational springs
    /// `kt` (twist, about n) and `kb` (bending), to particle `i`:
    /// `K_trans,k += (kn − ks)·n_k² + ks`,
    /// `K_rot,k += ks·lever²·(1 − n_k²) + (kt − kb)·n_k² + kb`.
    pub fn add(&mut self, i: usize, n: &Vec3, kn: Real, ks: Real, lever: Real, kt: Real, kb: Real) {
        let (t, r) = spring_increments(n, kn, ks, lever, kt, kb);
        self.translational[i] += t;
        self.rotational[i] += r;
    }
}

/// What [`StiffnessSums::add`] adds to a particle's translational and rotational sums.
#[inline]
pub(crate) fn spring_increments(
    n: &Vec3,
    kn: Real,
    ks: Real,
    lever: Real,
    kt: Real,
    kb: Real,
) -> (Vec3, Vec3) {
    let n2 = n.component_mul(n);
    let t = n2 * (kn - ks) + Vec3::repeat(ks);
    let r = (Vec3::repeat(1.0) - n2) * (ks * lever * lever) + n2 * (kt - kb) + Vec3::repeat(kb);
    (t, r)
}

/// `√(2·min(m/K_trans, J/K_rot))` over the particles that feel a stiffness and are free in
/// at least one DOF; `None` if none does. In parallel over the particles (a minimum of
/// numbers, none a NaN, is the same whatever the order it is taken in).
pub fn critical_step_from_stiffness(model: &Model, k: &StiffnessSums) -> Option<Real> {
    let p = &model.particles;
    (0..p.len())
        .into_par_iter()
        .with_min_len(MIN_PARALLEL_CHEAP)
        .filter_map(|i| particle_critical_step(p, k, i))
        .reduce_with(Real::min)
}

/// `√(2·min(m/K_trans, J/K_rot))` of particle `i`, if it feels a stiffness and is free in at
/// least one DOF (a positive number, never a NaN).
#[inline]
fn particle_critical_step(p: &Particles, k: &StiffnessSums, i: usize) -> Option<Real> {
    if p.blocked[i] == flexdem_elements::Dofs::ALL {
        return None;
    }
    let mut ratio = Real::INFINITY;
    let (kt, kr) = (k.translational[i].max(), k.rotational[i].max());
    if kt > 0.0 {
        ratio = ratio.min(p.mass[i] / kt);
    }
    if kr > 0.0 && p.inertia[i] > 0.0 {
        ratio = ratio.min(p.inertia[i] / kr);
    }
    ratio.is_finite().then(|| (2.0 * ratio).sqrt())
}

/// P-wave estimate `min over particles of r/√(E/ρ_eff)` with `ρ_eff = m/((4/3)πr³)` (YADE's
/// PWaveTimeStep); `None` for a model without massive particles.
pub fn p_wave_time_step(model: &Model) -> Option<Real> {
    let p = &model.particles;
    let mut best: Option<Real> = None;
    for i in 0..p.len() {
        let (r, m) = (p.radius[i], p.mass[i]);
        let e = model.materials[p.material[i] as usize].young;
        if r > 0.0 && m > 0.0 && e > 0.0 {
            let rho = m / (4.0 / 3.0 * std::f64::consts::PI * r * r * r);
            let dt = r / (e / rho).sqrt();
            best = Some(best.map_or(dt, |b: Real| b.min(dt)));
        }
    }
    best
}
