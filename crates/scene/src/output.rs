//! `[output]` → [`OutputSettings`]: folder, frequencies and the CSV series.

use crate::builder::Builder;
use crate::error::{unknown_name, SceneError};
use crate::output_measures::MEASURES;
use crate::schema::{OutputSpec, SelectSpec, SeriesSpecToml, S};
use flexdem_elements::{structure_volume, VolumeError};
use flexdem_output::{OutputSettings, Quantity, SeriesSpec};

/// The series quantities of particles, of the whole simulation and of a structure's enclosed
/// volume (those of walls and samples are [`MEASURES`]).
const QUANTITIES: [&str; 9] = [
    "position",
    "velocity",
    "angular_velocity",
    "force",
    "energy",
    "contacts",
    "broken_links",
    "volume",
    "triaxial",
];

impl Builder<'_> {
    /// Reads the `[output]` table.
    pub(crate) fn output(&self, spec: &S<OutputSpec>) -> Result<OutputSettings, SceneError> {
        let ctx = self.ctx;
        let o = spec.get_ref();
        let directory = match &o.directory {
            Some(d) if d.get_ref().trim().is_empty() => {
                return Err(ctx.at(
                    d.span(),
                    "output.directory",
                    "is empty: expected a folder name",
                ))
            }
            Some(d) => self.dir.join(d.get_ref()),
            None => self.dir.join("output"),
        };
        let every = |v: &Option<S<i64>>, k: &str| -> Result<Option<u64>, SceneError> {
            v.as_ref()
                .map(|n| ctx.count(n, &format!("output.{k}"), 1).map(|n| n as u64))
                .transpose()
        };
        let vtk_every = every(&o.vtk_every, "vtk_every")?;
        let series_every = every(&o.series_every, "series_every")?;
        let mut series: Vec<SeriesSpec> = Vec::with_capacity(o.series.len());
        for s in &o.series {
            let sp = s.get_ref();
            let name = sp.name.get_ref();
            let ok = !name.is_empty()
                && name.chars().all(|c| c.is_ascii_alphanumeric() || "_-.".contains(c));
            if !ok {
                return Err(ctx.at(sp.name.span(), "output.series.name", format!("`{name}` is not a valid series name: use ASCII letters, digits, '_', '-' and '.' only")));
            }
            if series.iter().any(|other| other.name == *name) {
                return Err(ctx.at(
                    sp.name.span(),
                    "output.series.name",
                    format!("two series are named `{name}`: names must be unique"),
                ));
            }
            let q = sp.quantity.get_ref().as_str();
            if !QUANTITIES.contains(&q) && !MEASURES.contains(&q) {
                let known: Vec<&str> = QUANTITIES.iter().chain(&MEASURES).copied().collect();
                return Err(ctx.at(
                    sp.quantity.span(),
                    "output.series.quantity",
                    unknown_name("quantity", q, &known),
                ));
            }
            self.check_measure_keys(sp)?;
            if q == "triaxial" {
                let quantity = self.triaxial_quantity(s)?;
                series.push(SeriesSpec { name: name.clone(), quantity });
                continue;
            }
            if let Some(w) = &sp.lateral_walls {
                return Err(ctx.at(
                    w.span(),
                    "output.series.lateral_walls",
                    format!("applies to quantity = \"triaxial\" only, not \"{q}\": remove it"),
                ));
            }
            if q == "volume" {
                let quantity = self.volume_quantity(s)?;
                series.push(SeriesSpec { name: name.clone(), quantity });
                continue;
            }
            if let Some(w) = &sp.walls {
                return Err(ctx.at(
                    w.span(),
                    "output.series.walls",
                    format!(
                    "applies to quantity = \"volume\" or \"triaxial\" only, not \"{q}\": remove it"
                ),
                ));
            }
            let needs_selection =
                matches!(q, "position" | "velocity" | "angular_velocity" | "force");
            let ids = match (&sp.of, needs_selection) {
                (Some(of), true) => self.select(of, "output.series.of")?,
                (None, true) => {
                    return Err(ctx.missing(
                        s.span(),
                        "output.series.of",
                        &format!("quantity = \"{q}\" needs `of = {{ ... }}`, a selection"),
                    ))
                }
                (Some(of), false) => {
                    return Err(ctx.at(
                        of.span(),
                        "output.series.of",
                        format!("quantity = \"{q}\" is global: remove `of`"),
                    ))
                }
                (None, false) => Vec::new(),
            };
            let one = || -> Result<u32, SceneError> {
                match ids.as_slice() {
                    [id] => Ok(*id),
                    _ => Err(ctx.at(
                        sp.of.as_ref().map_or(s.span(), |o| o.span()),
                        "output.series.of",
                        format!("quantity = \"{q}\" needs exactly one particle; this selection has {}: narrow it (e.g. `ids = [..]` or `side = \"end\"`)", ids.len()),
                    )),
                }
            };
            let quantity = match q {
                _ if MEASURES.contains(&q) => self.measure(q, s)?,
                "position" => Quantity::Position(one()?),
                "velocity" => Quantity::Velocity(one()?),
                "angular_velocity" => Quantity::AngularVelocity(one()?),
                "force" => Quantity::ForceOnParticles(ids.clone()),
                "energy" => Quantity::Energy,
                "contacts" => Quantity::ContactCount,
                _ => Quantity::BrokenLinks,
            };
            series.push(SeriesSpec { name: name.clone(), quantity });
        }
        if !series.is_empty() && series_every.is_none() {
            return Err(ctx.missing(
                spec.span(),
                "output.series_every",
                "series are defined: give `series_every = N` (steps between CSV rows)",
            ));
        }
        if o.plot == Some(true) && series.is_empty() {
            return Err(ctx.at(
                spec.span(),
                "output.plot",
                "is true but there is nothing to plot: add `[[output.series]]` (with \
                 `series_every`), or remove `plot`",
            ));
        }
        Ok(OutputSettings {
            directory,
            vtk_every,
            series_every,
            series,
            plot: o.plot.unwrap_or(false),
        })
    }
}

impl Builder<'_> {
    /// The structure name of `of = { structure = "name" }`, which must have no other key
    /// (`usage` says what is expected otherwise).
    pub(crate) fn structure_only<'s>(
        &self,
        of: &'s S<SelectSpec>,
        usage: &str,
    ) -> Result<&'s S<String>, SceneError> {
        let sel = of.get_ref();
        let others = sel.spheres.is_some()
            || sel.ids.is_some()
            || sel.side.is_some()
            || sel.region.is_some()
            || sel.plane.is_some();
        match &sel.structure {
            Some(name) if !others => Ok(name),
            _ => Err(self.ctx.at(of.span(), "output.series.of", usage)),
        }
    }

    /// `quantity = "volume"`: the volume enclosed by the PFacets of the structure named in
    /// `of = { structure = "name" }`, its open ends closed by the `[[walls]]` of `walls`
    /// (indices), checked now on the scene as built.
    fn volume_quantity(&self, s: &S<SeriesSpecToml>) -> Result<Quantity, SceneError> {
        let ctx = self.ctx;
        let sp = s.get_ref();
        let usage = "quantity = \"volume\" needs `of = { structure = \"name\" }` (the volume \
                     its PFacets enclose) and no other selection key";
        let Some(of) = &sp.of else {
            return Err(ctx.missing(s.span(), "output.series.of", usage));
        };
        let name = self.structure_only(of, usage)?;
        let structure = self.named_structure(name, "output.series.of.structure")?.id;
        let walls = match &sp.walls {
            Some(list) => self.wall_indices(list, "output.series.walls", None, "")?,
            None => Vec::new(),
        };
        let planes: Vec<_> = walls.iter().map(|&w| self.model.walls[w as usize].plane()).collect();
        if let Err(e) = structure_volume(&self.model, structure, &planes) {
            let hint = match e {
                VolumeError::NotClosed { .. } => {
                    " (`walls = [i, j]`: indices of [[walls]] in file order)"
                }
                _ => "",
            };
            let (span, key) = match &sp.walls {
                Some(w) => (w.span(), "output.series.walls"),
                None => (of.span(), "output.series.of"),
            };
            let message = match e {
                VolumeError::NoPFacets { .. } => format!("{e}"),
                _ => format!("structure `{}`: {e}{hint}", name.get_ref()),
            };
            return Err(ctx.at(span, key, message));
        }
        Ok(Quantity::EnclosedVolume { structure, walls })
    }
}
