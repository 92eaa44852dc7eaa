//! Schema → [`Scene`]: settings, materials, then structures, spheres and walls (in file
//! order within each section), then boundary conditions, loads, pressures and outputs, which
//! select what was built.

use crate::builder::Builder;
use crate::built::SceneNames;
use crate::error::{unknown_name, Ctx, SceneError};
use crate::run_length::{check_step_count, RunLength};
use crate::scene::{Scene, MAX_THREADS};
use crate::schema::{BoundarySpec, Dt, MaterialSpec, SceneFile, SimulationSpec, Tolerance, S};
use flexdem_contact::{ContactDamping, FailureMode, LinkKinematicsMode, Material};
use flexdem_elements::{Dofs, MaterialId, Model};
use flexdem_geom::Real;
use flexdem_integrate::{Settings, TimeStep};
use flexdem_output::OutputSettings;
use std::path::Path;

/// Builds the scene described by `file`.
pub(crate) fn build(file: SceneFile, ctx: Ctx<'_>, source: &Path) -> Result<Scene, SceneError> {
    let dir = source.parent().map(Path::to_path_buf).unwrap_or_default();
    let mut b = Builder {
        ctx,
        dir,
        model: Model::new(),
        materials: Vec::new(),
        names: SceneNames::empty(),
        wall_controls: Vec::new(),
        sections: Vec::new(),
        available: crate::memory::available_memory(),
    };
    let (settings, run, threads) = b.simulation(&file.simulation)?;
    for (name, spec) in &file.materials {
        b.add_material(name, spec)?;
    }
    // the simulation's memory, estimated as each part is added (the model is a fraction of
    // it), refused at the part that does not fit
    let fits =
        |b: &Builder<'_>, span: std::ops::Range<usize>, key: &str| match crate::memory::too_large(
            &b.model,
            b.available,
        ) {
            Some(message) => Err(ctx.at(span, key, message)),
            None => Ok(()),
        };
    for s in &file.structures {
        b.add_structure(s)?;
        fits(&b, s.span(), "structures")?;
    }
    for s in &file.spheres {
        b.add_spheres(s)?;
        fits(&b, s.span(), "spheres")?;
    }
    for w in &file.walls {
        b.add_wall(w)?;
    }
    b.check_sections()?;
    for bc in &file.boundary {
        b.add_boundary(bc)?;
    }
    let loads = file.loads.iter().map(|l| b.selector().load(l)).collect::<Result<Vec<_>, _>>()?;
    let pressures = file.pressures.iter().map(|p| b.pressure(p)).collect::<Result<Vec<_>, _>>()?;
    let output = match &file.output {
        Some(o) => b.output(o)?,
        None => OutputSettings {
            directory: b.dir.join("output"),
            vtk_every: None,
            series_every: None,
            series: Vec::new(),
            plot: false,
        },
    };
    b.model
        .validate()
        .map_err(|e| ctx.at(0..0, "", format!("the scene's model is invalid: {e}")))?;
    Ok(Scene {
        model: b.model,
        settings,
        loads,
        pressures,
        names: b.names,
        wall_controls: b.wall_controls,
        run,
        threads,
        output,
        source: source.to_path_buf(),
    })
}

impl Builder<'_> {
    /// The id of the material named by `name`.
    pub(crate) fn material(&self, name: &S<String>, key: &str) -> Result<MaterialId, SceneError> {
        let given = name.get_ref();
        match self.materials.iter().find(|(n, _)| n == given) {
            Some(&(_, id)) => Ok(id),
            None if self.materials.is_empty() => Err(self.ctx.at(
                name.span(),
                key,
                format!("unknown material `{given}`: no material is defined (add a [materials.{given}] table)"),
            )),
            None => {
                let known: Vec<&str> = self.materials.iter().map(|(n, _)| n.as_str()).collect();
                Err(self.ctx.at(name.span(), key, unknown_name("material", given, &known)))
            }
        }
    }

    fn simulation(
        &self,
        spec: &S<SimulationSpec>,
    ) -> Result<(Settings, RunLength, Option<usize>), SceneError> {
        let ctx = self.ctx;
        let sim = spec.get_ref();
        let key = |k: &str| format!("simulation.{k}");
        let mut settings = Settings::default();
        let safety = match &sim.safety {
            Some(s) => {
                let v = *s.get_ref();
                if !(v > 0.0 && v <= 1.0) {
                    return Err(ctx.at(
                        s.span(),
                        &key("safety"),
                        format!("is {v}: expected a number in (0, 1]"),
                    ));
                }
                Some((v, s.span()))
            }
            None => None,
        };
        settings.time_step = match sim.dt.as_ref().map(|d| (*d.get_ref(), d.span())) {
            None | Some((Dt::Auto, _)) => TimeStep::Auto { safety: safety.map_or(0.5, |s| s.0) },
            Some((Dt::Fixed(dt), span)) => {
                if !(dt > 0.0 && dt.is_finite()) {
                    return Err(ctx.at(
                        span,
                        &key("dt"),
                        format!("is {dt}: expected \"auto\" or a finite time step > 0 (s)"),
                    ));
                }
                if let Some((_, s)) = safety {
                    return Err(ctx.at(
                        s,
                        &key("safety"),
                        "`safety` applies to dt = \"auto\" only; remove it or set dt = \"auto\"",
                    ));
                }
                TimeStep::Fixed(dt)
            }
        };
        let run = match (&sim.steps, &sim.duration) {
            (Some(n), None) => RunLength::Steps(ctx.count(n, &key("steps"), 1)? as u64),
            (None, Some(t)) => RunLength::Duration(ctx.positive(t, &key("duration"), "s")?),
            (Some(_), Some(t)) => {
                return Err(ctx.at(
                    t.span(),
                    &key("duration"),
                    "conflicts with `steps`: give either `steps` or `duration`, not both",
                ))
            }
            (None, None) => {
                return Err(ctx.missing(
                    spec.span(),
                    "simulation.steps",
                    "give `steps = N` or `duration = T` (s)",
                ))
            }
        };
        // the step count is known now for a fixed dt (for dt = "auto", once the simulation is
        // built: `check_step_count`)
        let run_span = sim.steps.as_ref().map(|n| (n.span(), "steps"));
        let run_span = run_span.or(sim.duration.as_ref().map(|d| (d.span(), "duration")));
        let step = match settings.time_step {
            TimeStep::Fixed(dt) => dt,
            TimeStep::Auto { .. } => Real::INFINITY,
        };
        if let (Err(message), Some((span, k))) = (check_step_count(run, step), run_span) {
            return Err(ctx.at(span, &key(k), message));
        }
        if let Some(g) = &sim.gravity {
            settings.gravity = ctx.vec3(g, &key("gravity"), "m/s²")?;
        }
        if let Some(d) = &sim.damping {
            let v = *d.get_ref();
            if !(0.0..1.0).contains(&v) {
                return Err(ctx.at(
                    d.span(),
                    &key("damping"),
                    format!("is {v}: expected a number in [0, 1)"),
                ));
            }
            settings.damping = v;
        }
        let threads = match &sim.threads {
            Some(t) => {
                let n = ctx.count(t, &key("threads"), 1)?;
                if n > MAX_THREADS {
                    return Err(ctx.at(
                        t.span(),
                        &key("threads"),
                        format!("is {n}: expected a whole number in [1, {MAX_THREADS}]"),
                    ));
                }
                Some(n)
            }
            None => None,
        };
        if let Some(m) = &sim.link_kinematics {
            settings.link_mode = match m.get_ref().as_str() {
                "beam" => LinkKinematicsMode::Beam,
                "yade" => LinkKinematicsMode::Yade,
                other => {
                    return Err(ctx.at(
                        m.span(),
                        &key("link_kinematics"),
                        unknown_name("link kinematics", other, &["beam", "yade"]),
                    ))
                }
            };
        }
        if let Some(v) = &sim.verlet_factor {
            settings.verlet_factor =
                ctx.positive(v, &key("verlet_factor"), "fraction of each element's size")?;
        }
        if let Some(n) = &sim.time_step_interval {
            settings.time_step_interval = ctx.count(n, &key("time_step_interval"), 1)? as u64;
        }
        if let Some(t) = &sim.energy_tolerance {
            settings.energy_tolerance = match *t.get_ref() {
                Tolerance::Off => None,
                Tolerance::Value(v) if v > 0.0 && v.is_finite() => Some(v),
                Tolerance::Value(v) => {
                    return Err(ctx.at(
                        t.span(),
                        &key("energy_tolerance"),
                        format!(
                            "is {v}: expected \"off\" or a positive fraction of the energy \
                             scale (e.g. 0.05)"
                        ),
                    ))
                }
            };
        }
        settings.validate().map_err(|e| ctx.at(spec.span(), "simulation", e.to_string()))?;
        Ok((settings, run, threads))
    }

    fn add_material(&mut self, name: &S<String>, spec: &S<MaterialSpec>) -> Result<(), SceneError> {
        let ctx = self.ctx;
        let m = spec.get_ref();
        let n = name.get_ref();
        let key = |k: &str| format!("materials.{n}.{k}");
        let young = ctx.positive(&m.young, &key("young"), "Pa")?;
        let poisson = *m.poisson.get_ref();
        if !(poisson > -1.0 && poisson <= 0.5) {
            return Err(ctx.at(
                m.poisson.span(),
                &key("poisson"),
                format!("is {poisson}: expected a Poisson ratio with -1 < poisson <= 0.5"),
            ));
        }
        let density = ctx.positive(&m.density, &key("density"), "kg/m³")?;
        let phi = *m.friction_angle_deg.get_ref();
        if !(0.0..90.0).contains(&phi) {
            return Err(ctx.at(
                m.friction_angle_deg.span(),
                &key("friction_angle_deg"),
                format!("is {phi}: expected degrees with 0 <= angle < 90"),
            ));
        }
        let strength = |v: &Option<S<f64>>, k: &str| -> Result<Option<Real>, SceneError> {
            match v {
                None => Ok(None),
                Some(s) => ctx
                    .positive(s, &key(k), "Pa; omit the key for an unbreakable material")
                    .map(Some),
            }
        };
        let mut material = Material {
            young,
            poisson,
            shear_ratio: poisson,
            density,
            friction_angle: phi.to_radians(),
            tensile_strength: strength(&m.tensile_strength, "tensile_strength")?,
            shear_strength: strength(&m.shear_strength, "shear_strength")?,
            failure: FailureMode::Fragile,
            moments: m.moments.unwrap_or(true),
            damping: self.contact_damping(m, &key)?,
        };
        if let Some(r) = &m.shear_ratio {
            material.shear_ratio = ctx.non_negative(r, &key("shear_ratio"), "ks/kn")?;
        }
        if let Some(f) = &m.failure {
            material.failure = match f.get_ref().as_str() {
                "fragile" => FailureMode::Fragile,
                "plastic" => FailureMode::Plastic,
                other => {
                    return Err(ctx.at(
                        f.span(),
                        &key("failure"),
                        unknown_name("failure mode", other, &["fragile", "plastic"]),
                    ))
                }
            };
        }
        let id = self
            .model
            .add_material(material)
            .map_err(|e| ctx.at(spec.span(), &format!("materials.{n}"), e.to_string()))?;
        self.materials.push((n.clone(), id));
        Ok(())
    }

    /// The viscous contact damping of a material (model.md §7): `restitution` (0 < e ≤ 1), or
    /// the rates per unit mass `gamma_n`, `gamma_t` (1/s, each 0 when absent), not both.
    fn contact_damping(
        &self,
        m: &MaterialSpec,
        key: &dyn Fn(&str) -> String,
    ) -> Result<ContactDamping, SceneError> {
        let ctx = self.ctx;
        let rate = |v: &Option<S<f64>>, k: &str| match v {
            None => Ok(0.0),
            Some(g) => ctx.non_negative(g, &key(k), "1/s, a damping rate per unit mass"),
        };
        let (gamma_n, gamma_t) = (rate(&m.gamma_n, "gamma_n")?, rate(&m.gamma_t, "gamma_t")?);
        let Some(e) = &m.restitution else {
            return Ok(if m.gamma_n.is_none() && m.gamma_t.is_none() {
                ContactDamping::None
            } else {
                ContactDamping::Viscous { gamma_n, gamma_t }
            });
        };
        if let Some((g, k)) = [(&m.gamma_n, "gamma_n"), (&m.gamma_t, "gamma_t")]
            .into_iter()
            .find_map(|(g, k)| g.as_ref().map(|g| (g, k)))
        {
            return Err(ctx.at(
                g.span(),
                &key(k),
                "conflicts with `restitution`: give a coefficient of restitution or the damping \
                 rates `gamma_n`, `gamma_t` (1/s), not both",
            ));
        }
        let v = *e.get_ref();
        if !(v > 0.0 && v <= 1.0) {
            return Err(ctx.at(
                e.span(),
                &key("restitution"),
                format!("is {v}: expected a coefficient of restitution with 0 < restitution <= 1"),
            ));
        }
        Ok(ContactDamping::Restitution(v))
    }

    fn add_boundary(&mut self, spec: &S<BoundarySpec>) -> Result<(), SceneError> {
        let ctx = self.ctx;
        let bc = spec.get_ref();
        let ids = self.select(&bc.select, "boundary.select")?;
        if bc.block.is_none() && bc.velocity.is_none() && bc.angular_velocity.is_none() {
            return Err(ctx.missing(
                spec.span(),
                "boundary",
                "give `block`, `velocity` or `angular_velocity`",
            ));
        }
        let model_error =
            |e: flexdem_elements::ModelError| ctx.at(spec.span(), "boundary", e.to_string());
        if let Some(b) = &bc.block {
            let dofs: Dofs =
                b.get_ref().parse().map_err(|e: flexdem_elements::DofsParseError| {
                    ctx.at(b.span(), "boundary.block", e.to_string())
                })?;
            self.model.block(ids.iter().copied(), dofs).map_err(model_error)?;
        }
        if let Some(v) = &bc.velocity {
            let v = ctx.vec3(v, "boundary.velocity", "m/s")?;
            self.model.impose_velocity(ids.iter().copied(), v).map_err(model_error)?;
        }
        if let Some(w) = &bc.angular_velocity {
            let w = ctx.vec3(w, "boundary.angular_velocity", "rad/s")?;
            self.model.impose_angular_velocity(ids.iter().copied(), w).map_err(model_error)?;
        }
        Ok(())
    }
}
