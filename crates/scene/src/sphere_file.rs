//! The plain sphere file: CSV with a header naming `x`, `y`, `z` and `radius` (m), one sphere
//! per row, so that a packing made once (or a sample settled by a run) can be reused by
//! `[[spheres]] kind = "file"`.

use crate::packing::MAX_PACKED_SPHERES;
use flexdem_geom::{Real, Vec3};
use std::fmt::Write as _;

/// The columns the file must name.
const COLUMNS: [&str; 4] = ["x", "y", "z", "radius"];

/// Writes spheres as CSV: the header `x,y,z,radius` then one row per sphere, every number
/// with the digits that read back to the same `f64`.
pub fn write_spheres(spheres: &[(Vec3, Real)]) -> String {
    let mut out = String::from("x,y,z,radius\n");
    for (c, r) in spheres {
        let _ = writeln!(out, "{:?},{:?},{:?},{:?}", c.x, c.y, c.z, r);
    }
    out
}

/// Reads a sphere file (see the module's doc). Blank lines and lines starting with `#` are
/// skipped; an error names the line and what is wrong.
pub fn read_spheres(text: &str) -> Result<Vec<(Vec3, Real)>, String> {
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.trim()))
        .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'));
    let Some((_, header)) = lines.next() else {
        return Err("the file is empty: expected a header `x,y,z,radius`".into());
    };
    let names: Vec<&str> = header.split(',').map(str::trim).collect();
    let mut index = [0usize; 4];
    for (slot, column) in index.iter_mut().zip(COLUMNS) {
        *slot = names.iter().position(|n| *n == column).ok_or_else(|| {
            format!("line 1: the header has no column `{column}` (it needs x, y, z and radius)")
        })?;
    }
    let mut spheres = Vec::new();
    for (line, row) in lines {
        let fields: Vec<&str> = row.split(',').map(str::trim).collect();
        if fields.len() != names.len() {
            return Err(format!(
                "line {line}: {} fields where the header has {}",
                fields.len(),
                names.len()
            ));
        }
        let value = |k: usize| -> Result<Real, String> {
            let text = fields[index[k]];
            let v: Real = text
                .parse()
                .map_err(|_| format!("line {line}: `{}` = `{text}` is not a number", COLUMNS[k]))?;
            if v.is_finite() {
                Ok(v)
            } else {
                Err(format!("line {line}: `{}` = {v} is not finite", COLUMNS[k]))
            }
        };
        let c = Vec3::new(value(0)?, value(1)?, value(2)?);
        let r = value(3)?;
        if r <= 0.0 {
            return Err(format!("line {line}: radius {r} must be > 0"));
        }
        if spheres.len() == MAX_PACKED_SPHERES {
            return Err(format!("more than {MAX_PACKED_SPHERES} spheres"));
        }
        spheres.push((c, r));
    }
    Ok(spheres)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spheres_written_read_back_exactly() {
        let s =
            vec![(Vec3::new(0.1, -2.0 / 3.0, 1e-9), 0.003), (Vec3::new(1.0, 2.0, 3.0), 1.0 / 7.0)];
        assert_eq!(read_spheres(&write_spheres(&s)).unwrap(), s);
    }

    #[test]
    fn columns_in_any_order_and_extra_columns_are_read() {
        let text = "# a packing\nid, radius, z, y, x\n0, 0.5, 3, 2, 1\n\n1, 0.25, 0, 0, 0\n";
        let s = read_spheres(text).unwrap();
        assert_eq!(s, vec![(Vec3::new(1.0, 2.0, 3.0), 0.5), (Vec3::zeros(), 0.25)]);
    }

    #[test]
    fn bad_files_name_the_line() {
        assert!(read_spheres("").unwrap_err().contains("empty"));
        assert!(read_spheres("x,y,r\n").unwrap_err().contains("no column `z`"));
        let e = read_spheres("x,y,z,radius\n1,2,3,0.1\n1,2,three,0.1\n").unwrap_err();
        assert!(e.starts_with("line 3") && e.contains("`z`"), "{e}");
        assert!(read_spheres("x,y,z,radius\n1,2,3\n").unwrap_err().contains("3 fields"));
        assert!(read_spheres("x,y,z,radius\n1,2,3,-1\n").unwrap_err().contains("must be > 0"));
        assert!(read_spheres("x,y,z,radius\n1,2,NaN,1\n").unwrap_err().contains("not finite"));
    }
}
