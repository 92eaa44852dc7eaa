//! `select = { ... }`: particles picked by structure (all nodes or a side), sphere group, ids,
//! and filtered by a box or a plane. A selection that matches nothing is an error.

use crate::builder::Builder;
use crate::built::{Layout, SceneNames};
use crate::error::{unknown_name, Ctx, SceneError};
use crate::schema::{SelectSpec, S};
use flexdem_elements::builders::{GridLayout, GridSide};
use flexdem_elements::Model;

/// Selections over a model with the names of its scene: during the build (the model so
/// far), or after it (a script's loads between stages, over the simulation's current model).
#[derive(Clone, Copy)]
pub(crate) struct Selector<'a> {
    /// The text being read, for located errors.
    pub ctx: Ctx<'a>,
    /// The particles selected from (positions for `box` and `plane`).
    pub model: &'a Model,
    /// The structures and sphere groups by name.
    pub names: &'a SceneNames,
}

/// The sides a layout offers.
fn sides(layout: Layout) -> &'static [&'static str] {
    match layout {
        Layout::Line | Layout::Tube { .. } => &["start", "end", "ends"],
        Layout::Grid { .. } => &["u_min", "u_max", "v_min", "v_max", "boundary", "corners"],
        Layout::Disc { .. } => &["center", "boundary"],
        Layout::Unstructured => &[],
    }
}

impl Builder<'_> {
    /// Selections over the model built so far.
    pub(crate) fn selector(&self) -> Selector<'_> {
        Selector { ctx: self.ctx, model: &self.model, names: &self.names }
    }

    /// The particle ids chosen by `sel` among the particles built so far
    /// ([`Selector::select`]).
    pub(crate) fn select(&self, sel: &S<SelectSpec>, key: &str) -> Result<Vec<u32>, SceneError> {
        self.selector().select(sel, key)
    }
}

impl Selector<'_> {
    /// The error for a selection by name when the names are not known.
    fn names_unknown(&self, span: std::ops::Range<usize>, key: &str) -> SceneError {
        self.ctx.at(
            span,
            key,
            "the scene's structure and sphere group names are not known here (a simulation \
             resumed from a checkpoint does not keep them): select by `ids`, `box` or `plane`",
        )
    }

    /// The particle ids (ascending, no duplicates) chosen by `sel`; `key` is the dotted path of
    /// the `select` key for messages (e.g. `boundary.select`).
    pub(crate) fn select(&self, sel: &S<SelectSpec>, key: &str) -> Result<Vec<u32>, SceneError> {
        let ctx = self.ctx;
        let spec = sel.get_ref();
        let k = |sub: &str| format!("{key}.{sub}");
        let bases = [
            spec.structure.as_ref().map(|s| s.span()),
            spec.spheres.as_ref().map(|s| s.span()),
            spec.ids.as_ref().map(|s| s.span()),
        ];
        if let Some(second) = bases.iter().flatten().nth(1) {
            return Err(ctx.at(
                second.clone(),
                key,
                "give at most one of `structure`, `spheres` and `ids` (filter with `box`, `plane` \
                 or `side`)",
            ));
        }
        if let (Some(side), None) = (&spec.side, &spec.structure) {
            return Err(ctx.at(side.span(), &k("side"), "`side` needs `structure = \"name\"`"));
        }
        let mut ids: Vec<u32> = if let Some(name) = &spec.structure {
            if !self.names.known {
                return Err(self.names_unknown(name.span(), &k("structure")));
            }
            self.structure_selection(name, spec.side.as_ref(), key)?
        } else if let Some(name) = &spec.spheres {
            if !self.names.known {
                return Err(self.names_unknown(name.span(), &k("spheres")));
            }
            let Some(g) = self.names.groups.iter().find(|g| g.name == *name.get_ref()) else {
                let known: Vec<&str> = self.names.groups.iter().map(|g| g.name.as_str()).collect();
                return Err(ctx.at(
                    name.span(),
                    &k("spheres"),
                    unknown_name("sphere group", name.get_ref(), &known),
                ));
            };
            g.particles.clone().collect()
        } else if let Some(list) = &spec.ids {
            let count = self.model.particles.len();
            let mut out = Vec::with_capacity(list.get_ref().len());
            for &id in list.get_ref() {
                match u32::try_from(id) {
                    Ok(i) if (i as usize) < count => out.push(i),
                    _ => {
                        return Err(ctx.at(
                            list.span(),
                            &k("ids"),
                            format!("particle id {id} does not exist: the scene has {count} particles (ids 0..{count})"),
                        ))
                    }
                }
            }
            out
        } else if spec.region.is_some() || spec.plane.is_some() {
            (0..self.model.particles.len() as u32).collect()
        } else {
            return Err(ctx.at(
                sel.span(),
                key,
                "empty selection: give `structure`, `spheres`, `ids`, `box` or `plane`",
            ));
        };
        let pos = &self.model.particles.pos;
        if let Some(b) = &spec.region {
            let (lo, hi) = (
                ctx.vec3(&b.get_ref().min, &k("box.min"), "m")?,
                ctx.vec3(&b.get_ref().max, &k("box.max"), "m")?,
            );
            if (0..3).any(|i| lo[i] > hi[i]) {
                return Err(ctx.at(
                    b.span(),
                    &k("box"),
                    format!(
                        "min {:?} exceeds max {:?} on some axis: expected min <= max",
                        <[f64; 3]>::from(lo),
                        <[f64; 3]>::from(hi)
                    ),
                ));
            }
            ids.retain(|&i| {
                let p = pos[i as usize];
                (0..3).all(|a| lo[a] <= p[a] && p[a] <= hi[a])
            });
        }
        if let Some(pl) = &spec.plane {
            let p = pl.get_ref();
            let point = ctx.vec3(&p.point, &k("plane.point"), "m")?;
            let n = ctx.direction(&p.normal, &k("plane.normal"))?.normalize();
            let tol = match &p.tolerance {
                Some(t) => Some(ctx.non_negative(t, &k("plane.tolerance"), "m")?),
                None => None,
            };
            let radius = &self.model.particles.radius;
            ids.retain(|&i| {
                let d = (pos[i as usize] - point).dot(&n).abs();
                d <= tol.unwrap_or(radius[i as usize])
            });
        }
        ids.sort_unstable();
        ids.dedup();
        if ids.is_empty() {
            return Err(ctx.at(
                sel.span(),
                key,
                "this selection matches no particle: check the names, the box or the plane",
            ));
        }
        Ok(ids)
    }

    /// The nodes of a structure, or of one of its sides.
    fn structure_selection(
        &self,
        name: &S<String>,
        side: Option<&S<String>>,
        key: &str,
    ) -> Result<Vec<u32>, SceneError> {
        let ctx = self.ctx;
        let Some(st) = self.names.structures.iter().find(|s| s.name == *name.get_ref()) else {
            let known: Vec<&str> = self.names.structures.iter().map(|s| s.name.as_str()).collect();
            return Err(ctx.at(
                name.span(),
                &format!("{key}.structure"),
                unknown_name("structure", name.get_ref(), &known),
            ));
        };
        let nodes = self.model.structures[st.id as usize].nodes.clone();
        let Some(side) = side else { return Ok(nodes.collect()) };
        let which = side.get_ref().as_str();
        let offered = sides(st.layout);
        if !offered.contains(&which) {
            let message = if offered.is_empty() {
                format!(
                    "structure `{}` has no named sides: select its nodes with `box` or `plane`",
                    st.name
                )
            } else {
                format!("structure `{}`: {}", st.name, unknown_name("side", which, offered))
            };
            return Err(ctx.at(side.span(), &format!("{key}.side"), message));
        }
        let (first, last) = (nodes.start, nodes.end - 1);
        Ok(match (st.layout, which) {
            (Layout::Line, "start") => vec![first],
            (Layout::Line, "end") => vec![last],
            (Layout::Line, _) => vec![first, last],
            (Layout::Tube { around, along }, w) => {
                let ring = |j: usize| (0..around).map(move |i| first + (j * around + i) as u32);
                match w {
                    "start" => ring(0).collect(),
                    "end" => ring(along).collect(),
                    _ => ring(0).chain(ring(along)).collect(),
                }
            }
            (Layout::Disc { .. }, "center") => vec![first],
            (Layout::Disc { rings }, _) => (nodes.end - 6 * rings as u32..nodes.end).collect(),
            (Layout::Grid { n_u, n_v }, w) => {
                let g = GridLayout { first_node: first, n_u, n_v };
                match w {
                    "u_min" => g.side(GridSide::UMin),
                    "u_max" => g.side(GridSide::UMax),
                    "v_min" => g.side(GridSide::VMin),
                    "v_max" => g.side(GridSide::VMax),
                    "corners" => g.corners().to_vec(),
                    _ => g.boundary(),
                }
            }
            (Layout::Unstructured, _) => Vec::new(),
        })
    }
}
