//! The `[[output.series]]` quantities of walls and samples: `wall_force`, `wall_stress`
//! (keys `wall`, `area`), `stress` and `solid_fraction` (keys `box` or `cylinder`, and
//! `volume` for `stress`).

use crate::builder::Builder;
use crate::error::SceneError;
use crate::schema::{SeriesSpecToml, S};
use flexdem_integrate::{Region, WallControl};
use flexdem_output::Quantity;

/// The series quantities of walls and samples.
pub(crate) const MEASURES: [&str; 4] = ["wall_force", "wall_stress", "stress", "solid_fraction"];

/// The keys of the wall and sample quantities, with the quantities that take each.
const MEASURE_KEYS: [(&str, &[&str]); 5] = [
    ("wall", &["wall_force", "wall_stress"]),
    ("area", &["wall_stress"]),
    ("box", &["stress", "solid_fraction"]),
    ("cylinder", &["stress", "solid_fraction"]),
    ("volume", &["stress"]),
];

impl Builder<'_> {
    /// Refuses the keys of the wall and sample quantities given to a quantity that does not
    /// take them, at the key.
    pub(crate) fn check_measure_keys(&self, sp: &SeriesSpecToml) -> Result<(), SceneError> {
        let q = sp.quantity.get_ref().as_str();
        let given = [
            sp.wall.as_ref().map(|v| v.span()),
            sp.area.as_ref().map(|v| v.span()),
            sp.region.as_ref().map(|v| v.span()),
            sp.cylinder.as_ref().map(|v| v.span()),
            sp.volume.as_ref().map(|v| v.span()),
        ];
        for ((key, takers), span) in MEASURE_KEYS.iter().zip(given) {
            if let (Some(span), false) = (span, takers.contains(&q)) {
                return Err(self.ctx.at(
                    span,
                    &format!("output.series.{key}"),
                    format!(
                        "quantity = \"{q}\" does not take `{key}` (only {})",
                        takers.join(" and ")
                    ),
                ));
            }
        }
        Ok(())
    }

    /// The quantity `q` (one of [`MEASURES`]) of the series `s`.
    pub(crate) fn measure(&self, q: &str, s: &S<SeriesSpecToml>) -> Result<Quantity, SceneError> {
        let sp = s.get_ref();
        Ok(match q {
            "wall_force" => Quantity::WallForce(self.series_wall(s)?),
            "wall_stress" => {
                let wall = self.series_wall(s)?;
                Quantity::WallStress { wall, area: self.series_area(s, wall)? }
            }
            "stress" => {
                let volume = sp
                    .volume
                    .as_ref()
                    .map(|v| self.ctx.positive(v, "output.series.volume", "m³"))
                    .transpose()?;
                Quantity::Stress { region: self.series_region(s)?, volume }
            }
            _ => Quantity::SolidFraction(self.series_region(s)?),
        })
    }

    /// The wall of a series: `wall`, a wall index (0-based, in file order).
    fn series_wall(&self, s: &S<SeriesSpecToml>) -> Result<u32, SceneError> {
        let sp = s.get_ref();
        let q = sp.quantity.get_ref();
        let Some(w) = &sp.wall else {
            return Err(self.ctx.missing(
                s.span(),
                "output.series.wall",
                &format!("quantity = \"{q}\" needs `wall = N`, the index of a [[walls]] entry (0 for the first)"),
            ));
        };
        let walls = self.model.walls.len();
        let n = *w.get_ref();
        match u32::try_from(n) {
            Ok(id) if (id as usize) < walls => Ok(id),
            _ if walls == 0 => Err(self.ctx.at(
                w.span(),
                "output.series.wall",
                format!("is {n}, but the scene has no [[walls]]"),
            )),
            _ => Err(self.ctx.at(
                w.span(),
                "output.series.wall",
                format!(
                    "is {n}: expected the index of a [[walls]] entry, from 0 to {} (in file order)",
                    walls - 1
                ),
            )),
        }
    }

    /// The area of a wall stress: `area`, or the area of the wall's servo.
    fn series_area(&self, s: &S<SeriesSpecToml>, wall: u32) -> Result<f64, SceneError> {
        match (&s.get_ref().area, self.wall_controls.get(wall as usize)) {
            (Some(a), _) => self.ctx.positive(a, "output.series.area", "m²"),
            (None, Some(WallControl::Stress(servo))) => Ok(servo.area),
            (None, _) => Err(self.ctx.missing(
                s.span(),
                "output.series.area",
                &format!("wall {wall} has no servo to take the area from: give `area` (m²)"),
            )),
        }
    }

    /// The region of a series: `box = { min, max }` or `cylinder = { start, axis, radius,
    /// length }`, one of the two.
    fn series_region(&self, s: &S<SeriesSpecToml>) -> Result<Region, SceneError> {
        let ctx = self.ctx;
        let sp = s.get_ref();
        let key = |k: &str| format!("output.series.{k}");
        let region = match (&sp.region, &sp.cylinder) {
            (Some(b), None) => {
                let min = ctx.vec3(&b.get_ref().min, &key("box.min"), "m")?;
                let max = ctx.vec3(&b.get_ref().max, &key("box.max"), "m")?;
                if (0..3).any(|k| min[k] >= max[k]) {
                    return Err(ctx.at(
                        b.span(),
                        &key("box"),
                        format!(
                            "min {:?} is not below max {:?} on every axis: the box has no volume",
                            <[f64; 3]>::from(min),
                            <[f64; 3]>::from(max)
                        ),
                    ));
                }
                Region::Box { min, max }
            }
            (None, Some(c)) => {
                let c = c.get_ref();
                Region::Cylinder {
                    start: ctx.vec3(&c.start, &key("cylinder.start"), "m")?,
                    axis: ctx.direction(&c.axis, &key("cylinder.axis"))?,
                    radius: ctx.positive(&c.radius, &key("cylinder.radius"), "m")?,
                    length: ctx.positive(&c.length, &key("cylinder.length"), "m")?,
                }
            }
            (Some(_), Some(c)) => {
                return Err(ctx.at(
                    c.span(),
                    &key("cylinder"),
                    "conflicts with `box`: give one region, `box` or `cylinder`",
                ))
            }
            (None, None) => {
                return Err(ctx.missing(
                    s.span(),
                    &key("box"),
                    &format!(
                        "quantity = \"{}\" needs a region: `box = {{ min, max }}` or `cylinder = {{ start, axis, radius, length }}`",
                        sp.quantity.get_ref()
                    ),
                ))
            }
        };
        region.validate().map_err(|e| ctx.at(s.span(), &key("box"), e.to_string()))?;
        Ok(region)
    }
}
