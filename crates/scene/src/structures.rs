//! `[[structures]]` → builder calls: kind-specific keys, defaults, placement, initial
//! velocity. Each structure is built with its lengths scaled, then moved rigidly (rotation and
//! translation), which keeps rest lengths and lumped masses exact.

use crate::builder::Builder;
use crate::built::{BuiltStructure, Layout};
use crate::error::{unknown_name, Ctx, SceneError};
use crate::memory;
use crate::placement::Placement;
use crate::schema::{PlacementSpec, StructureSpec, S, V3};
use flexdem_elements::builders::{self, ShellBase};
use flexdem_elements::{MassLumping, StructureId, StructureOptions};
use flexdem_geom::{Real, TriMesh, Vec3};
use flexdem_mesh::read_mesh;
use std::ops::Range;

/// The kinds of structure and the keys each takes besides the common ones.
const KINDS: [(&str, &[&str]); 8] = [
    ("chain", &["points", "start", "end", "segments"]),
    ("helix", &["center", "radius", "pitch", "turns", "segments_per_turn"]),
    ("net", &["origin", "u_dir", "v_dir", "size", "cells", "diagonals"]),
    ("membrane", &["origin", "u_dir", "v_dir", "size", "cells"]),
    ("disc", &["center", "normal", "radius", "rings"]),
    ("tube", &["start", "axis", "radius", "length", "around", "along"]),
    ("sphere_shell", &["center", "radius", "base", "subdivisions"]),
    ("mesh", &["file", "merge_tolerance"]),
];

/// Largest number of nodes a scene may ask of one structure (a guard against typos that would
/// exhaust memory).
pub const MAX_STRUCTURE_NODES: usize = 2_000_000;

impl StructureSpec {
    /// The kind-specific keys that are present, with their spans.
    fn present(&self) -> Vec<(&'static str, Range<usize>)> {
        fn sp<T>(v: &Option<S<T>>) -> Option<Range<usize>> {
            v.as_ref().map(|s| s.span())
        }
        let all = [
            ("points", sp(&self.points)),
            ("start", sp(&self.start)),
            ("end", sp(&self.end)),
            ("segments", sp(&self.segments)),
            ("center", sp(&self.center)),
            ("radius", sp(&self.radius)),
            ("pitch", sp(&self.pitch)),
            ("turns", sp(&self.turns)),
            ("segments_per_turn", sp(&self.segments_per_turn)),
            ("origin", sp(&self.origin)),
            ("u_dir", sp(&self.u_dir)),
            ("v_dir", sp(&self.v_dir)),
            ("size", sp(&self.size)),
            ("cells", sp(&self.cells)),
            ("diagonals", sp(&self.diagonals)),
            ("normal", sp(&self.normal)),
            ("rings", sp(&self.rings)),
            ("axis", sp(&self.axis)),
            ("length", sp(&self.length)),
            ("around", sp(&self.around)),
            ("along", sp(&self.along)),
            ("base", sp(&self.base)),
            ("subdivisions", sp(&self.subdivisions)),
            ("file", sp(&self.file)),
            ("merge_tolerance", sp(&self.merge_tolerance)),
        ];
        all.into_iter().filter_map(|(k, s)| s.map(|s| (k, s))).collect()
    }
}

/// A required key, or an error at the table naming the kind.
fn req<'s, T>(
    ctx: &Ctx<'_>,
    v: &'s Option<S<T>>,
    table: Range<usize>,
    key: &str,
    kind: &str,
) -> Result<&'s S<T>, SceneError> {
    v.as_ref().ok_or_else(|| {
        ctx.missing(
            table,
            &format!("structures.{key}"),
            &format!("kind = \"{kind}\" needs `{key}` (see docs/scene-reference.md)"),
        )
    })
}

impl Builder<'_> {
    /// Parses a placement table.
    pub(crate) fn placement(&self, p: Option<&S<PlacementSpec>>) -> Result<Placement, SceneError> {
        let Some(p) = p else { return Ok(Placement::default()) };
        let ctx = &self.ctx;
        let key = |k: &str| format!("structures.placement.{k}");
        let p = p.get_ref();
        let translate = match &p.translate {
            Some(t) => ctx.vec3(t, &key("translate"), "m")?,
            None => Vec3::zeros(),
        };
        let scale = match &p.scale {
            Some(s) => ctx.positive(s, &key("scale"), "a factor")?,
            None => 1.0,
        };
        let rotation = match (&p.rotate_deg, &p.axis, &p.angle_deg) {
            (Some(r), None, None) => {
                Placement::euler_deg(ctx.vec3(r, &key("rotate_deg"), "°")?.into())
            }
            (None, Some(axis), Some(angle)) => {
                let a = ctx.direction(axis, &key("axis"))?;
                let deg = ctx.finite(angle, &key("angle_deg"), "degrees")?;
                Placement::axis_angle_deg(a, deg).unwrap_or_default()
            }
            (None, None, None) => Default::default(),
            (Some(r), _, _) => {
                return Err(ctx.at(
                    r.span(),
                    &key("rotate_deg"),
                    "give either `rotate_deg = [rx, ry, rz]` or `axis` with `angle_deg`, not both",
                ))
            }
            (None, Some(s), None) => {
                return Err(ctx.at(s.span(), &key("axis"), "`axis` needs `angle_deg` (degrees)"))
            }
            (None, None, Some(s)) => {
                return Err(ctx.at(
                    s.span(),
                    &key("angle_deg"),
                    "`angle_deg` needs `axis` [x, y, z]",
                ))
            }
        };
        Ok(Placement { translate, rotation, scale })
    }

    /// Builds one `[[structures]]` entry.
    pub(crate) fn add_structure(&mut self, spec: &S<StructureSpec>) -> Result<(), SceneError> {
        let table = spec.span();
        let st = spec.get_ref();
        let ctx = self.ctx;
        let name = st.name.get_ref().clone();
        if self.names.structures.iter().any(|s| s.name == name) {
            return Err(ctx.at(
                st.name.span(),
                "structures.name",
                format!("a structure named `{name}` already exists: names must be unique"),
            ));
        }
        let kind = st.kind.get_ref().as_str();
        let Some(&(kind, allowed)) = KINDS.iter().find(|(k, _)| *k == kind) else {
            let known: Vec<&str> = KINDS.iter().map(|(k, _)| *k).collect();
            return Err(ctx.at(
                st.kind.span(),
                "structures.kind",
                unknown_name("kind", kind, &known),
            ));
        };
        for (key, span) in st.present() {
            if !allowed.contains(&key) {
                return Err(ctx.at(
                    span,
                    &format!("structures.{key}"),
                    format!(
                        "`{key}` does not apply to kind = \"{kind}\"; it takes: {}",
                        allowed.join(", ")
                    ),
                ));
            }
        }
        let material = self.material(&st.material, "structures.material")?;
        let radius = ctx.positive(&st.node_radius, "structures.node_radius", "m")?;
        let mass = match st.mass.as_ref().map(|m| (m.get_ref().as_str(), m.span())) {
            None | Some(("connections", _)) => MassLumping::Connections,
            Some(("plate", _)) => MassLumping::Plate,
            Some((other, span)) => {
                return Err(ctx.at(
                    span,
                    "structures.mass",
                    unknown_name("mass lumping", other, &["connections", "plate"]),
                ))
            }
        };
        let mask = ctx.mask(st.mask.as_ref(), "structures.mask")?;
        let place = self.placement(st.placement.as_ref())?;
        let velocity = match &st.velocity {
            Some(v) => ctx.vec3(v, "structures.velocity", "m/s")?,
            None => Vec3::zeros(),
        };
        let self_contact = st.self_contact.as_ref().is_none_or(|v| *v.get_ref());
        let opts = StructureOptions::new(name.clone(), radius, material)
            .with_mask(mask)
            .with_mass(mass)
            .with_self_contact(self_contact);
        let (id, layout) = self.build_kind(st, kind, table.clone(), place.scale, &opts)?;
        let nodes = self.model.structures[id as usize].nodes.clone();
        for n in nodes {
            let n = n as usize;
            self.model.particles.pos[n] = place.apply_rigid(self.model.particles.pos[n]);
            self.model.particles.vel[n] = velocity;
        }
        // a structure that does not touch itself may overlap itself
        let overlap = self_contact
            .then(|| flexdem_elements::self_overlap::self_overlap(&self.model, id))
            .flatten();
        if let Some(o) = overlap {
            return Err(ctx.at(
                table,
                "structures",
                format!(
                    "structure `{name}` overlaps itself at the start: its {} and {} are {:.3e} m \
                     apart near [{:.4}, {:.4}, {:.4}], less than the sum of \
                     their radii ({:.3e} m), and would push each other apart from the first step: \
                     expected elements apart by at least 2 × node_radius (fewer segments or \
                     cells, a larger pitch, or a smaller node_radius)",
                    o.first, o.second, o.distance, o.at.x, o.at.y, o.at.z, o.radii
                ),
            ));
        }
        self.names.structures.push(BuiltStructure { name, id, layout });
        Ok(())
    }

    /// Calls the builder of `kind` with every length scaled by `s`.
    fn build_kind(
        &mut self,
        st: &StructureSpec,
        kind: &str,
        table: Range<usize>,
        s: Real,
        opts: &StructureOptions,
    ) -> Result<(StructureId, Layout), SceneError> {
        let ctx = self.ctx;
        let key = |k: &str| format!("structures.{k}");
        let v3 = |v: &Option<S<V3>>, k: &str, default: Vec3| -> Result<Vec3, SceneError> {
            v.as_ref().map_or(Ok(default), |v| ctx.vec3(v, &key(k), "m"))
        };
        let dir = |v: &Option<S<V3>>, k: &str, default: Vec3| -> Result<Vec3, SceneError> {
            v.as_ref().map_or(Ok(default), |v| ctx.direction(v, &key(k)))
        };
        let len = |v: &Option<S<f64>>, k: &str| -> Result<Real, SceneError> {
            Ok(s * ctx.positive(req(&ctx, v, table.clone(), k, kind)?, &key(k), "m")?)
        };
        let cnt = |v: &Option<S<i64>>, k: &str, min: i64| -> Result<usize, SceneError> {
            ctx.count(req(&ctx, v, table.clone(), k, kind)?, &key(k), min)
        };
        // memory: the scene so far, and elements per node of this kind (a polyline has a
        // connection per node, a net two or three, a PFacet surface three and two PFacets)
        let (base, available) = (memory::estimate_memory(&self.model), self.available);
        let per_node: u64 = match kind {
            "chain" | "helix" => 2,
            "net" => 4,
            _ => 6,
        };
        let too_big = |nodes: Option<usize>| -> Result<(), SceneError> {
            match nodes {
                Some(n) if n <= MAX_STRUCTURE_NODES => {
                    match memory::too_large_to_build(base, n as u64 * per_node, available) {
                        Some(message) => Err(ctx.at(table.clone(), "structures", message)),
                        None => Ok(()),
                    }
                }
                _ => Err(ctx.at(
                    table.clone(),
                    "structures",
                    format!(
                        "kind = \"{kind}\" with these counts has {} nodes, more than the {MAX_STRUCTURE_NODES} allowed: expected fewer cells, rings, segments or subdivisions",
                        nodes.map_or("about 10^18 or more".to_string(), |n| n.to_string())
                    ),
                )),
            }
        };
        let scene_dir = self.dir.clone();
        let model = &mut self.model;
        let (result, layout) = match kind {
            "chain" => {
                let points =
                    match (&st.points, &st.start, &st.end, &st.segments) {
                        (Some(p), None, None, None) => {
                            let mut pts = Vec::with_capacity(p.get_ref().len());
                            for q in p.get_ref() {
                                let v = S::new(p.span(), *q);
                                pts.push(ctx.vec3(&v, &key("points"), "m")? * s);
                            }
                            pts
                        }
                        (None, Some(a), Some(b), Some(n)) => {
                            let (a, b) =
                                (ctx.vec3(a, &key("start"), "m")?, ctx.vec3(b, &key("end"), "m")?);
                            let n = ctx.count(n, &key("segments"), 1)?;
                            too_big(n.checked_add(1))?;
                            builders::straight_line(a * s, b * s, n)
                                .map_err(|e| ctx.at(table.clone(), "structures", e.to_string()))?
                        }
                        _ => return Err(ctx.missing(
                            table,
                            "structures.points",
                            "kind = \"chain\" needs either `points = [[x, y, z], ...]` or all of \
                             `start`, `end` and `segments`",
                        )),
                    };
                (builders::chain(model, &points, opts), Layout::Line)
            }
            "helix" => {
                let pitch = ctx.finite(
                    req(&ctx, &st.pitch, table.clone(), "pitch", kind)?,
                    &key("pitch"),
                    "m per turn",
                )?;
                let turns = ctx.positive(
                    req(&ctx, &st.turns, table.clone(), "turns", kind)?,
                    &key("turns"),
                    "turns",
                )?;
                let per_turn = match &st.segments_per_turn {
                    Some(n) => ctx.count(n, &key("segments_per_turn"), 3)?,
                    None => 12,
                };
                too_big(Some((turns * per_turn as Real).min(1e18) as usize))?;
                let pts = builders::helix(
                    v3(&st.center, "center", Vec3::zeros())? * s,
                    len(&st.radius, "radius")?,
                    pitch * s,
                    turns,
                    per_turn,
                )
                .map_err(|e| ctx.at(table.clone(), "structures", e.to_string()))?;
                (builders::chain(model, &pts, opts), Layout::Line)
            }
            "net" | "membrane" => {
                let origin = v3(&st.origin, "origin", Vec3::zeros())? * s;
                let u = dir(&st.u_dir, "u_dir", Vec3::x())?;
                let v = dir(&st.v_dir, "v_dir", Vec3::y())?;
                let size = req(&ctx, &st.size, table.clone(), "size", kind)?;
                let [su, sv] = size.get_ref().0;
                let su = s * ctx.positive(&S::new(size.span(), su), &key("size"), "m")?;
                let sv = s * ctx.positive(&S::new(size.span(), sv), &key("size"), "m")?;
                let cells = req(&ctx, &st.cells, table.clone(), "cells", kind)?;
                let [nu, nv] = cells.get_ref().0;
                let nu = ctx.count(&S::new(cells.span(), nu), &key("cells"), 1)?;
                let nv = ctx.count(&S::new(cells.span(), nv), &key("cells"), 1)?;
                too_big((nu + 1).checked_mul(nv + 1))?;
                let layout = Layout::Grid { n_u: nu, n_v: nv };
                if kind == "net" {
                    let diagonals = st.diagonals.as_ref().is_some_and(|d| *d.get_ref());
                    (builders::net(model, origin, u, v, su, sv, nu, nv, diagonals, opts), layout)
                } else {
                    (
                        builders::membrane_rectangle(model, origin, u, v, su, sv, nu, nv, opts),
                        layout,
                    )
                }
            }
            "disc" => {
                let rings = cnt(&st.rings, "rings", 1)?;
                too_big(rings.checked_mul(rings + 1).and_then(|r| r.checked_mul(3)))?;
                let c = v3(&st.center, "center", Vec3::zeros())? * s;
                let n = dir(&st.normal, "normal", Vec3::z())?;
                (
                    builders::membrane_disc(model, c, n, len(&st.radius, "radius")?, rings, opts),
                    Layout::Disc { rings },
                )
            }
            "tube" => {
                let around = cnt(&st.around, "around", 3)?;
                let along = cnt(&st.along, "along", 1)?;
                too_big(around.checked_mul(along + 1))?;
                let start = v3(&st.start, "start", Vec3::zeros())? * s;
                let axis = dir(&st.axis, "axis", Vec3::x())?;
                let r = len(&st.radius, "radius")?;
                let l = len(&st.length, "length")?;
                (
                    builders::tube(model, start, axis, r, l, around, along, opts),
                    Layout::Tube { around, along },
                )
            }
            "sphere_shell" => {
                let base = match st.base.as_ref().map(|b| (b.get_ref().as_str(), b.span())) {
                    None | Some(("icosahedron", _)) => ShellBase::Icosahedron,
                    Some(("octahedron", _)) => ShellBase::Octahedron,
                    Some((other, span)) => {
                        return Err(ctx.at(
                            span,
                            &key("base"),
                            unknown_name("base", other, &["icosahedron", "octahedron"]),
                        ))
                    }
                };
                let sub = match &st.subdivisions {
                    Some(n) => ctx.count(n, &key("subdivisions"), 0)?,
                    None => 0,
                };
                if sub > builders::MAX_SHELL_SUBDIVISIONS as usize {
                    let span = st.subdivisions.as_ref().map_or(table.clone(), |n| n.span());
                    return Err(ctx.at(
                        span,
                        &key("subdivisions"),
                        format!("is {sub}: expected at most {}", builders::MAX_SHELL_SUBDIVISIONS),
                    ));
                }
                // V = F/2 + 2 nodes, F = F₀·4^subdivisions (F₀ = 20 or 8)
                let faces = if base == ShellBase::Icosahedron { 20 } else { 8 };
                too_big(Some(faces * 4usize.pow(sub as u32) / 2 + 2))?;
                let c = v3(&st.center, "center", Vec3::zeros())? * s;
                (
                    builders::sphere_shell(
                        model,
                        c,
                        len(&st.radius, "radius")?,
                        base,
                        sub as u32,
                        opts,
                    ),
                    Layout::Unstructured,
                )
            }
            _ => {
                let file = req(&ctx, &st.file, table.clone(), "file", kind)?;
                let tolerance = match &st.merge_tolerance {
                    Some(t) => {
                        ctx.non_negative(t, &key("merge_tolerance"), "relative to the mesh size")?
                    }
                    None => 1e-6,
                };
                let path = scene_dir.join(file.get_ref());
                let mesh = read_mesh(&path).map_err(|e| {
                    ctx.at(file.span(), &key("file"), format!("cannot read the mesh: {e}"))
                })?;
                let (v, f) = (mesh.vertices.len() as u64, mesh.triangles.len() as u64);
                if let Some(message) =
                    memory::too_large_to_build(base, v + f + f * 3 / 2, available)
                {
                    return Err(ctx.at(file.span(), &key("file"), message));
                }
                let mesh = TriMesh {
                    vertices: mesh.vertices.iter().map(|v| v * s).collect(),
                    triangles: mesh.triangles,
                };
                (builders::pfacets_from_mesh(model, &mesh, tolerance, opts), Layout::Unstructured)
            }
        };
        let id = result.map_err(|e| {
            ctx.at(
                table,
                "structures",
                format!("cannot build structure `{}` (kind = \"{kind}\"): {e}", opts.name),
            )
        })?;
        Ok((id, layout))
    }
}
