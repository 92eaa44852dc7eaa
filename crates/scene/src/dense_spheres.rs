//! `[[spheres]]` of kind `dense` (a packing filling a box, a cylinder or the inside of a
//! closed structure to a solid fraction) and of kind `file` (spheres read from a CSV file).

use crate::builder::Builder;
use crate::dense::{dense_packing, DensePacking};
use crate::error::{unknown_name, SceneError};
use crate::region::{ClosedSurface, Region};
use crate::schema::{SpheresSpec, S};
use flexdem_geom::{Real, Vec3};
use std::ops::Range;

/// Default largest overlap left in a dense packing, as a fraction of the smallest radius.
pub const DEFAULT_TOLERANCE: Real = 1e-3;
/// Default number of minimisation iterations before a dense packing gives up.
pub const DEFAULT_MAX_ITERATIONS: usize = 20_000;

/// The most `spheres.max_iterations` a dense packing may ask for. FIRE reaches the default
/// tolerance in 10³–10⁴ iterations; more only makes a packing that cannot reach it take
/// longer to fail (each iteration visits every sphere and its neighbours), and a typo of a
/// few zeros would hold the run for days before its error.
pub const MAX_ITERATIONS: usize = 1_000_000;

impl Builder<'_> {
    /// The spheres of a `kind = "dense"` entry.
    pub(crate) fn dense_spheres(
        &self,
        sp: &SpheresSpec,
        table: Range<usize>,
    ) -> Result<Vec<(Vec3, Real)>, SceneError> {
        let ctx = self.ctx;
        let key = |k: &str| format!("spheres.{k}");
        let radius_range = self.radius_range(sp, table.clone())?;
        let fraction = sp.solid_fraction.as_ref().ok_or_else(|| {
            ctx.missing(
                table.clone(),
                &key("solid_fraction"),
                "kind = \"dense\" needs `solid_fraction` (e.g. 0.6)",
            )
        })?;
        let solid_fraction = ctx.positive(fraction, &key("solid_fraction"), "")?;
        let count = sp.count.as_ref().map(|c| ctx.count(c, &key("count"), 1)).transpose()?;
        let seed = sp.seed.as_ref().map_or(Ok(0), |s| ctx.count(s, &key("seed"), 0))? as u64;
        let tolerance = sp
            .tolerance
            .as_ref()
            .map_or(Ok(DEFAULT_TOLERANCE), |t| ctx.positive(t, &key("tolerance"), ""))?;
        let max_iterations = sp
            .max_iterations
            .as_ref()
            .map_or(Ok(DEFAULT_MAX_ITERATIONS), |m| ctx.count(m, &key("max_iterations"), 1))?;
        if let Some(m) = sp.max_iterations.as_ref().filter(|_| max_iterations > MAX_ITERATIONS) {
            return Err(ctx.at(
                m.span(),
                &key("max_iterations"),
                format!(
                    "is {max_iterations}: expected at most {MAX_ITERATIONS} (FIRE reaches the \
                     default tolerance in 10³–10⁴ iterations; a packing that has not reached \
                     it by then needs a lower solid_fraction or a larger tolerance)"
                ),
            ));
        }
        let region = self.packing_region(sp, table.clone(), radius_range.1)?;
        let spec = DensePacking {
            region,
            radius_range,
            count,
            solid_fraction,
            seed,
            tolerance,
            max_iterations,
        };
        let result =
            dense_packing(&spec).map_err(|e| ctx.at(table.clone(), "spheres", e.to_string()))?;
        Ok(result.spheres)
    }

    /// The region of a dense packing: exactly one of `box`, `cylinder` and `inside`.
    fn packing_region(
        &self,
        sp: &SpheresSpec,
        table: Range<usize>,
        r_max: Real,
    ) -> Result<Region, SceneError> {
        let ctx = self.ctx;
        let key = |k: &str| format!("spheres.{k}");
        let given = [sp.region.is_some(), sp.cylinder.is_some(), sp.inside.is_some()];
        if given.iter().filter(|g| **g).count() != 1 {
            return Err(ctx.at(
                table,
                "spheres",
                "kind = \"dense\" fills one region: give exactly one of `box`, `cylinder` and \
                 `inside` (a structure's name)",
            ));
        }
        if let Some(b) = &sp.region {
            let min = ctx.vec3(&b.get_ref().min, &key("box.min"), "m")?;
            let max = ctx.vec3(&b.get_ref().max, &key("box.max"), "m")?;
            if (0..3).any(|k| min[k] >= max[k]) {
                return Err(ctx.at(b.span(), &key("box"), "expected min < max on every axis"));
            }
            return Ok(Region::Box { min, max });
        }
        if let Some(c) = &sp.cylinder {
            let c = c.get_ref();
            return Ok(Region::Cylinder {
                base: ctx.vec3(&c.start, &key("cylinder.start"), "m")?,
                axis: ctx.direction(&c.axis, &key("cylinder.axis"))?.normalize(),
                radius: ctx.positive(&c.radius, &key("cylinder.radius"), "m")?,
                height: ctx.positive(&c.length, &key("cylinder.length"), "m")?,
            });
        }
        let name = sp.inside.as_ref().expect("one region is given");
        self.structure_interior(name, r_max)
    }

    /// The inside of a structure's closed PFacet surface, kept the PFacets' radius away.
    fn structure_interior(&self, name: &S<String>, r_max: Real) -> Result<Region, SceneError> {
        let ctx = self.ctx;
        let Some(st) = self.names.structures.iter().find(|s| s.name == *name.get_ref()) else {
            let known: Vec<&str> = self.names.structures.iter().map(|s| s.name.as_str()).collect();
            return Err(ctx.at(
                name.span(),
                "spheres.inside",
                unknown_name("structure", name.get_ref(), &known),
            ));
        };
        let structure = &self.model.structures[st.id as usize];
        let facets =
            &self.model.pfacets[structure.pfacets.start as usize..structure.pfacets.end as usize];
        if facets.is_empty() {
            return Err(ctx.at(
                name.span(),
                "spheres.inside",
                format!("structure `{}` has no PFacets: it cannot enclose spheres", st.name),
            ));
        }
        let first = structure.nodes.start;
        let vertices: Vec<Vec3> =
            structure.nodes.clone().map(|n| self.model.particles.pos[n as usize]).collect();
        let triangles: Vec<[usize; 3]> =
            facets.iter().map(|f| f.nodes.map(|n| (n - first) as usize)).collect();
        let inset = facets.iter().map(|f| f.radius).fold(0.0, Real::max);
        let surface =
            ClosedSurface::new(&vertices, &triangles, inset, r_max + inset).map_err(|e| {
                ctx.at(name.span(), "spheres.inside", format!("structure `{}`: {e}", st.name))
            })?;
        Ok(Region::Surface(surface))
    }

    /// The spheres of a `kind = "file"` entry: a CSV file with a header naming the columns
    /// `x`, `y`, `z` and `radius` (in any order, other columns ignored), one sphere a row.
    pub(crate) fn file_spheres(
        &self,
        sp: &SpheresSpec,
        table: Range<usize>,
    ) -> Result<Vec<(Vec3, Real)>, SceneError> {
        let ctx = self.ctx;
        let file = sp.file.as_ref().ok_or_else(|| {
            ctx.missing(table, "spheres.file", "kind = \"file\" needs `file` (a CSV file)")
        })?;
        let path = self.dir.join(file.get_ref());
        let text = std::fs::read_to_string(&path).map_err(|e| {
            ctx.at(file.span(), "spheres.file", format!("cannot read {}: {e}", path.display()))
        })?;
        crate::sphere_file::read_spheres(&text)
            .map_err(|e| ctx.at(file.span(), "spheres.file", format!("{}: {e}", path.display())))
    }
}
