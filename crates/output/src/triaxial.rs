//! What a triaxial test measures: the sample's height and volume, the axial and confining
//! stresses, and from them the strains and the stress invariants p and q.
//!
//! Sign convention of soil mechanics: compression and contraction positive.
//!
//! - height `H = (x_top − x_bottom)·n_bottom`, the distance between the platens' planes;
//! - volume `V`: for a membrane, the volume enclosed by its inner surface: the volume of its
//!   PFacets' mid-surface closed by the platens' planes less the PFacets' radius times their
//!   area (`flexdem_integrate::membrane_sample_volume`); between rigid walls, `H·L₁·L₂` (L the distances between the opposite lateral
//!   walls);
//! - axial strain `εa = (H₀ − H)/H₀`, volumetric strain `εv = (V₀ − V)/V₀`, from the height
//!   and volume at the start of the run (so they include the consolidation's strains);
//! - axial stress `σa = (F_bottom + F_top)/(2A)`: the mean normal force on the platens over
//!   the sample's current mean cross-section `A = V/H` (membrane) or `L₁·L₂` (walls);
//! - confining stress `σr`: the pressure on the membrane's PFacets at time t (its ramp
//!   applied), or the mean normal stress of the four lateral walls (each force over its
//!   current face, `H·L`);
//! - mean stress `p = (σa + 2σr)/3`, deviator stress `q = σa − σr`.

use flexdem_elements::Model;
use flexdem_geom::{Real, Vec3};
use flexdem_integrate::{membrane_sample_volume, normal_force, wall_gap, Simulation};
use serde::{Deserialize, Serialize};

/// How a triaxial sample is confined laterally.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum Lateral {
    /// A PFacet membrane (a structure) closed by the platens, under a pressure load.
    Membrane {
        /// The membrane's structure id.
        structure: u32,
    },
    /// Four rigid walls: two pairs of opposite walls (`[a, a', b, b']`).
    Walls([u32; 4]),
}

/// A triaxial test's boundaries and the reference of its strains.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TriaxialSpec {
    /// Bottom and top platens (wall ids), their normals facing each other.
    pub platens: [u32; 2],
    /// The lateral boundary.
    pub lateral: Lateral,
    /// Height at the start (m), the reference of the axial strain.
    pub height0: Real,
    /// Volume at the start (m³), the reference of the volumetric strain.
    pub volume0: Real,
}

/// Names and units of the columns of a triaxial series, in the order of
/// [`TriaxialState::values`].
pub const TRIAXIAL_COLUMNS: [(&str, &str); 8] = [
    ("axial_strain", ""),
    ("volumetric_strain", ""),
    ("axial_stress", "Pa"),
    ("confining_stress", "Pa"),
    ("mean_stress", "Pa"),
    ("deviator_stress", "Pa"),
    ("height", "m"),
    ("volume", "m3"),
];

/// A triaxial sample's state at one instant.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TriaxialState {
    /// Height (m).
    pub height: Real,
    /// Volume (m³).
    pub volume: Real,
    /// Axial stress σa (Pa).
    pub axial_stress: Real,
    /// Confining stress σr (Pa).
    pub confining_stress: Real,
}

impl TriaxialState {
    /// Mean stress `p = (σa + 2σr)/3` (Pa).
    pub fn mean_stress(&self) -> Real {
        (self.axial_stress + 2.0 * self.confining_stress) / 3.0
    }

    /// Deviator stress `q = σa − σr` (Pa).
    pub fn deviator_stress(&self) -> Real {
        self.axial_stress - self.confining_stress
    }

    /// The columns of [`TRIAXIAL_COLUMNS`], strains against `spec`'s reference.
    pub fn values(&self, spec: &TriaxialSpec) -> [Real; 8] {
        [
            (spec.height0 - self.height) / spec.height0,
            (spec.volume0 - self.volume) / spec.volume0,
            self.axial_stress,
            self.confining_stress,
            self.mean_stress(),
            self.deviator_stress(),
            self.height,
            self.volume,
        ]
    }
}

/// The size of a triaxial sample.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SampleGeometry {
    /// Height (m).
    pub height: Real,
    /// Volume (m³).
    pub volume: Real,
    /// The distances `(L₁, L₂)` between the opposite lateral walls (rigid walls only).
    pub spans: Option<(Real, Real)>,
}

/// The sample's height and volume in `model` (see the module's doc), with the lateral
/// walls' spans for rigid walls.
pub fn triaxial_geometry(
    model: &Model,
    spec_platens: [u32; 2],
    lateral: &Lateral,
) -> Result<SampleGeometry, String> {
    let height = wall_gap(model, spec_platens[0], spec_platens[1])?;
    if !(height > 0.0) {
        return Err(format!(
            "the platens (walls {} and {}) are {height} m apart: they must face each other, \
             the first one's normal pointing to the second",
            spec_platens[0], spec_platens[1]
        ));
    }
    match lateral {
        Lateral::Membrane { structure } => {
            let volume = membrane_sample_volume(model, *structure, spec_platens)?;
            Ok(SampleGeometry { height, volume, spans: None })
        }
        Lateral::Walls([a, a2, b, b2]) => {
            let (l1, l2) = (wall_gap(model, *a, *a2)?, wall_gap(model, *b, *b2)?);
            if !(l1 > 0.0 && l2 > 0.0) {
                return Err(format!(
                    "the lateral walls {a}–{a2} and {b}–{b2} are {l1} m and {l2} m apart: each \
                     pair must face each other"
                ));
            }
            Ok(SampleGeometry { height, volume: height * l1 * l2, spans: Some((l1, l2)) })
        }
    }
}

/// The state of the triaxial sample of `spec` in `sim` (see the module's doc).
pub fn triaxial_state(sim: &Simulation, spec: &TriaxialSpec) -> Result<TriaxialState, String> {
    let model = sim.model();
    let SampleGeometry { height, volume, spans } =
        triaxial_geometry(model, spec.platens, &spec.lateral)?;
    let forces = sim.wall_forces();
    let normal = |w: u32| -> Real {
        let wall = &model.walls[w as usize];
        normal_force(wall, &forces.get(w as usize).copied().unwrap_or_else(Vec3::zeros))
    };
    let platen_force = 0.5 * (normal(spec.platens[0]) + normal(spec.platens[1]));
    let (area, confining) = match (&spec.lateral, spans) {
        (Lateral::Walls([a, a2, b, b2]), Some((l1, l2))) => {
            // walls a, a' span the b-direction (L₂) over the height, and conversely
            let sides = (normal(*a) + normal(*a2)) / (height * l2)
                + (normal(*b) + normal(*b2)) / (height * l1);
            (l1 * l2, 0.25 * sides)
        }
        (Lateral::Membrane { structure }, _) => {
            (volume / height, membrane_pressure(sim, *structure))
        }
        (Lateral::Walls(_), None) => return Err("rigid walls without their spans".into()),
    };
    Ok(TriaxialState {
        height,
        volume,
        axial_stress: platen_force / area,
        confining_stress: confining,
    })
}

/// The pressure on the PFacets of `structure` at the current time (Pa, positive when it
/// pushes them against their normals, inward on a builder's tube): the sum of the pressure
/// loads whose PFacets all belong to the structure, each with its ramp.
fn membrane_pressure(sim: &Simulation, structure: u32) -> Real {
    let Some(st) = sim.model().structures.get(structure as usize) else { return 0.0 };
    let t = sim.time();
    sim.pressures()
        .iter()
        .filter(|p| !p.pfacets.is_empty() && p.pfacets.iter().all(|f| st.pfacets.contains(f)))
        .map(|p| {
            let inward = if p.flip { 1.0 } else { -1.0 };
            inward * p.pressure * p.ramp.factor(t)
        })
        .sum()
}
