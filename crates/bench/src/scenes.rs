//! The benchmark scenes: the paper's tube impact, a PFacet membrane under a layer of
//! spheres, and a packing of spheres falling in a box. Each builder returns a model and its
//! settings, ready for `Simulation::new`; the builds are deterministic (no clock, fixed seeds).

use crate::BenchError;
use flexdem_contact::Material;
use flexdem_elements::builders::{membrane_rectangle, GridLayout};
use flexdem_elements::{Dofs, MassLumping, MaterialId, Model, ModelError, StructureOptions};
use flexdem_geom::{Real, Vec3};
use flexdem_integrate::{Settings, Simulation, TimeStep};
use std::path::Path;

/// The tube impact scene file (`examples/tube_impact_heavy.toml`: the 4.19 kg sphere),
/// embedded so that the benchmark runs from any folder. It is flexdem's own speed scene; the
/// YADE comparison (`bench/run_vs_yade.sh`) runs the twin of YADE's reference run instead
/// (`bench/scenes/tube_impact_solid_yade.toml`: the light sphere, YADE's mesh and dt).
const TUBE_IMPACT_TOML: &str = include_str!("../../../examples/tube_impact_heavy.toml");

/// Fixed time step of the tube impact benchmark (s). flexdem's critical step estimate (links
/// and contacts) is 8.9e-4 s at the start and stays above 3.7e-4 s over the 750 steps
/// (0.15 s) of the benchmark (tested), so 2e-4 s is at most 0.54 of it. (It is above YADE's
/// own P-wave step for this scene, 1.71e-4 s, which is why the YADE twin does not use it.)
pub const TUBE_IMPACT_DT: Real = 2e-4;

/// Size of the tube impact scene: its PFacet count (it has one size only).
pub const TUBE_IMPACT_PFACETS: usize = 640;

/// Membrane grid cell (m): the 1 m / 16 cells of `examples/membrane_spheres.toml`.
pub const MEMBRANE_CELL: Real = 0.0625;

/// Radius of the membrane's nodes, connections and PFacets (m): half its thickness.
pub const MEMBRANE_NODE_RADIUS: Real = 0.002;

/// The membrane's interior nodes (i, j) with i and j multiples of this are pinned too
/// (posts), so that the membrane carries the spheres within a few hundred steps instead of
/// free-falling with them: the tension from the edges alone would take a time growing with
/// the membrane's size to reach its middle.
pub const MEMBRANE_POST_SPACING: usize = 4;

/// Radius of the packing's spheres (m).
pub const PACKING_RADIUS: Real = 0.005;

/// The packing's columns start pressed together (and into the floor) by this fraction of
/// their heights (an overlap of 2r·1e-5 = 0.1 µm per contact, a few times the static one),
/// so that every sphere has its contact below from the first step.
pub const PACKING_PRESS: Real = 1e-5;

/// Layers of the packing's initial lattice.
pub const PACKING_LAYERS: usize = 10;

/// A benchmark scene.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum SceneKind {
    /// The paper's tube impact (§7), `examples/tube_impact_heavy.toml` with a fixed step.
    TubeImpact,
    /// A square PFacet membrane, edges pinned, under one layer of spheres, with gravity.
    Membrane,
    /// Spheres falling in a box of walls, with gravity.
    Packing,
}

impl SceneKind {
    /// Every scene, in table order.
    pub const ALL: [SceneKind; 3] =
        [SceneKind::TubeImpact, SceneKind::Membrane, SceneKind::Packing];

    /// The scene's name on the command line and in tables.
    pub fn name(self) -> &'static str {
        match self {
            SceneKind::TubeImpact => "tube_impact",
            SceneKind::Membrane => "membrane",
            SceneKind::Packing => "packing",
        }
    }

    /// The scene called `name`.
    pub fn parse(name: &str) -> Result<SceneKind, BenchError> {
        SceneKind::ALL
            .into_iter()
            .find(|k| k.name() == name)
            .ok_or_else(|| BenchError::UnknownScene(name.to_owned()))
    }

    /// What the size parameter counts.
    pub fn size_meaning(self) -> &'static str {
        match self {
            SceneKind::TubeImpact => "PFacets (fixed: 640)",
            SceneKind::Membrane => "PFacets (about)",
            SceneKind::Packing => "spheres (about)",
        }
    }

    /// Sizes run by default: 10³ to 10⁶ PFacets for the membrane, 10³ to 10⁵ spheres for
    /// the packing, the paper's 640 PFacets for the tube.
    pub fn default_sizes(self) -> Vec<usize> {
        match self {
            SceneKind::TubeImpact => vec![TUBE_IMPACT_PFACETS],
            SceneKind::Membrane => vec![1_000, 10_000, 100_000, 1_000_000],
            SceneKind::Packing => vec![1_000, 10_000, 100_000],
        }
    }

    /// Sizes of `--quick` runs (seconds in all).
    pub fn quick_sizes(self) -> Vec<usize> {
        match self {
            SceneKind::TubeImpact => vec![TUBE_IMPACT_PFACETS],
            SceneKind::Membrane => vec![200],
            SceneKind::Packing => vec![200],
        }
    }

    /// Steps run before timing, so that contacts exist: the tube's impactor starts 5 mm
    /// above the tube at 2 m/s and touches it after 2.5 ms (12.5 steps of 0.2 ms); the
    /// membrane's spheres and the packing's columns touch from the first step, and the
    /// warm-up lets their contacts and the broad phase settle.
    pub fn warmup_steps(self) -> u64 {
        match self {
            SceneKind::TubeImpact => 25,
            SceneKind::Membrane => 20,
            SceneKind::Packing => 20,
        }
    }

    /// Timed steps when none are asked for and the run length is not adaptive: the tube
    /// impact runs to 0.15 s of simulated time (750 steps of 0.2 ms with the warm-up): the
    /// first half of the scene file's impact, before the sphere has dragged the tube far and
    /// while the fixed step is well below the critical one.
    pub fn fixed_steps(self) -> Option<u64> {
        match self {
            SceneKind::TubeImpact => Some(725),
            SceneKind::Membrane | SceneKind::Packing => None,
        }
    }

    /// A final value to compare with other codes: the impactor's vertical velocity (m/s)
    /// for the tube impact (the last particle), None for the others.
    pub fn probe(self, sim: &Simulation) -> Option<(&'static str, Real)> {
        match self {
            SceneKind::TubeImpact => sim.model().particles.vel.last().map(|v| ("impactor_vz", v.z)),
            SceneKind::Membrane | SceneKind::Packing => None,
        }
    }

    /// Checks that the scene can be built at `size`: 640 for the tube impact, 8 to 2·10⁷
    /// PFacets for the membrane, 10 to 2·10⁷ spheres for the packing.
    pub fn check_size(self, size: usize) -> Result<(), BenchError> {
        let (ok, expected) = match self {
            SceneKind::TubeImpact => {
                (size == TUBE_IMPACT_PFACETS, "640 (the paper's tube has one size)")
            }
            SceneKind::Membrane => ((8..=20_000_000).contains(&size), "8 to 2·10⁷ PFacets"),
            SceneKind::Packing => ((10..=20_000_000).contains(&size), "10 to 2·10⁷ spheres"),
        };
        if ok {
            Ok(())
        } else {
            Err(BenchError::BadSize { scene: self.name(), size, expected })
        }
    }

    /// Builds the scene at `size` (see [`SceneKind::size_meaning`] and
    /// [`SceneKind::check_size`]).
    pub fn build(self, size: usize) -> Result<(Model, Settings), BenchError> {
        self.check_size(size)?;
        match self {
            SceneKind::TubeImpact => tube_impact(),
            SceneKind::Membrane => membrane(size),
            SceneKind::Packing => packing(size),
        }
    }
}

/// The paper's tube impact (§7): `examples/tube_impact_heavy.toml` (640-PFacet tube of
/// radius 0.1 m and node radius 2 mm, E = 1 MPa, both end rings clamped; a solid sphere of
/// radius 0.1 m, E = 100 MPa, at 2 m/s; no gravity, no damping), with the automatic time
/// step replaced by [`TUBE_IMPACT_DT`] so that every run takes the same steps. flexdem's own
/// speed scene, not a YADE twin (that is `bench/scenes/tube_impact_solid_yade.toml`).
pub fn tube_impact() -> Result<(Model, Settings), BenchError> {
    let scene =
        flexdem_scene::parse_scene(TUBE_IMPACT_TOML, Path::new("examples/tube_impact_heavy.toml"))?;
    let mut settings = scene.settings;
    settings.time_step = TimeStep::Fixed(TUBE_IMPACT_DT);
    Ok((scene.model, settings))
}

/// Cells per side of a square membrane of about `pfacets` PFacets (2 per cell):
/// n = round(√(pfacets/2)), at least 2.
pub fn membrane_cells(pfacets: usize) -> usize {
    ((pfacets as Real / 2.0).sqrt().round() as usize).max(2)
}

/// A square PFacet membrane of n × n cells (n = [`membrane_cells`], 2n² ≈ `pfacets`
/// PFacets) of [`MEMBRANE_CELL`] in the plane z = 0, node radius [`MEMBRANE_NODE_RADIUS`],
/// geotextile-like (E = 50 MPa, ν = 0.3, 1000 kg/m³, 25°, plate mass lumping) as in
/// `examples/membrane_spheres.toml`, its boundary pinned (translations blocked) and its
/// nodes (i, j) with i, j multiples of [`MEMBRANE_POST_SPACING`] pinned too (posts). On it,
/// one layer of sand-like spheres (E = 100 MPa, ν = 0.3, 2650 kg/m³, 30°) of diameter one
/// cell, one per 2 × 2 cells, each just touching a PFacet's face (overlap 0). They bounce
/// on the sagging membrane: about half to all of them touch it at any step.
/// Gravity −9.81 m/s² along z, Cundall damping 0.1, automatic time step (safety 0.5).
/// Counts: (n + 1)² nodes, 3n² + 2n connections, 2n² PFacets, ⌊n/2⌋² spheres.
pub fn membrane(pfacets: usize) -> Result<(Model, Settings), BenchError> {
    const SCENE: &str = "membrane";
    SceneKind::Membrane.check_size(pfacets)?;
    let model_err = |source| BenchError::Model { scene: SCENE, source };
    let n = membrane_cells(pfacets);
    let mut model = Model::new();
    let geotextile = add_material(&mut model, 50e6, 1000.0, 25.0).map_err(model_err)?;
    let sand = add_material(&mut model, 1e8, 2650.0, 30.0).map_err(model_err)?;
    let side = n as Real * MEMBRANE_CELL;
    let opts = StructureOptions::new("membrane", MEMBRANE_NODE_RADIUS, geotextile)
        .with_mass(MassLumping::Plate);
    let s = membrane_rectangle(
        &mut model,
        Vec3::zeros(),
        Vec3::x(),
        Vec3::y(),
        side,
        side,
        n,
        n,
        &opts,
    )
    .map_err(|source| BenchError::Build { scene: SCENE, source })?;
    let grid = GridLayout::of(&model, s, n, n).map_err(model_err)?;
    let mut pinned = grid.boundary();
    pinned.extend(
        (0..=n)
            .step_by(MEMBRANE_POST_SPACING)
            .flat_map(|j| (0..=n).step_by(MEMBRANE_POST_SPACING).map(move |i| grid.node(i, j))),
    );
    model.block(pinned, Dofs::TRANSLATION).map_err(model_err)?;
    let r = 0.5 * MEMBRANE_CELL;
    let z = r + MEMBRANE_NODE_RADIUS;
    for j in 0..n / 2 {
        for i in 0..n / 2 {
            // (0.35, 0.6) of a cell: inside the cell's upper PFacet, off its edges.
            let x = (2 * i) as Real * MEMBRANE_CELL + 0.35 * MEMBRANE_CELL;
            let y = (2 * j) as Real * MEMBRANE_CELL + 0.6 * MEMBRANE_CELL;
            model.add_sphere(Vec3::new(x, y, z), r, sand).map_err(model_err)?;
        }
    }
    let settings = Settings {
        gravity: Vec3::new(0.0, 0.0, -9.81),
        damping: 0.1,
        time_step: TimeStep::Auto { safety: 0.5 },
        ..Settings::default()
    };
    Ok((model, settings))
}

/// Columns per side of the packing of about `spheres` spheres in [`PACKING_LAYERS`] layers:
/// round(√(spheres/layers)), at least 1.
pub fn packing_columns(spheres: usize) -> usize {
    ((spheres as Real / PACKING_LAYERS as Real).sqrt().round() as usize).max(1)
}

/// Spheres falling in a box: m × m columns (m = [`packing_columns`]) of
/// [`PACKING_LAYERS`] sand-like spheres (radius [`PACKING_RADIUS`], E = 100 MPa, ν = 0.3,
/// 2650 kg/m³, 30°), each sphere on the one below, the bottom one on the floor, all heights
/// scaled by 1 − [`PACKING_PRESS`] so that every sphere touches from the first step; columns
/// 2.1r apart with a horizontal jitter of up to ±0.05r, each sphere off its column's axis by
/// up to ±1e-4·r and given a random horizontal velocity of up to ±5 cm/s (fixed seed), so
/// that the columns wobble, slide, lean and collapse into a packing. Five walls: the floor z = 0 and the four sides 0.05r beyond the outer columns.
/// Gravity −9.81 m/s² along z, Cundall damping 0.1, automatic time step (safety 0.5).
pub fn packing(spheres: usize) -> Result<(Model, Settings), BenchError> {
    const SCENE: &str = "packing";
    SceneKind::Packing.check_size(spheres)?;
    let model_err = |source| BenchError::Model { scene: SCENE, source };
    let m = packing_columns(spheres);
    let r = PACKING_RADIUS;
    let pitch = 2.1 * r;
    let mut model = Model::new();
    let sand = add_material(&mut model, 1e8, 2650.0, 30.0).map_err(model_err)?;
    let side = m as Real * pitch;
    let walls = [
        (Vec3::zeros(), Vec3::z()),
        (Vec3::zeros(), Vec3::x()),
        (Vec3::zeros(), Vec3::y()),
        (Vec3::new(side, side, 0.0), -Vec3::x()),
        (Vec3::new(side, side, 0.0), -Vec3::y()),
    ];
    for (point, normal) in walls {
        model.add_wall(point, normal, sand).map_err(model_err)?;
    }
    let mut rng = SplitMix64(0x5EED);
    let symmetric = |rng: &mut SplitMix64, half_width: Real| half_width * (2.0 * rng.unit() - 1.0);
    for j in 0..m {
        for i in 0..m {
            let x0 = (i as Real + 0.5) * pitch + symmetric(&mut rng, 0.05 * r);
            let y0 = (j as Real + 0.5) * pitch + symmetric(&mut rng, 0.05 * r);
            for k in 0..PACKING_LAYERS {
                let x = x0 + symmetric(&mut rng, 1e-4 * r);
                let y = y0 + symmetric(&mut rng, 1e-4 * r);
                let z = (r + 2.0 * r * k as Real) * (1.0 - PACKING_PRESS);
                let id = model.add_sphere(Vec3::new(x, y, z), r, sand).map_err(model_err)?;
                let v = Vec3::new(symmetric(&mut rng, 0.05), symmetric(&mut rng, 0.05), 0.0);
                model.particles.vel[id as usize] = v;
            }
        }
    }
    let settings = Settings {
        gravity: Vec3::new(0.0, 0.0, -9.81),
        damping: 0.1,
        time_step: TimeStep::Auto { safety: 0.5 },
        ..Settings::default()
    };
    Ok((model, settings))
}

/// Adds a material with ν = 0.3 (also the ks/kn ratio of contacts), Young's modulus `young`
/// (Pa), `density` (kg/m³) and friction angle `friction_deg` (degrees); returns its id.
fn add_material(
    model: &mut Model,
    young: Real,
    density: Real,
    friction_deg: Real,
) -> Result<MaterialId, ModelError> {
    let id = model.materials.len() as MaterialId;
    let m = Material::new(young, 0.3, density, friction_deg.to_radians())
        .map_err(|source| ModelError::Material { material: id, source })?;
    model.add_material(m)
}

/// SplitMix64 (as in `flexdem_scene::packing`): a small reproducible generator.
struct SplitMix64(u64);

impl SplitMix64 {
    /// Uniform in [0, 1).
    fn unit(&mut self) -> Real {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as Real / (1u64 << 53) as Real
    }
}
