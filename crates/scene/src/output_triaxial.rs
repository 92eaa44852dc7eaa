//! `[[output.series]] quantity = "triaxial"`: the measures of a triaxial test (platens
//! `walls = [bottom, top]`, and a membrane `of = { structure = "name" }` or four rigid
//! `lateral_walls`), with the sample's height and volume as built as the strains' reference.

use crate::builder::Builder;
use crate::error::SceneError;
use crate::schema::{SeriesSpecToml, S};
use flexdem_output::triaxial::{triaxial_geometry, Lateral, TriaxialSpec};
use flexdem_output::Quantity;

impl Builder<'_> {
    /// Wall indices of `list` (distinct, existing), exactly `count` of them when given (`what`
    /// says what they are then).
    pub(crate) fn wall_indices(
        &self,
        list: &S<Vec<i64>>,
        key: &str,
        count: Option<usize>,
        what: &str,
    ) -> Result<Vec<u32>, SceneError> {
        let ctx = self.ctx;
        let walls = self.model.walls.len();
        let mut ids: Vec<u32> = Vec::new();
        for &w in list.get_ref() {
            let id = match u32::try_from(w) {
                Ok(id) if (id as usize) < walls => id,
                _ => {
                    return Err(ctx.at(
                        list.span(),
                        key,
                        format!(
                            "wall {w} does not exist: the scene has {walls} [[walls]] (indices \
                             0..{walls}, in file order)"
                        ),
                    ))
                }
            };
            if ids.contains(&id) {
                return Err(ctx.at(list.span(), key, format!("wall {id} is given twice")));
            }
            ids.push(id);
        }
        match count {
            Some(count) if ids.len() != count => Err(ctx.at(
                list.span(),
                key,
                format!("has {} walls: expected {count}, {what}", ids.len()),
            )),
            _ => Ok(ids),
        }
    }

    /// `quantity = "triaxial"`.
    pub(crate) fn triaxial_quantity(&self, s: &S<SeriesSpecToml>) -> Result<Quantity, SceneError> {
        let ctx = self.ctx;
        let sp = s.get_ref();
        let platens_usage = "the platens `walls = [bottom, top]` (indices of [[walls]], their \
                             normals facing each other)";
        let list = sp.walls.as_ref().ok_or_else(|| {
            ctx.missing(
                s.span(),
                "output.series.walls",
                &format!("quantity = \"triaxial\" needs {platens_usage}"),
            )
        })?;
        let platens = self.wall_indices(list, "output.series.walls", Some(2), platens_usage)?;
        let lateral = match (&sp.of, &sp.lateral_walls) {
            (Some(of), None) => {
                let name = self.structure_only(
                    of,
                    "quantity = \"triaxial\" takes `of = { structure = \"name\" }`, the \
                     membrane, and no other selection key",
                )?;
                let structure = self.named_structure(name, "output.series.of.structure")?.id;
                Lateral::Membrane { structure }
            }
            (None, Some(list)) => {
                let ids = self.wall_indices(
                    list,
                    "output.series.lateral_walls",
                    Some(4),
                    "two pairs of facing walls [a, a', b, b']",
                )?;
                Lateral::Walls([ids[0], ids[1], ids[2], ids[3]])
            }
            _ => {
                return Err(ctx.at(
                    s.span(),
                    "output.series",
                    "quantity = \"triaxial\" needs one lateral boundary: a membrane `of = { \
                     structure = \"name\" }` or four rigid `lateral_walls = [a, a', b, b']`",
                ))
            }
        };
        let platens = [platens[0], platens[1]];
        let start = triaxial_geometry(&self.model, platens, &lateral)
            .map_err(|e| ctx.at(s.span(), "output.series", format!("triaxial: {e}")))?;
        Ok(Quantity::Triaxial(TriaxialSpec {
            platens,
            lateral,
            height0: start.height,
            volume0: start.volume,
        }))
    }
}
