//! `[[spheres]]` → free spheres: one sphere, a lattice or a random packing in a box, with an
//! initial velocity and spin.

use crate::builder::Builder;
use crate::built::SphereGroup;
use crate::error::{unknown_name, SceneError};
use crate::packing::{lattice_packing, random_packing};
use crate::schema::{SpheresSpec, S};
use flexdem_geom::{Real, Vec3};
use std::ops::Range;

/// The kinds of `[[spheres]]` entry and the keys each takes besides the common ones.
const KINDS: [(&str, &[&str]); 5] = [
    ("single", &["center", "radius"]),
    ("lattice", &["box", "radius", "spacing"]),
    ("random", &["box", "radius", "radius_range", "count", "seed"]),
    (
        "dense",
        &[
            "box",
            "cylinder",
            "inside",
            "radius",
            "radius_range",
            "count",
            "seed",
            "solid_fraction",
            "tolerance",
            "max_iterations",
        ],
    ),
    ("file", &["file"]),
];

impl SpheresSpec {
    fn present(&self) -> Vec<(&'static str, Range<usize>)> {
        fn sp<T>(v: &Option<S<T>>) -> Option<Range<usize>> {
            v.as_ref().map(|s| s.span())
        }
        [
            ("center", sp(&self.center)),
            ("radius", sp(&self.radius)),
            ("box", sp(&self.region)),
            ("spacing", sp(&self.spacing)),
            ("radius_range", sp(&self.radius_range)),
            ("count", sp(&self.count)),
            ("seed", sp(&self.seed)),
            ("cylinder", sp(&self.cylinder)),
            ("inside", sp(&self.inside)),
            ("solid_fraction", sp(&self.solid_fraction)),
            ("tolerance", sp(&self.tolerance)),
            ("max_iterations", sp(&self.max_iterations)),
            ("file", sp(&self.file)),
        ]
        .into_iter()
        .filter_map(|(k, s)| s.map(|s| (k, s)))
        .collect()
    }
}

impl Builder<'_> {
    /// Adds the spheres of one `[[spheres]]` entry.
    pub(crate) fn add_spheres(&mut self, spec: &S<SpheresSpec>) -> Result<(), SceneError> {
        let ctx = self.ctx;
        let table = spec.span();
        let sp = spec.get_ref();
        let key = |k: &str| format!("spheres.{k}");
        let kind = sp.kind.get_ref().as_str();
        let Some(&(kind, allowed)) = KINDS.iter().find(|(k, _)| *k == kind) else {
            let known: Vec<&str> = KINDS.iter().map(|(k, _)| *k).collect();
            return Err(ctx.at(sp.kind.span(), &key("kind"), unknown_name("kind", kind, &known)));
        };
        for (k, span) in sp.present() {
            if !allowed.contains(&k) {
                return Err(ctx.at(
                    span,
                    &key(k),
                    format!(
                        "`{k}` does not apply to kind = \"{kind}\"; it takes: {}",
                        allowed.join(", ")
                    ),
                ));
            }
        }
        let name = sp.name.as_ref().map(|n| (n.get_ref().clone(), n.span()));
        if let Some((n, span)) = &name {
            if self.names.groups.iter().any(|g| g.name == *n) {
                return Err(ctx.at(
                    span.clone(),
                    &key("name"),
                    format!("a sphere group named `{n}` already exists: names must be unique"),
                ));
            }
        }
        let material = self.material(&sp.material, &key("material"))?;
        let mask = ctx.mask(sp.mask.as_ref(), &key("mask"))?;
        let velocity = sp
            .velocity
            .as_ref()
            .map_or(Ok(Vec3::zeros()), |v| ctx.vec3(v, &key("velocity"), "m/s"))?;
        let spin = sp
            .angular_velocity
            .as_ref()
            .map_or(Ok(Vec3::zeros()), |v| ctx.vec3(v, &key("angular_velocity"), "rad/s"))?;
        let need = |k: &str| {
            ctx.missing(table.clone(), &key(k), &format!("kind = \"{kind}\" needs `{k}`"))
        };
        let region = || -> Result<(Vec3, Vec3), SceneError> {
            let b = sp.region.as_ref().ok_or_else(|| need("box"))?;
            let lo = ctx.vec3(&b.get_ref().min, &key("box.min"), "m")?;
            let hi = ctx.vec3(&b.get_ref().max, &key("box.max"), "m")?;
            Ok((lo, hi))
        };
        let radius = || -> Result<Real, SceneError> {
            ctx.positive(sp.radius.as_ref().ok_or_else(|| need("radius"))?, &key("radius"), "m")
        };
        let packing_error =
            |e: crate::packing::PackingError| ctx.at(table.clone(), "spheres", e.to_string());
        let spheres: Vec<(Vec3, Real)> = match kind {
            "single" => {
                let c = ctx.vec3(
                    sp.center.as_ref().ok_or_else(|| need("center"))?,
                    &key("center"),
                    "m",
                )?;
                vec![(c, radius()?)]
            }
            "lattice" => {
                let (lo, hi) = region()?;
                let r = radius()?;
                let spacing = match &sp.spacing {
                    Some(s) => ctx.positive(s, &key("spacing"), "m")?,
                    None => 2.0 * r,
                };
                lattice_packing(lo, hi, r, spacing)
                    .map_err(packing_error)?
                    .into_iter()
                    .map(|c| (c, r))
                    .collect()
            }
            "dense" => self.dense_spheres(sp, table.clone())?,
            "file" => self.file_spheres(sp, table.clone())?,
            _ => {
                let (lo, hi) = region()?;
                let (r_min, r_max) = self.radius_range(sp, table.clone())?;
                let count =
                    ctx.count(sp.count.as_ref().ok_or_else(|| need("count"))?, &key("count"), 1)?;
                let seed = match &sp.seed {
                    Some(s) => ctx.count(s, &key("seed"), 0)? as u64,
                    None => 0,
                };
                random_packing(lo, hi, r_min, r_max, count, seed).map_err(packing_error)?
            }
        };
        let first = self.model.particles.len() as u32;
        for (c, r) in spheres {
            let id = self
                .model
                .add_sphere(c, r, material)
                .map_err(|e| ctx.at(table.clone(), "spheres", e.to_string()))?
                as usize;
            self.model.particles.vel[id] = velocity;
            self.model.particles.ang_vel[id] = spin;
            self.model.particles.mask[id] = mask;
        }
        let end = self.model.particles.len() as u32;
        if let Some((name, _)) = name {
            self.names.groups.push(SphereGroup { name, particles: first..end });
        }
        Ok(())
    }

    /// `radius` (one size) or `radius_range = [smallest, largest]`, exactly one of them.
    pub(crate) fn radius_range(
        &self,
        sp: &SpheresSpec,
        table: Range<usize>,
    ) -> Result<(Real, Real), SceneError> {
        let ctx = self.ctx;
        let key = |k: &str| format!("spheres.{k}");
        let kind = sp.kind.get_ref().as_str();
        let need = |k: &str| {
            ctx.missing(table.clone(), &key(k), &format!("kind = \"{kind}\" needs `{k}`"))
        };
        let radius = || -> Result<Real, SceneError> {
            ctx.positive(sp.radius.as_ref().ok_or_else(|| need("radius"))?, &key("radius"), "m")
        };
        Ok(match (&sp.radius, &sp.radius_range) {
            (Some(_), None) => (radius()?, radius()?),
            (None, Some(rr)) => {
                let [a, b] = rr.get_ref().0;
                let a = ctx.positive(&S::new(rr.span(), a), &key("radius_range"), "m")?;
                let b = ctx.positive(&S::new(rr.span(), b), &key("radius_range"), "m")?;
                if b < a {
                    return Err(ctx.at(
                        rr.span(),
                        &key("radius_range"),
                        format!("is [{a}, {b}]: expected [smallest, largest]"),
                    ));
                }
                (a, b)
            }
            (Some(r), Some(_)) => {
                return Err(ctx.at(
                    r.span(),
                    &key("radius"),
                    "give either `radius` or `radius_range`, not both",
                ))
            }
            (None, None) => return Err(need("radius")),
        })
    }
}
