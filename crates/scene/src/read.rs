//! Reading a scene file: its bytes as UTF-8 text, the TOML into the schema, then the build.

use crate::build::build;
use crate::error::{Ctx, SceneError};
use crate::scene::Scene;
use crate::schema;
use std::path::Path;

/// Reads and builds the scene file at `path`. Relative paths inside the file are relative to
/// its folder.
pub fn load_scene(path: &Path) -> Result<Scene, SceneError> {
    let bytes =
        std::fs::read(path).map_err(|source| SceneError::Io { path: path.to_owned(), source })?;
    let text = scene_text(bytes, path)?;
    parse_scene(&text, path)
}

/// The text of a scene file, or an error at the first byte that is not UTF-8 (line, column
/// and byte offset).
fn scene_text(bytes: Vec<u8>, path: &Path) -> Result<String, SceneError> {
    String::from_utf8(bytes).map_err(|e| {
        let valid = e.utf8_error().valid_up_to();
        let bytes = e.as_bytes();
        let before = std::str::from_utf8(&bytes[..valid]).unwrap_or_default();
        let file = path.display().to_string();
        let ctx = Ctx { file: &file, text: before };
        let bad: Vec<String> =
            bytes[valid..].iter().take(4).map(|b| format!("0x{b:02x}")).collect();
        ctx.at(
            valid..valid,
            "",
            format!(
                "invalid UTF-8 at byte {valid} ({}): a scene file must be UTF-8 text (save it \
                 as UTF-8)",
                bad.join(" ")
            ),
        )
    })
}

/// Builds a scene from its text. `source` names the file in messages and gives the folder
/// that relative paths (meshes, output) start from; it is not read.
pub fn parse_scene(text: &str, source: &Path) -> Result<Scene, SceneError> {
    let file = source.display().to_string();
    let ctx = Ctx { file: &file, text };
    let parsed: schema::SceneFile = toml::from_str(text).map_err(|e| ctx.toml_error(&e))?;
    build(parsed, ctx, source)
}
