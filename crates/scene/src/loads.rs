//! `[[loads]]` → [`Load`]: during the build of a scene, and after it ([`parse_loads`]: a
//! script's loads between the stages of a run, with the same keys, checks and messages).

use crate::built::SceneNames;
use crate::error::{Ctx, SceneError};
use crate::schema::{LoadSpec, S};
use crate::selection::Selector;
use flexdem_elements::Model;
use flexdem_geom::{Real, Vec3};
use flexdem_integrate::{Load, Ramp};
use serde::Deserialize;
use std::path::Path;

/// A text of `[[loads]]` tables and nothing else.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct LoadsFile {
    #[serde(default)]
    loads: Vec<S<LoadSpec>>,
}

/// The loads of `text`, a TOML text of `[[loads]]` tables (the keys of a scene file's
/// `[[loads]]`), selected over `model` (positions for `box` and `plane`: the model's
/// current ones) with the structures and sphere groups of `names`. `source` names the text
/// in messages; errors are located in `text` as a scene file's are.
///
/// ```
/// use flexdem_scene::{parse_loads, parse_scene};
/// let scene = parse_scene(
///     r#"
///     [simulation]
///     steps = 10
///     [materials.m]
///     young = 1e8
///     poisson = 0.3
///     density = 1000
///     friction_angle_deg = 30
///     [[structures]]
///     name = "cable"
///     kind = "chain"
///     material = "m"
///     node_radius = 0.01
///     start = [0, 0, 0]
///     end = [1, 0, 0]
///     segments = 4
///     "#,
///     "scene.toml".as_ref(),
/// )?;
/// let text = "[[loads]]\nselect = { structure = \"cable\", side = \"end\" }\nforce = [0, 0, -1]\n";
/// let loads = parse_loads(text, "<loads>".as_ref(), &scene.model, &scene.names)?;
/// assert_eq!(loads[0].particles, vec![4]);
/// # Ok::<(), flexdem_scene::SceneError>(())
/// ```
pub fn parse_loads(
    text: &str,
    source: &Path,
    model: &Model,
    names: &SceneNames,
) -> Result<Vec<Load>, SceneError> {
    let file = source.display().to_string();
    let ctx = Ctx { file: &file, text };
    let parsed: LoadsFile = toml::from_str(text).map_err(|e| ctx.toml_error(&e))?;
    let selector = Selector { ctx, model, names };
    parsed.loads.iter().map(|l| selector.load(l)).collect()
}

impl Selector<'_> {
    /// One `[[loads]]` table: its particles, force (on each, or a total shared equally),
    /// moment and ramp.
    pub(crate) fn load(&self, spec: &S<LoadSpec>) -> Result<Load, SceneError> {
        let ctx = self.ctx;
        let l = spec.get_ref();
        let particles = self.select(&l.select, "loads.select")?;
        let force = match (&l.force, &l.total_force) {
            (Some(f), None) => ctx.vec3(f, "loads.force", "N on each particle")?,
            (None, Some(f)) => ctx.vec3(f, "loads.total_force", "N")? / particles.len() as Real,
            (None, None) => Vec3::zeros(),
            (Some(_), Some(f)) => {
                return Err(ctx.at(f.span(), "loads.total_force", "give either `force` (on each particle) or `total_force` (shared equally), not both"))
            }
        };
        let torque = l
            .moment
            .as_ref()
            .map_or(Ok(Vec3::zeros()), |m| ctx.vec3(m, "loads.moment", "N·m on each particle"))?;
        if l.force.is_none() && l.total_force.is_none() && l.moment.is_none() {
            return Err(ctx.missing(
                spec.span(),
                "loads",
                "give `force`, `total_force` or `moment`",
            ));
        }
        let ramp = match &l.ramp {
            None => Ramp::Constant,
            Some(r) => Ramp::Linear {
                start: ctx.non_negative(&r.get_ref().start, "loads.ramp.start", "s")?,
                duration: ctx.positive(&r.get_ref().duration, "loads.ramp.duration", "s")?,
            },
        };
        Ok(Load { particles, force, torque, ramp })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::parse_scene;

    /// A net of 2 × 2 cells and a group of one sphere.
    fn scene() -> crate::Scene {
        let text = r#"
            [simulation]
            steps = 10
            [materials.m]
            young = 1e8
            poisson = 0.3
            density = 1000
            friction_angle_deg = 30
            [[structures]]
            name = "net"
            kind = "net"
            material = "m"
            node_radius = 0.01
            size = [1, 1]
            cells = [2, 2]
            [[spheres]]
            name = "rock"
            kind = "single"
            material = "m"
            center = [0.5, 0.5, 0.5]
            radius = 0.1
        "#;
        parse_scene(text, "scene.toml".as_ref()).expect("scene")
    }

    #[test]
    fn loads_select_by_the_scenes_names() {
        let s = scene();
        let text = "[[loads]]\nselect = { structure = \"net\", side = \"corners\" }\n\
                    total_force = [0, 0, -4]\n\
                    [[loads]]\nselect = { spheres = \"rock\" }\nmoment = [0, 0, 1]\n\
                    ramp = { start = 0.5, duration = 1 }\n";
        let loads = parse_loads(text, "<loads>".as_ref(), &s.model, &s.names).expect("loads");
        assert_eq!(loads[0].particles, vec![0, 2, 6, 8]);
        assert_eq!(loads[0].force, Vec3::new(0.0, 0.0, -1.0));
        assert_eq!(loads[1].particles, vec![9]);
        assert_eq!(loads[1].torque, Vec3::z());
        assert_eq!(loads[1].ramp, Ramp::Linear { start: 0.5, duration: 1.0 });
        assert!(parse_loads("", "<loads>".as_ref(), &s.model, &s.names).expect("none").is_empty());
    }

    #[test]
    fn errors_are_located_in_the_loads_text() {
        let s = scene();
        let text = "[[loads]]\nselect = { structure = \"nett\" }\nforce = [0, 0, 1]\n";
        let e = parse_loads(text, "<loads>".as_ref(), &s.model, &s.names).unwrap_err();
        let message = e.to_string();
        assert!(message.starts_with("<loads>:2:"), "{message}");
        assert!(message.contains("did you mean `net`?"), "{message}");
        let e = parse_loads("[[load]]\n", "<loads>".as_ref(), &s.model, &s.names).unwrap_err();
        assert!(e.to_string().contains("load"), "{e}");
    }

    #[test]
    fn without_names_only_ids_box_and_plane_select() {
        let s = scene();
        let names = SceneNames::unknown();
        let by_name = "[[loads]]\nselect = { spheres = \"rock\" }\nforce = [0, 0, 1]\n";
        let e = parse_loads(by_name, "<loads>".as_ref(), &s.model, &names).unwrap_err();
        assert!(e.to_string().contains("resumed from a checkpoint"), "{e}");
        let by_box =
            "[[loads]]\nselect = { box = { min = [0.4, 0.4, 0.4], max = [0.6, 0.6, 0.6] } }\n\
                      force = [0, 0, 1]\n";
        let loads = parse_loads(by_box, "<loads>".as_ref(), &s.model, &names).expect("box");
        assert_eq!(loads[0].particles, vec![9]);
    }
}
