//! The scene file as written: serde structs mirroring the TOML, every table with
//! `deny_unknown_fields` and every value that a later check may reject wrapped in
//! [`Spanned`] so that the error can point at its line. Names (`kind`, `material`, ...) are
//! kept as strings and resolved in `build.rs` with suggestions for misspellings. See
//! `docs/scene-reference.md` for the meaning of each key.

use serde::de::{self, Deserializer, Unexpected, Visitor};
use serde::Deserialize;
use serde_spanned::Spanned;
use std::collections::BTreeMap;
use std::fmt;

/// A value with its byte span in the file.
pub(crate) type S<T> = Spanned<T>;
/// Three numbers `[x, y, z]`.
pub(crate) type V3 = Arr<f64, 3>;

/// Exactly `N` values `[a, b, ...]`. serde's arrays read the first `N` values of a longer
/// TOML array and drop the rest without a word (`gravity = [0, 0, -9.81, 1]`); this refuses
/// any other length, with the error at the array.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Arr<T, const N: usize>(pub [T; N]);

impl<'de, T, const N: usize> Deserialize<'de> for Arr<T, N>
where
    T: Deserialize<'de> + Copy + Default,
{
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct ArrVisitor<T, const N: usize>(std::marker::PhantomData<T>);
        impl<'de, T, const N: usize> Visitor<'de> for ArrVisitor<T, N>
        where
            T: Deserialize<'de> + Copy + Default,
        {
            type Value = Arr<T, N>;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                write!(f, "an array of length {N}")
            }
            fn visit_seq<A: de::SeqAccess<'de>>(self, mut seq: A) -> Result<Arr<T, N>, A::Error> {
                let mut out = [T::default(); N];
                let mut len = 0;
                while len < N {
                    match seq.next_element::<T>()? {
                        Some(x) => out[len] = x,
                        None => return Err(de::Error::invalid_length(len, &self)),
                    }
                    len += 1;
                }
                while seq.next_element::<de::IgnoredAny>()?.is_some() {
                    len += 1;
                }
                if len == N {
                    Ok(Arr(out))
                } else {
                    Err(de::Error::invalid_length(len, &self))
                }
            }
        }
        d.deserialize_seq(ArrVisitor(std::marker::PhantomData))
    }
}

/// The whole file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct SceneFile {
    pub simulation: S<SimulationSpec>,
    #[serde(default)]
    pub materials: BTreeMap<S<String>, S<MaterialSpec>>,
    #[serde(default)]
    pub structures: Vec<S<StructureSpec>>,
    #[serde(default)]
    pub spheres: Vec<S<SpheresSpec>>,
    #[serde(default)]
    pub walls: Vec<S<WallSpec>>,
    #[serde(default)]
    pub boundary: Vec<S<BoundarySpec>>,
    #[serde(default)]
    pub loads: Vec<S<LoadSpec>>,
    #[serde(default)]
    pub pressures: Vec<S<PressureSpec>>,
    pub output: Option<S<OutputSpec>>,
}

/// `[simulation]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct SimulationSpec {
    pub dt: Option<S<Dt>>,
    pub safety: Option<S<f64>>,
    pub steps: Option<S<i64>>,
    pub duration: Option<S<f64>>,
    pub gravity: Option<S<V3>>,
    pub damping: Option<S<f64>>,
    pub threads: Option<S<i64>>,
    pub link_kinematics: Option<S<String>>,
    pub verlet_factor: Option<S<f64>>,
    pub time_step_interval: Option<S<i64>>,
    pub energy_tolerance: Option<S<Tolerance>>,
}

/// `energy_tolerance = "off"` or a fraction of the energy scale.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Tolerance {
    Off,
    Value(f64),
}

impl<'de> Deserialize<'de> for Tolerance {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct ToleranceVisitor;
        impl Visitor<'_> for ToleranceVisitor {
            type Value = Tolerance;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("\"off\" or a fraction of the energy scale (e.g. 0.05)")
            }
            fn visit_str<E: de::Error>(self, v: &str) -> Result<Tolerance, E> {
                if v == "off" {
                    Ok(Tolerance::Off)
                } else {
                    Err(E::invalid_value(Unexpected::Str(v), &self))
                }
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<Tolerance, E> {
                Ok(Tolerance::Value(v))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Tolerance, E> {
                Ok(Tolerance::Value(v as f64))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Tolerance, E> {
                Ok(Tolerance::Value(v as f64))
            }
        }
        d.deserialize_any(ToleranceVisitor)
    }
}

/// `dt = "auto"` or a number of seconds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Dt {
    Auto,
    Fixed(f64),
}

impl<'de> Deserialize<'de> for Dt {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct DtVisitor;
        impl Visitor<'_> for DtVisitor {
            type Value = Dt;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("\"auto\" or a time step in seconds (e.g. 1e-6)")
            }
            fn visit_str<E: de::Error>(self, v: &str) -> Result<Dt, E> {
                if v == "auto" {
                    Ok(Dt::Auto)
                } else {
                    Err(E::invalid_value(Unexpected::Str(v), &self))
                }
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<Dt, E> {
                Ok(Dt::Fixed(v))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Dt, E> {
                Ok(Dt::Fixed(v as f64))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Dt, E> {
                Ok(Dt::Fixed(v as f64))
            }
        }
        d.deserialize_any(DtVisitor)
    }
}

/// `[materials.<name>]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct MaterialSpec {
    pub young: S<f64>,
    pub poisson: S<f64>,
    pub density: S<f64>,
    pub friction_angle_deg: S<f64>,
    pub shear_ratio: Option<S<f64>>,
    pub tensile_strength: Option<S<f64>>,
    pub shear_strength: Option<S<f64>>,
    pub failure: Option<S<String>>,
    pub moments: Option<bool>,
    pub restitution: Option<S<f64>>,
    pub gamma_n: Option<S<f64>>,
    pub gamma_t: Option<S<f64>>,
}

/// `placement = { translate, rotate_deg | axis + angle_deg, scale }`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct PlacementSpec {
    pub translate: Option<S<V3>>,
    pub rotate_deg: Option<S<V3>>,
    pub axis: Option<S<V3>>,
    pub angle_deg: Option<S<f64>>,
    pub scale: Option<S<f64>>,
}

/// `[[structures]]`: the keys of every kind in one table; `build` checks that only the keys
/// of the chosen `kind` are given.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct StructureSpec {
    pub name: S<String>,
    pub kind: S<String>,
    pub material: S<String>,
    pub node_radius: S<f64>,
    pub mass: Option<S<String>>,
    pub mask: Option<S<i64>>,
    pub self_contact: Option<S<bool>>,
    pub velocity: Option<S<V3>>,
    pub placement: Option<S<PlacementSpec>>,
    // chain
    pub points: Option<S<Vec<V3>>>,
    pub start: Option<S<V3>>,
    pub end: Option<S<V3>>,
    pub segments: Option<S<i64>>,
    // helix, disc, tube, sphere shell
    pub center: Option<S<V3>>,
    pub radius: Option<S<f64>>,
    pub pitch: Option<S<f64>>,
    pub turns: Option<S<f64>>,
    pub segments_per_turn: Option<S<i64>>,
    // net, membrane
    pub origin: Option<S<V3>>,
    pub u_dir: Option<S<V3>>,
    pub v_dir: Option<S<V3>>,
    pub size: Option<S<Arr<f64, 2>>>,
    pub cells: Option<S<Arr<i64, 2>>>,
    pub diagonals: Option<S<bool>>,
    // disc
    pub normal: Option<S<V3>>,
    pub rings: Option<S<i64>>,
    // tube
    pub axis: Option<S<V3>>,
    pub length: Option<S<f64>>,
    pub around: Option<S<i64>>,
    pub along: Option<S<i64>>,
    // sphere shell
    pub base: Option<S<String>>,
    pub subdivisions: Option<S<i64>>,
    // mesh
    pub file: Option<S<String>>,
    pub merge_tolerance: Option<S<f64>>,
}

/// An axis-aligned box `{ min = [..], max = [..] }`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct BoxSpec {
    pub min: S<V3>,
    pub max: S<V3>,
}

/// `[[spheres]]`: one sphere, a lattice, a random or dense packing, or spheres from a file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct SpheresSpec {
    pub name: Option<S<String>>,
    pub kind: S<String>,
    pub material: S<String>,
    pub radius: Option<S<f64>>,
    pub radius_range: Option<S<Arr<f64, 2>>>,
    pub center: Option<S<V3>>,
    #[serde(rename = "box")]
    pub region: Option<S<BoxSpec>>,
    pub spacing: Option<S<f64>>,
    pub count: Option<S<i64>>,
    pub seed: Option<S<i64>>,
    // dense
    pub cylinder: Option<S<CylinderSpec>>,
    pub inside: Option<S<String>>,
    pub solid_fraction: Option<S<f64>>,
    pub tolerance: Option<S<f64>>,
    pub max_iterations: Option<S<i64>>,
    // file
    pub file: Option<S<String>>,
    pub velocity: Option<S<V3>>,
    pub angular_velocity: Option<S<V3>>,
    pub mask: Option<S<i64>>,
}

/// `[[walls]]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct WallSpec {
    pub point: S<V3>,
    pub normal: S<V3>,
    pub material: S<String>,
    pub velocity: Option<S<V3>>,
    pub servo: Option<S<ServoSpec>>,
    pub mask: Option<S<i64>>,
}

/// `area_of = { membrane, platens }` or `area_of = { walls = [[a, a'], [b, b']] }`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct AreaOfSpec {
    pub membrane: Option<S<String>>,
    pub platens: Option<S<Vec<i64>>>,
    pub walls: Option<S<Vec<Vec<i64>>>>,
}

/// `servo = { stress, area, gain, max_speed, until, velocity_after }` of a wall.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct ServoSpec {
    pub stress: S<f64>,
    pub area: Option<S<f64>>,
    pub area_of: Option<S<AreaOfSpec>>,
    pub gain: Option<S<f64>>,
    pub max_speed: S<f64>,
    pub until: Option<S<f64>>,
    pub velocity_after: Option<S<V3>>,
}

/// A plane `{ point, normal, tolerance }`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct PlaneSpec {
    pub point: S<V3>,
    pub normal: S<V3>,
    pub tolerance: Option<S<f64>>,
}

/// `select = { ... }`: which particles a boundary condition, load or output applies to.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct SelectSpec {
    pub structure: Option<S<String>>,
    pub spheres: Option<S<String>>,
    pub ids: Option<S<Vec<i64>>>,
    pub side: Option<S<String>>,
    #[serde(rename = "box")]
    pub region: Option<S<BoxSpec>>,
    pub plane: Option<S<PlaneSpec>>,
}

/// `[[boundary]]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct BoundarySpec {
    pub select: S<SelectSpec>,
    pub block: Option<S<String>>,
    pub velocity: Option<S<V3>>,
    pub angular_velocity: Option<S<V3>>,
}

/// `ramp = { start, duration }`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RampSpec {
    pub start: S<f64>,
    pub duration: S<f64>,
}

/// `[[loads]]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct LoadSpec {
    pub select: S<SelectSpec>,
    pub force: Option<S<V3>>,
    pub total_force: Option<S<V3>>,
    pub moment: Option<S<V3>>,
    pub ramp: Option<S<RampSpec>>,
}

/// `[[pressures]]`: a pressure on the PFacets of a structure (`structure`) or on those whose
/// three nodes a selection picks (`select`).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct PressureSpec {
    pub structure: Option<S<String>>,
    pub select: Option<S<SelectSpec>>,
    pub pressure: S<f64>,
    pub flip: Option<bool>,
    pub ramp: Option<S<RampSpec>>,
}

/// `[output]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct OutputSpec {
    pub directory: Option<S<String>>,
    pub vtk_every: Option<S<i64>>,
    pub series_every: Option<S<i64>>,
    pub plot: Option<bool>,
    #[serde(default)]
    pub series: Vec<S<SeriesSpecToml>>,
}

/// `[[output.series]]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct SeriesSpecToml {
    pub name: S<String>,
    pub quantity: S<String>,
    pub of: Option<S<SelectSpec>>,
    // volume: indices of the [[walls]] closing the structure's open ends; triaxial: the
    // platens
    pub walls: Option<S<Vec<i64>>>,
    // triaxial between rigid walls: the four lateral walls
    pub lateral_walls: Option<S<Vec<i64>>>,
    // wall_force, wall_stress
    pub wall: Option<S<i64>>,
    pub area: Option<S<f64>>,
    // stress, solid_fraction
    #[serde(rename = "box")]
    pub region: Option<S<BoxSpec>>,
    pub cylinder: Option<S<CylinderSpec>>,
    pub volume: Option<S<f64>>,
}

/// A solid cylinder `{ start, axis, radius, length }`, placed as a `tube`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct CylinderSpec {
    pub start: S<V3>,
    pub axis: S<V3>,
    pub radius: S<f64>,
    pub length: S<f64>,
}
