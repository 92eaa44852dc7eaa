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

/// Puts spheres in the order of space: by the Morton code (bits of the x, y and z cell
/// indices interleaved) of the cell of side 2·r_max holding each centre, ties kept in the
/// order given. A run keeps the file's order as its particles' order, and the contact pass
/// reads each pair's particles and adds into their forces: with neighbours near in the
/// file, near in memory, those reads hit the cache (spheres in random order made the LAMMPS
/// twin's step 13–25 % slower). Positions and radii are unchanged.
pub fn in_space_order(spheres: &mut [(Vec3, Real)]) {
    let Some(r_max) = spheres.iter().map(|s| s.1).reduce(Real::max) else { return };
    let lo = spheres.iter().fold(Vec3::repeat(Real::INFINITY), |m, s| m.inf(&s.0));
    let side = 2.0 * r_max;
    // 21 bits per axis (2 million cells a side); a larger or non-finite cell index clamps
    let cell = |x: Real, lo: Real| {
        let c = ((x - lo) / side).floor();
        if c.is_finite() {
            c.clamp(0.0, ((1u64 << 21) - 1) as Real) as u64
        } else {
            0
        }
    };
    let code = |c: &Vec3| {
        let spread = |mut v: u64| {
            v &= 0x1f_ffff;
            v = (v | v << 32) & 0x1f_0000_0000_ffff;
            v = (v | v << 16) & 0x1f_0000_ff00_00ff;
            v = (v | v << 8) & 0x100f_00f0_0f00_f00f;
            v = (v | v << 4) & 0x10c3_0c30_c30c_30c3;
            (v | v << 2) & 0x1249_2492_4924_9249
        };
        spread(cell(c.x, lo.x)) | spread(cell(c.y, lo.y)) << 1 | spread(cell(c.z, lo.z)) << 2
    };
    spheres.sort_by_cached_key(|s| code(&s.0));
}

/// Reads a sphere file (see the module's doc). Blank lines and lines starting with `#` are
/// skipped; an error names the line and what is wrong.
pub fn read_spheres(text: &str) -> Result<Vec<(Vec3, Real)>, String> {
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.trim()))
        .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'));
    let Some((header_line, header)) = lines.next() else {
        return Err("the file is empty: expected a header `x,y,z,radius`".into());
    };
    let names: Vec<&str> = header.split(',').map(str::trim).collect();
    let mut index = [0usize; 4];
    for (slot, column) in index.iter_mut().zip(COLUMNS) {
        *slot = names.iter().position(|n| *n == column).ok_or_else(|| {
            format!(
                "line {header_line}: the header has no column `{column}` (it needs x, y, z and \
                 radius)"
            )
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
    fn spheres_in_space_order_are_those_given_with_neighbours_near() {
        // a 4 × 4 × 4 lattice of spacing 2r in a scrambled order
        let r = 0.5;
        let mut spheres: Vec<(Vec3, Real)> = (0..64)
            .map(|k| (k * 37) % 64)
            .map(|k| (Vec3::new((k % 4) as Real, (k / 4 % 4) as Real, (k / 16) as Real), r))
            .collect();
        let mut given = spheres.clone();
        in_space_order(&mut spheres);
        // the same spheres
        let key = |s: &(Vec3, Real)| (s.0.x, s.0.y, s.0.z);
        given.sort_by(|a, b| key(a).partial_cmp(&key(b)).unwrap());
        let mut sorted = spheres.clone();
        sorted.sort_by(|a, b| key(a).partial_cmp(&key(b)).unwrap());
        assert_eq!(sorted, given);
        // Morton order: each octant of 2 × 2 × 2 cells is 8 spheres in a row, and the first
        // is the corner
        assert_eq!(spheres[0].0, Vec3::zeros());
        for octant in spheres.chunks(8) {
            let corner = octant[0].0.map(|x| (x / 2.0).floor());
            assert!(octant.iter().all(|s| s.0.map(|x| (x / 2.0).floor()) == corner));
        }
        // nothing to order, one sphere, a NaN: no panic
        in_space_order(&mut []);
        let mut odd = vec![(Vec3::repeat(Real::NAN), 1.0), (Vec3::zeros(), 1.0)];
        in_space_order(&mut odd);
        assert_eq!(odd.len(), 2);
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
        // the header's own line, after comments and blank lines
        let e = read_spheres("# packing\n\nx,y,z,r\n").unwrap_err();
        assert!(e.starts_with("line 3: the header has no column `radius`"), "{e}");
        let e = read_spheres("x,y,z,radius\n1,2,3,0.1\n1,2,three,0.1\n").unwrap_err();
        assert!(e.starts_with("line 3") && e.contains("`z`"), "{e}");
        assert!(read_spheres("x,y,z,radius\n1,2,3\n").unwrap_err().contains("3 fields"));
        assert!(read_spheres("x,y,z,radius\n1,2,3,-1\n").unwrap_err().contains("must be > 0"));
        assert!(read_spheres("x,y,z,radius\n1,2,NaN,1\n").unwrap_err().contains("not finite"));
    }
}
