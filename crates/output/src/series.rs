//! What a run records: the output settings, the quantities of the CSV series, their column
//! names (with units) and their values taken from a simulation.

use crate::error::OutputError;
use crate::triaxial::{triaxial_state, TriaxialSpec, TRIAXIAL_COLUMNS};
use flexdem_geom::{Real, Vec3};
use flexdem_integrate::{
    deviator_stress, love_weber_stress, mean_stress, solid_fraction, wall_normal_stress, Energy,
    Region, Simulation,
};
use serde::{Deserialize, Serialize};
use std::path::PathBuf;

/// A quantity recorded each output step into the CSV series.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum Quantity {
    /// Position of a particle (m): 3 columns `x, y, z`.
    Position(u32),
    /// Velocity of a particle (m/s): 3 columns `vx, vy, vz`.
    Velocity(u32),
    /// Angular velocity of a particle (rad/s): 3 columns `wx, wy, wz`.
    AngularVelocity(u32),
    /// Every energy term of [`flexdem_integrate::Energy`] and its balance (J): one column each.
    Energy,
    /// Sum of the total forces (links, contacts, loads) on a selection of particles at the
    /// last step (N): 3 columns `fx, fy, fz`.
    ForceOnParticles(Vec<u32>),
    /// Number of contacts: 1 column.
    ContactCount,
    /// Number of broken links: 1 column.
    BrokenLinks,
    /// Force the bodies put on a wall at the last step (N, `Simulation::wall_forces`):
    /// 3 columns `fx, fy, fz`.
    WallForce(u32),
    /// Normal stress on a wall (Pa, compression positive): its normal force over `area`
    /// (m²): 1 column `normal_stress`.
    WallStress {
        /// The wall.
        wall: u32,
        /// The area the force is spread over (m²).
        area: Real,
    },
    /// The Love–Weber average stress of the free spheres whose centres are in `region` (Pa,
    /// compression positive, `flexdem_integrate::love_weber_stress`) over `volume` (m³; by
    /// default the region's): 8 columns, the symmetric part `sxx, syy, szz, sxy, sxz, syz`,
    /// then the mean stress `mean_stress` and the deviator `deviator_stress`.
    Stress {
        /// Which spheres count.
        region: Region,
        /// The volume the sum is divided by (m³), None: the region's.
        volume: Option<Real>,
    },
    /// The solid fraction of a region (centre counting, `flexdem_integrate::solid_fraction`):
    /// 1 column `solid_fraction`.
    SolidFraction(Region),
    /// Volume enclosed by the PFacets of a structure (m³), each of its open ends closed by
    /// the plane of one of `walls` (the nearest; one per open end, none for a closed shell):
    /// 1 column `volume` (see [`flexdem_elements::structure_volume`]; NaN if it cannot be
    /// measured any more).
    EnclosedVolume {
        /// The structure.
        structure: u32,
        /// The walls whose current planes close its open ends.
        walls: Vec<u32>,
    },
    /// A triaxial test's measures (see [`crate::triaxial`]): 8 columns `axial_strain`,
    /// `volumetric_strain`, `axial_stress`, `confining_stress`, `mean_stress`,
    /// `deviator_stress` (Pa), `height` (m) and `volume` (m³); NaN if they cannot be measured
    /// any more.
    Triaxial(TriaxialSpec),
}

/// One named quantity of the CSV series; the name prefixes its columns.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SeriesSpec {
    /// Name of the series: letters, digits, `_`, `-` and `.` only (it goes into CSV column
    /// names and the plot's panel titles).
    pub name: String,
    /// What is recorded.
    pub quantity: Quantity,
}

/// What a run writes and how often.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct OutputSettings {
    /// Folder of all output files (created if missing).
    pub directory: PathBuf,
    /// Steps between VTK frames (None: no VTK).
    pub vtk_every: Option<u64>,
    /// Steps between CSV rows (None: no CSV).
    pub series_every: Option<u64>,
    /// The quantities of the CSV series.
    pub series: Vec<SeriesSpec>,
    /// PNG plot of the series at the end of the run.
    pub plot: bool,
}

/// Names of the energy columns: the terms of [`flexdem_integrate::Energy::named_terms`] and
/// the balance, in the order of [`energy_values`].
fn energy_terms() -> [&'static str; 14] {
    let mut names = ["balance"; 14];
    for (name, (term, _)) in names.iter_mut().zip(Energy::default().named_terms()) {
        *name = term;
    }
    names
}

/// The energy terms of a simulation and their balance, in the order of [`energy_terms`] (J).
fn energy_values(sim: &Simulation) -> [Real; 14] {
    let e = sim.energy();
    let mut values = [e.balance(); 14];
    for (value, (_, term)) in values.iter_mut().zip(e.named_terms()) {
        *value = term;
    }
    values
}

/// Names of the stress columns, in the order of [`stress_values`].
const STRESS_COMPONENTS: [&str; 8] =
    ["sxx", "syy", "szz", "sxy", "sxz", "syz", "mean_stress", "deviator_stress"];

/// The Love–Weber stress of the spheres in `region` over `volume`, in the order of
/// [`STRESS_COMPONENTS`] (Pa).
fn stress_values(sim: &Simulation, region: &Region, volume: Option<Real>) -> [Real; 8] {
    let s = love_weber_stress(sim.model(), &sim.contacts(), region, volume);
    let sym = |i: usize, j: usize| 0.5 * (s[(i, j)] + s[(j, i)]);
    [
        s[(0, 0)],
        s[(1, 1)],
        s[(2, 2)],
        sym(0, 1),
        sym(0, 2),
        sym(1, 2),
        mean_stress(&s),
        deviator_stress(&s),
    ]
}

/// Column names of one series, each `NAME_COMPONENT_UNIT`: `tip_x_m`, `tip_vx_m_per_s`,
/// `tip_wx_rad_per_s`, `e_kinetic_translation_J`, `load_fx_N`, `n_count`,
/// `top_normal_stress_Pa`, `sample_szz_Pa`, `sample_mean_stress_Pa`, `sample_solid_fraction`,
/// `membrane_volume_m3`.
pub fn series_columns(spec: &SeriesSpec) -> Vec<String> {
    let name = &spec.name;
    let triple = |prefix: &str, unit: &str| -> Vec<String> {
        ["x", "y", "z"].iter().map(|c| format!("{name}_{prefix}{c}_{unit}")).collect()
    };
    match &spec.quantity {
        Quantity::Position(_) => triple("", "m"),
        Quantity::Velocity(_) => triple("v", "m_per_s"),
        Quantity::AngularVelocity(_) => triple("w", "rad_per_s"),
        Quantity::Energy => energy_terms().iter().map(|t| format!("{name}_{t}_J")).collect(),
        Quantity::ForceOnParticles(_) => triple("f", "N"),
        Quantity::ContactCount | Quantity::BrokenLinks => vec![format!("{name}_count")],
        Quantity::WallForce(_) => triple("f", "N"),
        Quantity::WallStress { .. } => vec![format!("{name}_normal_stress_Pa")],
        Quantity::Stress { .. } => {
            STRESS_COMPONENTS.iter().map(|c| format!("{name}_{c}_Pa")).collect()
        }
        Quantity::SolidFraction(_) => vec![format!("{name}_solid_fraction")],
        Quantity::EnclosedVolume { .. } => vec![format!("{name}_volume_m3")],
        Quantity::Triaxial(_) => {
            TRIAXIAL_COLUMNS
                .iter()
                .map(|(c, unit)| {
                    if unit.is_empty() {
                        format!("{name}_{c}")
                    } else {
                        format!("{name}_{c}_{unit}")
                    }
                })
                .collect()
        }
    }
}

/// The whole CSV header: `time_s`, `step`, then the columns of every series in order.
pub fn header_columns(series: &[SeriesSpec]) -> Vec<String> {
    let mut columns = vec!["time_s".to_string(), "step".to_string()];
    columns.extend(series.iter().flat_map(series_columns));
    columns
}

/// Checks a series list against a simulation: names valid and distinct, particle and wall ids
/// in range, selections not empty, areas, volumes and regions valid, enclosed volumes
/// measurable (structure and walls exist, one wall per open end).
pub fn validate_series(series: &[SeriesSpec], sim: &Simulation) -> Result<(), OutputError> {
    let count = sim.model().particles.pos.len();
    for (i, spec) in series.iter().enumerate() {
        let name_ok = !spec.name.is_empty()
            && spec.name.chars().all(|c| c.is_ascii_alphanumeric() || "_-.".contains(c));
        if !name_ok {
            return Err(OutputError::Series {
                series: spec.name.clone(),
                problem: "the name must be non-empty and use only ASCII letters, digits, \
                          '_', '-' and '.'"
                    .into(),
            });
        }
        if series[..i].iter().any(|other| other.name == spec.name) {
            return Err(OutputError::Series {
                series: spec.name.clone(),
                problem: "two series have this name".into(),
            });
        }
        let ids: &[u32] = match &spec.quantity {
            Quantity::Position(id) | Quantity::Velocity(id) | Quantity::AngularVelocity(id) => {
                std::slice::from_ref(id)
            }
            Quantity::ForceOnParticles(ids) => ids,
            _ => &[],
        };
        if matches!(spec.quantity, Quantity::ForceOnParticles(_)) && ids.is_empty() {
            return Err(OutputError::Series {
                series: spec.name.clone(),
                problem: "the particle selection is empty".into(),
            });
        }
        if let Some(bad) = ids.iter().find(|&&id| id as usize >= count) {
            return Err(OutputError::Series {
                series: spec.name.clone(),
                problem: format!("particle {bad} does not exist (the model has {count})"),
            });
        }
        check_measure(&spec.quantity, sim)
            .map_err(|problem| OutputError::Series { series: spec.name.clone(), problem })?;
    }
    Ok(())
}

/// What is wrong with the wall, area, region or volume of a quantity, or what keeps an
/// enclosed volume from being measured, if anything.
fn check_measure(quantity: &Quantity, sim: &Simulation) -> Result<(), String> {
    let walls = sim.model().walls.len();
    let wall_exists = |w: u32| {
        if (w as usize) < walls {
            Ok(())
        } else {
            Err(format!("wall {w} does not exist (the model has {walls})"))
        }
    };
    let positive = |x: Real, what: &str| {
        if x > 0.0 && x.is_finite() {
            Ok(())
        } else {
            Err(format!("the {what} is {x}: expected a finite number > 0"))
        }
    };
    match quantity {
        Quantity::WallForce(w) => wall_exists(*w),
        Quantity::WallStress { wall, area } => {
            wall_exists(*wall)?;
            positive(*area, "area (m²)")
        }
        Quantity::Stress { region, volume } => {
            region.validate().map_err(|e| e.to_string())?;
            volume.map_or(Ok(()), |v| positive(v, "volume (m³)"))
        }
        Quantity::SolidFraction(region) => region.validate().map_err(|e| e.to_string()),
        Quantity::EnclosedVolume { structure, walls } => {
            enclosed_volume(sim, *structure, walls).map(|_| ())
        }
        Quantity::Triaxial(spec) => {
            if !(spec.height0 > 0.0 && spec.volume0 > 0.0) {
                return Err(format!(
                    "the sample's reference height {} m and volume {} m³ must be > 0",
                    spec.height0, spec.volume0
                ));
            }
            triaxial_state(sim, spec).map(|_| ())
        }
        _ => Ok(()),
    }
}

/// The volume enclosed by the PFacets of `structure`, closed by the current planes of
/// `walls` (m³), or what prevents measuring it.
fn enclosed_volume(sim: &Simulation, structure: u32, walls: &[u32]) -> Result<Real, String> {
    let model = sim.model();
    let planes = walls
        .iter()
        .map(|&w| match model.walls.get(w as usize) {
            Some(wall) => Ok(wall.plane()),
            None => Err(format!("wall {w} does not exist (the model has {})", model.walls.len())),
        })
        .collect::<Result<Vec<_>, _>>()?;
    flexdem_elements::structure_volume(model, structure, &planes).map_err(|e| e.to_string())
}

/// Pushes the three components of `v` onto `row`.
fn push_vec3(row: &mut Vec<Real>, v: Vec3) {
    row.extend_from_slice(&[v.x, v.y, v.z]);
}

/// Value of particle `id`'s entry in `values`, zero if it is missing (checked beforehand by
/// [`validate_series`]).
fn particle_value(values: &[Vec3], id: u32) -> Vec3 {
    values.get(id as usize).copied().unwrap_or_else(Vec3::zeros)
}

/// The values of one series at the simulation's current state, in the order of
/// [`series_columns`].
pub fn series_values(spec: &SeriesSpec, sim: &Simulation, row: &mut Vec<Real>) {
    let p = &sim.model().particles;
    match &spec.quantity {
        Quantity::Position(id) => push_vec3(row, particle_value(&p.pos, *id)),
        Quantity::Velocity(id) => push_vec3(row, particle_value(&p.vel, *id)),
        Quantity::AngularVelocity(id) => push_vec3(row, particle_value(&p.ang_vel, *id)),
        Quantity::Energy => row.extend_from_slice(&energy_values(sim)),
        Quantity::ForceOnParticles(ids) => {
            let forces = sim.forces();
            let total = ids.iter().fold(Vec3::zeros(), |sum, &i| sum + particle_value(forces, i));
            push_vec3(row, total);
        }
        Quantity::ContactCount => row.push(sim.contacts().len() as Real),
        Quantity::BrokenLinks => {
            let broken = sim
                .links()
                .state
                .iter()
                .filter(|s| s.status == flexdem_contact::LinkStatus::Broken)
                .count();
            row.push(broken as Real);
        }
        Quantity::WallForce(w) => {
            push_vec3(row, sim.wall_forces().get(*w as usize).copied().unwrap_or_default())
        }
        Quantity::WallStress { wall, area } => {
            let stress = match (
                sim.model().walls.get(*wall as usize),
                sim.wall_forces().get(*wall as usize),
            ) {
                (Some(w), Some(f)) => wall_normal_stress(w, f, *area),
                _ => 0.0,
            };
            row.push(stress);
        }
        Quantity::Stress { region, volume } => {
            row.extend_from_slice(&stress_values(sim, region, *volume))
        }
        Quantity::SolidFraction(region) => row.push(solid_fraction(&sim.model().particles, region)),
        Quantity::EnclosedVolume { structure, walls } => {
            row.push(enclosed_volume(sim, *structure, walls).unwrap_or(Real::NAN));
        }
        Quantity::Triaxial(spec) => match triaxial_state(sim, spec) {
            Ok(state) => row.extend_from_slice(&state.values(spec)),
            Err(_) => row.extend_from_slice(&[Real::NAN; TRIAXIAL_COLUMNS.len()]),
        },
    }
}

/// One CSV row: time, step, then every series' values.
pub fn row_values(series: &[SeriesSpec], sim: &Simulation) -> Vec<Real> {
    let mut row = vec![sim.time(), sim.steps() as Real];
    for spec in series {
        series_values(spec, sim, &mut row);
    }
    row
}
