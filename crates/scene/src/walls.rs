//! `[[walls]]` → the model's walls and how each moves: a constant `velocity` (strain
//! control) or a `servo` holding a normal stress.

use crate::builder::Builder;
use crate::error::SceneError;
use crate::schema::{ServoSpec, WallSpec, S};
use flexdem_geom::Vec3;
use flexdem_integrate::{StressControl, WallControl};

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
            (Some(servo), None) => WallControl::Stress(self.servo(servo)?),
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

    /// The servo of `servo = { stress, area, gain, max_speed }`.
    fn servo(&self, spec: &S<ServoSpec>) -> Result<StressControl, SceneError> {
        let ctx = self.ctx;
        let s = spec.get_ref();
        let control = StressControl {
            target: ctx.non_negative(&s.stress, "walls.servo.stress", "Pa, compression")?,
            area: ctx.positive(&s.area, "walls.servo.area", "m²")?,
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
