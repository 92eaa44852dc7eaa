//! `[[pressures]]` → [`Pressure`]: a pressure on the PFacets of a structure (`structure =
//! "name"`) or on the PFacets whose three nodes a selection picks (`select = { ... }`).
//!
//! A table of its own rather than a `pressure` key of `[[loads]]`: a load acts on particles
//! (a force and a moment on each selected node or sphere) while a pressure acts on PFacets
//! (a follower force from each one's current area and normal); in `[[loads]]` its keys
//! (`pressure`, `flip`) would conflict with `force`, `total_force` and `moment` and its
//! `select` would mean something else.

use crate::builder::Builder;
use crate::built::BuiltStructure;
use crate::error::{unknown_name, SceneError};
use crate::schema::{PressureSpec, S};
use flexdem_elements::PFacetId;
use flexdem_integrate::{Pressure, Ramp};

impl Builder<'_> {
    /// Reads one `[[pressures]]` table.
    pub(crate) fn pressure(&self, spec: &S<PressureSpec>) -> Result<Pressure, SceneError> {
        let ctx = self.ctx;
        let p = spec.get_ref();
        let pfacets = match (&p.structure, &p.select) {
            (Some(name), None) => {
                let st = self.named_structure(name, "pressures.structure")?;
                let range = self.model.structures[st.id as usize].pfacets.clone();
                if range.is_empty() {
                    return Err(ctx.at(
                        name.span(),
                        "pressures.structure",
                        format!(
                            "structure `{}` has no PFacets: a pressure acts on PFacets (a \
                             membrane, disc, tube, sphere shell or mesh)",
                            st.name
                        ),
                    ));
                }
                range.collect()
            }
            (None, Some(select)) => {
                let pfacets = self.selected_pfacets(&self.select(select, "pressures.select")?);
                if pfacets.is_empty() {
                    return Err(ctx.at(
                        select.span(),
                        "pressures.select",
                        "this selection holds no PFacet: a PFacet is loaded when its three \
                         nodes are selected",
                    ));
                }
                pfacets
            }
            (Some(_), Some(select)) => {
                return Err(ctx.at(
                    select.span(),
                    "pressures.select",
                    "give either `structure` (all its PFacets) or `select` (the PFacets whose \
                     three nodes it picks), not both",
                ))
            }
            (None, None) => {
                return Err(ctx.missing(
                    spec.span(),
                    "pressures",
                    "give `structure = \"name\"` or `select = { ... }`",
                ))
            }
        };
        let pressure = ctx.finite(&p.pressure, "pressures.pressure", "Pa")?;
        let ramp = match &p.ramp {
            None => Ramp::Constant,
            Some(r) => Ramp::Linear {
                start: ctx.non_negative(&r.get_ref().start, "pressures.ramp.start", "s")?,
                duration: ctx.positive(&r.get_ref().duration, "pressures.ramp.duration", "s")?,
            },
        };
        Ok(Pressure { pfacets, pressure, flip: p.flip.unwrap_or(false), ramp })
    }

    /// The structure named `name`, or an error at it (with the nearest known name).
    pub(crate) fn named_structure(
        &self,
        name: &S<String>,
        key: &str,
    ) -> Result<&BuiltStructure, SceneError> {
        let structures = &self.names.structures;
        match structures.iter().find(|s| s.name == *name.get_ref()) {
            Some(st) => Ok(st),
            None => {
                let known: Vec<&str> = structures.iter().map(|s| s.name.as_str()).collect();
                Err(self.ctx.at(
                    name.span(),
                    key,
                    unknown_name("structure", name.get_ref(), &known),
                ))
            }
        }
    }

    /// The PFacets whose three nodes are all among `particles` (ascending ids).
    fn selected_pfacets(&self, particles: &[u32]) -> Vec<PFacetId> {
        let mut chosen = vec![false; self.model.particles.len()];
        for &i in particles {
            chosen[i as usize] = true;
        }
        (0..self.model.pfacets.len() as PFacetId)
            .filter(|&f| self.model.pfacets[f as usize].nodes.iter().all(|&n| chosen[n as usize]))
            .collect()
    }
}
