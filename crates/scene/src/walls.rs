//! `[[walls]]` → the model's walls and how each moves: a constant `velocity` (strain
//! control) or a `servo` holding a normal stress.

use crate::builder::Builder;
use crate::error::SceneError;
use crate::schema::{AreaOfSpec, ServoSpec, WallSpec, S};
use flexdem_geom::Vec3;
use flexdem_integrate::{SampleSection, StressControl, WallControl};

impl Builder<'_> {
    /// Adds the wall of `spec` and its control.
    pub(crate) fn add_wall(&mut self, spec: &S<WallSpec>) -> Result<(), SceneError> {
        let ctx = self.ctx;
        let w = spec.get_ref();
        let point = ctx.vec3(&w.point, "walls.point", "m")?;
        let normal = ctx.direction(&w.normal, "walls.normal")?;
        let material = self.material(&w.material, "walls.material")?;
        let velocity = w
            .velocity
            .as_ref()
            .map_or(Ok(Vec3::zeros()), |v| ctx.vec3(v, "walls.velocity", "m/s"))?;
        let control = match (&w.servo, &w.velocity) {
            (None, _) => WallControl::Velocity,
            (Some(servo), None) => self.servo_control(servo)?,
            (Some(servo), Some(_)) => {
                return Err(ctx.at(
                    servo.span(),
                    "walls.servo",
                    "conflicts with `velocity`: a wall moves with a constant `velocity` or \
                     under a `servo`, not both",
                ))
            }
        };
        let mask = ctx.mask(w.mask.as_ref(), "walls.mask")?;
        let id = self
            .model
            .add_wall(point, normal, material)
            .map_err(|e| ctx.at(spec.span(), "walls", e.to_string()))? as usize;
        self.model.walls[id].velocity = velocity;
        self.model.walls[id].mask = mask;
        self.wall_controls.push(control);
        Ok(())
    }

    /// `servo = { ..., until, velocity_after }`: the servo alone, or until a time and then a
    /// constant velocity (`velocity_after`, default at rest).
    fn servo_control(&mut self, spec: &S<ServoSpec>) -> Result<WallControl, SceneError> {
        let ctx = self.ctx;
        let s = spec.get_ref();
        let servo = self.servo(spec)?;
        match (&s.until, &s.velocity_after) {
            (None, None) => Ok(WallControl::Stress(servo)),
            (None, Some(v)) => Err(ctx.at(
                v.span(),
                "walls.servo.velocity_after",
                "needs `until` (the time the servo ends and this velocity starts)",
            )),
            (Some(until), after) => Ok(WallControl::StressUntil {
                servo,
                until: ctx.non_negative(until, "walls.servo.until", "s")?,
                then: after.as_ref().map_or(Ok(Vec3::zeros()), |v| {
                    ctx.vec3(v, "walls.servo.velocity_after", "m/s")
                })?,
            }),
        }
    }

    /// `area_of = { membrane = "name", platens = [i, j] }` or `area_of = { walls = [[a, a'],
    /// [b, b']] }` (wall indices checked by [`Builder::check_sections`]).
    fn sample_section(&self, spec: &S<AreaOfSpec>) -> Result<SampleSection, SceneError> {
        let ctx = self.ctx;
        let a = spec.get_ref();
        let usage = "expected `area_of = { membrane = \"name\", platens = [bottom, top] }` or \
                     `area_of = { walls = [[a, a'], [b, b']] }` (indices of [[walls]])";
        let index = |v: i64| u32::try_from(v).ok();
        match (&a.membrane, &a.platens, &a.walls) {
            (Some(name), Some(platens), None) => {
                let structure = self.named_structure(name, "walls.servo.area_of.membrane")?.id;
                match platens.get_ref().as_slice() {
                    &[p, q] if index(p).is_some() && index(q).is_some() => {
                        Ok(SampleSection::Membrane { structure, platens: [p as u32, q as u32] })
                    }
                    _ => Err(ctx.at(platens.span(), "walls.servo.area_of.platens", usage)),
                }
            }
            (None, None, Some(walls)) => match walls.get_ref().as_slice() {
                [a, b]
                    if a.len() == 2
                        && b.len() == 2
                        && a.iter().chain(b).all(|&w| index(w).is_some()) =>
                {
                    Ok(SampleSection::Rectangle {
                        a: [a[0] as u32, a[1] as u32],
                        b: [b[0] as u32, b[1] as u32],
                    })
                }
                _ => Err(ctx.at(walls.span(), "walls.servo.area_of.walls", usage)),
            },
            _ => Err(ctx.at(spec.span(), "walls.servo.area_of", usage)),
        }
    }

    /// Measures the section of every servo that follows one, now that every wall is built:
    /// an error names the servo; a servo without `area` starts from the area measured.
    pub(crate) fn check_sections(&mut self) -> Result<(), SceneError> {
        for (w, span, fill) in std::mem::take(&mut self.sections) {
            let (WallControl::Stress(servo) | WallControl::StressUntil { servo, .. }) =
                &mut self.wall_controls[w]
            else {
                continue;
            };
            let Some(section) = servo.section else { continue };
            match section.area(&self.model) {
                Ok(area) if area > 0.0 && area.is_finite() => {
                    if fill {
                        servo.area = area;
                    }
                }
                Ok(area) => {
                    return Err(self.ctx.at(
                        span,
                        "walls.servo.area_of",
                        format!("the section measures {area} m²: the walls must face each other"),
                    ))
                }
                Err(e) => return Err(self.ctx.at(span, "walls.servo.area_of", e)),
            }
        }
        Ok(())
    }

    /// The servo of `servo = { stress, area, gain, max_speed }`.
    fn servo(&mut self, spec: &S<ServoSpec>) -> Result<StressControl, SceneError> {
        let ctx = self.ctx;
        let s = spec.get_ref();
        let section = s.area_of.as_ref().map(|a| self.sample_section(a)).transpose()?;
        let area = match (&s.area, section) {
            (Some(a), _) => ctx.positive(a, "walls.servo.area", "m²")?,
            // measured once every wall is built (`Builder::check_sections`)
            (None, Some(_)) => 1.0,
            (None, None) => {
                return Err(ctx.missing(
                    spec.span(),
                    "walls.servo.area",
                    "a servo needs `area` (m²) or `area_of` (the sample's section it follows)",
                ))
            }
        };
        if section.is_some() {
            self.sections.push((self.model.walls.len(), spec.span(), s.area.is_none()));
        }
        let control = StressControl {
            target: ctx.non_negative(&s.stress, "walls.servo.stress", "Pa, compression")?,
            area,
            section,
            gain: s
                .gain
                .as_ref()
                .map(|g| {
                    ctx.positive(g, "walls.servo.gain", "m/s per N; omit it for the automatic gain")
                })
                .transpose()?,
            max_speed: ctx.positive(&s.max_speed, "walls.servo.max_speed", "m/s")?,
        };
        control.validate().map_err(|e| ctx.at(spec.span(), "walls.servo", e.to_string()))?;
        Ok(control)
    }
}
