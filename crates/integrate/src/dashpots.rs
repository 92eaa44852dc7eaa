//! What the engine adds to the contact dashpots of the law (`flexdem_contact::damping`,
//! model.md §7), for the general contacts (`contacts.rs`) and the free spheres' neighbour list
//! (`neighbours.rs`) alike: the effective mass a contact is made with, the power of the
//! dashpots over the half kick after the step (the second half of their dissipation), what
//! the shear spring of a damped contact that ends moves the balance by, and the stiffness a
//! damped contact counts for in the critical time step.

use flexdem_contact::{FrictionalContact, FrictionalParams};
use flexdem_elements::virtual_sphere::{Feature, NodeLoad, Site};
use flexdem_elements::{Dofs, Model, Particles};
use flexdem_geom::{Real, Vec3};

/// The mass a site moves with (kg): the particle's for a free sphere or a node, and for a
/// site on an edge or a face (a virtual sphere interpolated from its nodes with weights wᵢ)
/// the interpolated mass `Σ wᵢ·mᵢ`. A wall, or a site with a node of weight > 0 whose
/// translations are all blocked, is infinitely massive.
pub(crate) fn site_mass(site: &Site, p: &Particles) -> Real {
    if let Feature::Wall(_) = site.feature {
        return Real::INFINITY;
    }
    let mut mass = 0.0;
    for k in 0..site.node_count() {
        let w = site.weights[k];
        if !(w > 0.0) {
            continue;
        }
        let i = site.nodes[k] as usize;
        if p.blocked[i].contains(Dofs::TRANSLATION) {
            return Real::INFINITY;
        }
        mass += w * p.mass[i];
    }
    mass
}

/// The power of a contact's dashpot force at t (`force` on body 2, shared among the nodes of
/// the two sites as `loads`: site 1's in slots 0..3, site 2's in 3..6) with the particles'
/// current velocities and, for a wall on site 1, the wall's: `Σ (fᵢ·vᵢ + τᵢ·ωᵢ) − F·v_wall`
/// (W). The node loads are the transpose of the interpolation (`distribute_force`), so this
/// is `F·v_rel` with the relative velocity of the contact point at the positions of t: the
/// power the leapfrog sees.
pub(crate) fn dashpot_power(
    site1: &Site,
    site2: &Site,
    force: &Vec3,
    loads: &[NodeLoad; 6],
    model: &Model,
) -> Real {
    let p = &model.particles;
    let (n1, n2) = (site1.node_count(), site2.node_count());
    let mut power = 0.0;
    for l in loads[..n1].iter().chain(&loads[3..3 + n2]) {
        let i = l.node as usize;
        power += l.force.dot(&p.vel[i]) + l.torque.dot(&p.ang_vel[i]);
    }
    if let Feature::Wall(w) = site1.feature {
        power -= force.dot(&model.walls[w as usize].velocity);
    }
    power
}

/// [`dashpot_power`] of a free spheres' pair `key` (a sphere and a sphere, or a wall and a
/// sphere) whose dashpots pushed body 2 with `force`: its node loads are `−force` with the
/// moment `moments[0]` on sphere 1 (none on a wall) and `force` with `moments[1]` on sphere
/// 2, summed in that order and less `force·v_wall` for a wall, as [`dashpot_power`] sums
/// them (the same operations, so the same result to the last bit).
pub(crate) fn pair_dashpot_power(
    key: &(Feature, Feature),
    force: &Vec3,
    moments: &[Vec3; 2],
    model: &Model,
) -> Real {
    let p = &model.particles;
    let load = |i: u32, f: &Vec3, moment: &Vec3| {
        f.dot(&p.vel[i as usize]) + moment.dot(&p.ang_vel[i as usize])
    };
    let mut power = 0.0;
    if let Feature::Particle(i) = key.0 {
        power += load(i, &(-force), &moments[0]);
    }
    if let Feature::Particle(j) = key.1 {
        power += load(j, force, &moments[1]);
    }
    if let Feature::Wall(w) = key.0 {
        power -= force.dot(&model.walls[w as usize].velocity);
    }
    power
}

/// What a contact that ended moves the energy balance by through the force `fs` its shear
/// spring had at its last update, which also works over the half step after it (the kinetic
/// energy shows it): `½·Fs·v_rel·dt`, `v_rel` the relative velocity of the contact point
/// continued to now. Counted for a damped contact, which can end holding a large spring
/// force (`ct·u̇s`, model.md §7); an undamped one ends with at most tanφ·Fn, which vanishes as
/// it opens, and leaves this small term out (0), as it always has.
pub(crate) fn shear_exit(params: &FrictionalParams, fs: &Vec3, v_rel: &Vec3, dt: Real) -> Real {
    if params.is_damped() {
        0.5 * fs.dot(v_rel) * dt
    } else {
        0.0
    }
}

/// What a contact that ended moves the energy balance by, added to `put_in` and `released`
/// (model.md §2): its normal spring leaves the balance, `−½·F·δ_now` (`now` the overlap, less
/// its offset, continued to this step: put in when it ended by separating, released when it
/// ended while compressed); its shear spring's energy `|Fs|²/(2ks)` is released; and
/// [`shear_exit`], by its sign. The additions in that order, each to its sum.
pub(crate) fn account_ended_springs(
    params: &FrictionalParams,
    state: &FrictionalContact,
    now: Real,
    v_rel: &Vec3,
    dt: Real,
    put_in: &mut Real,
    released: &mut Real,
) {
    let jump = -0.5 * state.normal_force * now;
    if jump >= 0.0 {
        *put_in += jump;
    } else {
        *released -= jump;
    }
    if params.ks > 0.0 {
        *released += 0.5 * state.shear_force.norm_squared() / params.ks;
    }
    let w = shear_exit(params, &state.shear_force, v_rel, dt);
    if w >= 0.0 {
        *put_in += w;
    } else {
        *released -= w;
    }
}

/// The factor a contact stiffness `k` with a dashpot `c` is raised by in the critical time
/// step estimate of a particle of mass `m` (time_step.rs): the leapfrog, whose dashpot acts
/// with the velocity of the half step before, is stable for `ω·dt < 2·(√(1 + ζ²) − ζ)`
/// instead of `ω·dt < 2`, the stability of an undamped spring `k·(√(1 + ζ²) + ζ)²`. With
/// `ζ = c/√(2·k·m)`: the damping ratio of two equal particles in contact, in the same
/// convention as the estimate `√(2m/K)` (it overstates a particle against a wall's, which
/// is safe). 1 without a dashpot.
pub(crate) fn damped_stiffness_factor(k: Real, c: Real, m: Real) -> Real {
    if !(c > 0.0 && k > 0.0 && m > 0.0) {
        return 1.0;
    }
    let zeta = c / (2.0 * k * m).sqrt();
    let s = (1.0 + zeta * zeta).sqrt() + zeta;
    s * s
}

/// [`damped_stiffness_factor`] with its last answer kept: a sum over the contacts (the time
/// step's estimate) asks it for the same stiffness, dashpot and mass again and again in a
/// packing of one material and one size (each call is two square roots and a division; in
/// the LAMMPS twin the estimate, every 10 steps, was 4 % of the step). Same bits: the
/// function's own answer for the same inputs.
#[derive(Clone, Copy, Debug)]
pub(crate) struct FactorMemo {
    /// The last inputs' bits (k, c, m).
    asked: [u64; 3],
    /// `damped_stiffness_factor` of them.
    factor: Real,
}

impl Default for FactorMemo {
    fn default() -> Self {
        // (NaN inputs, whose factor is 1: the memo holds a true answer from the start)
        let asked = [u64::MAX; 3];
        let [k, c, m] = asked.map(Real::from_bits);
        FactorMemo { asked, factor: damped_stiffness_factor(k, c, m) }
    }
}

impl FactorMemo {
    /// `damped_stiffness_factor(k, c, m)`, computed only when the inputs changed.
    #[inline]
    pub(crate) fn factor(&mut self, k: Real, c: Real, m: Real) -> Real {
        let asked = [k, c, m].map(Real::to_bits);
        if asked != self.asked {
            self.asked = asked;
            self.factor = damped_stiffness_factor(k, c, m);
        }
        self.factor
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use flexdem_elements::{Particle, ParticleKind};

    #[test]
    fn a_site_moves_with_its_interpolated_mass_unless_held() {
        let mut p = Particles::default();
        for (i, m) in [1.0, 2.0, 4.0].into_iter().enumerate() {
            let mut q =
                Particle::at_rest(ParticleKind::Node, Vec3::new(i as Real, 0.0, 0.0), 0.1, 0);
            q.mass = m;
            p.push(q);
        }
        let face = Site {
            feature: Feature::Face(0),
            nodes: [0, 1, 2],
            weights: [0.5, 0.25, 0.25],
            radius: 0.1,
        };
        assert_eq!(site_mass(&face, &p), 0.5 + 0.5 + 1.0);
        assert_eq!(site_mass(&Site::particle(2, 0.1), &p), 4.0);
        assert_eq!(site_mass(&Site::wall(0), &p), Real::INFINITY);
        p.blocked[2] = Dofs::TRANSLATION;
        assert_eq!(site_mass(&face, &p), Real::INFINITY);
        // a held node of weight 0 does not hold the site
        let edge = Site::edge(0, [0, 2], 0.0, 0.1);
        assert_eq!(site_mass(&edge, &p), 1.0);
    }

    #[test]
    fn a_pairs_dashpot_power_is_the_general_one_to_the_bit() {
        use flexdem_contact::Material;
        let mut model = Model::new();
        let m = model.add_material(Material::new(1e8, 0.3, 2650.0, 0.5).unwrap()).unwrap();
        let wall = model.add_wall(Vec3::zeros(), Vec3::z(), m).unwrap();
        model.walls[wall as usize].velocity = Vec3::new(0.3, -0.2, 0.7);
        for (x, v, w) in
            [(0.0, [1.1, -0.3, 0.2], [3.0, 1.0, -2.0]), (0.9, [-0.4, 0.5, 0.1], [0.5, -7.0, 2.5])]
        {
            let i = model.add_sphere(Vec3::new(x, 0.0, 0.5), 0.5, m).unwrap();
            model.particles.vel[i as usize] = Vec3::from(v);
            model.particles.ang_vel[i as usize] = Vec3::from(w);
        }
        let f = Vec3::new(0.37, -1.9, 4.3);
        let moments = [Vec3::new(0.1, 0.25, -0.3), Vec3::new(-0.7, 0.05, 0.9)];
        let load = |node: u32, force: Vec3, torque: Vec3| NodeLoad { node, force, torque };
        let none = load(0, Vec3::zeros(), Vec3::zeros());
        let spheres = [load(0, -f, moments[0]), none, none, load(1, f, moments[1]), none, none];
        let general =
            dashpot_power(&Site::particle(0, 0.5), &Site::particle(1, 0.5), &f, &spheres, &model);
        let key = (Feature::Particle(0), Feature::Particle(1));
        assert_eq!(pair_dashpot_power(&key, &f, &moments, &model).to_bits(), general.to_bits());
        let on_wall = [none, none, none, load(1, f, moments[1]), none, none];
        let general =
            dashpot_power(&Site::wall(wall), &Site::particle(1, 0.5), &f, &on_wall, &model);
        let key = (Feature::Wall(wall), Feature::Particle(1));
        assert_eq!(pair_dashpot_power(&key, &f, &moments, &model).to_bits(), general.to_bits());
        assert!(general != 0.0);
    }

    #[test]
    fn a_dashpot_lowers_the_critical_step_as_the_damped_leapfrog_needs() {
        assert_eq!(damped_stiffness_factor(1e6, 0.0, 1.0), 1.0);
        // ζ = 0.6: stable for ω·dt < 2·(√1.36 − 0.6) = 1.1324
        let (k, m): (Real, Real) = (1e6, 2.0);
        let c = 0.6 * (2.0 * k * m).sqrt();
        let f = damped_stiffness_factor(k, c, m);
        let limit = 2.0 * ((1.0_f64 + 0.36).sqrt() - 0.6);
        assert!((2.0 / f.sqrt() - limit).abs() < 1e-12, "{f}");
    }

    #[test]
    fn the_memo_answers_as_the_factor_does() {
        let mut memo = FactorMemo::default();
        // repeated inputs, each input changed alone, undamped, a NaN and back
        let asks = [
            (1e6, 300.0, 2.0),
            (1e6, 300.0, 2.0),
            (1e6, 300.0, 3.0),
            (1e6, 400.0, 3.0),
            (2e6, 400.0, 3.0),
            (2e6, 0.0, 3.0),
            (Real::NAN, 400.0, 3.0),
            (1e6, 300.0, 2.0),
        ];
        for (k, c, m) in asks {
            let (got, want) = (memo.factor(k, c, m), damped_stiffness_factor(k, c, m));
            assert_eq!(got.to_bits(), want.to_bits(), "k {k}, c {c}, m {m}");
        }
        let nan = Real::from_bits(u64::MAX);
        assert_eq!(FactorMemo::default().factor(nan, nan, nan), 1.0);
    }
}
