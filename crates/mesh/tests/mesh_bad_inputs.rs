//! The malformed meshes of `tests/data/bad_meshes/`: each gives an error (never a panic)
//! that names the file and where (line for text, byte offset for binary data) and says what
//! was wrong.

use std::collections::BTreeSet;
use std::path::PathBuf;

use flexdem_mesh::read_mesh;

/// Where the error must point.
enum Where {
    /// `file:line:`
    Line(usize),
    /// `file: byte offset:` (also for the size and count of a binary file)
    Byte(usize),
}

use Where::{Byte, Line};

/// File, location, and a part of the message saying what was expected or found.
const CASES: &[(&str, Where, &str)] = &[
    ("empty.obj", Line(1), "no face (f) found"),
    ("obj_face_two_vertices.obj", Line(5), "expected at least 3 vertices for a face, found 2"),
    ("obj_index_out_of_range.obj", Line(10), "face index 9 out of range (8 vertices)"),
    ("obj_nan_vertex.obj", Line(1), "expected a finite number for coordinate x, found \"nan\""),
    ("obj_non_numeric.obj", Line(2), "expected a number for coordinate y, found \"zero\""),
    (
        "obj_relative_index_too_far.obj",
        Line(4),
        "relative face index -4 out of range (3 vertices so far)",
    ),
    ("obj_zero_index.obj", Line(5), "face index 0 is invalid"),
    ("obj_bad_corner.obj", Line(4), "found \"1/1/1/1\""),
    (
        "obj_short_vertex.obj",
        Line(2),
        "expected at least 3 numbers for a vertex (v x y z), found 2",
    ),
    ("obj_only_vertices.obj", Line(3), "no face (f) found"),
    ("gts_edge_missing_vertex.gts", Line(6), "index 4 out of range (1-based, 3 vertices)"),
    ("gts_truncated.gts", Line(13), "expected edge 5 of 18 (a b), found the end of the file"),
    ("gts_face_not_triangle.gts", Line(10), "edges 1 2 3 do not form a triangle"),
    (
        "gts_bad_header.gts",
        Line(1),
        "non-negative integer for the number of vertices, found \"eight\"",
    ),
    ("gts_face_edge_out_of_range.gts", Line(8), "index 4 out of range (1-based, 3 edges)"),
    (
        "gts_huge_count.gts",
        Line(2),
        "expected vertex 2 of 1000000000 (x y z), found the end of the file",
    ),
    ("gts_inf_vertex.gts", Line(3), "expected a finite number for coordinate y, found \"inf\""),
    (
        "mesh_triangle_out_of_range.mesh",
        Line(11),
        "triangle 2 uses vertex 9 but the file has 3 vertices",
    ),
    ("mesh_missing_triangles.mesh", Line(8), "no Triangles section"),
    ("mesh_dimension_2.mesh", Line(2), "expected Dimension 3, found 2"),
    (
        "mesh_truncated_vertices.mesh",
        Line(8),
        "expected a number for coordinate x, found \"Triangles\"",
    ),
    (
        "mesh_count_too_large.mesh",
        Line(4),
        "declared 1000 vertices but the rest of the file holds at most 4",
    ),
    (
        "mesh_inf_coordinate.mesh",
        Line(7),
        "expected a finite number for coordinate x, found \"inf\"",
    ),
    (
        "mesh_no_version.mesh",
        Line(1),
        "expected \"MeshVersionFormatted\" first, found \"Dimension\"",
    ),
    ("stl_ascii_truncated.stl", Line(12), "expected \"endsolid\", found the end of the file"),
    ("stl_ascii_two_vertices.stl", Line(6), "expected 3 vertices in a facet's loop, found 2"),
    ("stl_ascii_bad_number.stl", Line(6), "expected a number for coordinate z, found \"z\""),
    ("stl_ascii_empty_solid.stl", Line(2), "no facet found"),
    (
        "stl_too_short.stl",
        Byte(4),
        "too short for a binary STL: the file ends after 4 bytes, expected at least 84",
    ),
    (
        "stl_binary_wrong_size.stl",
        Byte(80),
        "binary STL declares 12 triangles (600 bytes of facets from byte 84) but the file holds 11",
    ),
    ("stl_binary_nan.stl", Byte(96), "triangle 1: expected a finite coordinate, found NaN"),
    ("msh_version3.msh", Line(2), "unsupported msh version 3.0 (supported: 2.2 and 4.1)"),
    ("msh_missing_nodes.msh", Line(8), "no $Nodes section"),
    ("msh_no_format.msh", Line(1), "expected $MeshFormat as the first section, found $Nodes"),
    (
        "msh_unterminated_section.msh",
        Line(4),
        "section $PhysicalNames has no $EndPhysicalNames line",
    ),
    ("msh22_node_three_numbers.msh", Line(7), "expected 4 numbers for a node (tag x y z), found 3"),
    ("msh22_unknown_node_tag.msh", Line(12), "node tag 99, which $Nodes does not define"),
    ("msh22_no_triangles.msh", Line(12), "no triangle (element type 2 or 9)"),
    (
        "msh22_count_too_small.msh",
        Line(8),
        "expected $EndNodes (or is the declared count too small?), found \"3 0 1 0\"",
    ),
    ("msh22_count_too_large.msh", Line(9), "expected node 4 of 4 (tag x y z), found $EndNodes"),
    ("msh22_nan_node.msh", Line(7), "expected a finite number for coordinate x, found \"NaN\""),
    ("msh22_duplicate_node_tag.msh", Line(8), "node tag 2 defined twice (first line 7)"),
    (
        "msh22_triangle_two_nodes.msh",
        Line(12),
        "expected 8 numbers for an element of type 2 with 2 tags, found 7",
    ),
    (
        "msh41_block_total_mismatch.msh",
        Line(5),
        "the header declares 5 nodes but the blocks hold 4",
    ),
    (
        "msh41_bad_coordinates.msh",
        Line(12),
        "expected 3 numbers for the coordinates of node 3, found 2",
    ),
    (
        "msh22_binary_truncated.msh",
        Line(13),
        "declared 15 nodes (28 bytes each) but only 90 bytes follow",
    ),
    (
        "msh41_binary_truncated.msh",
        Byte(1099),
        "expected 8 bytes for number of elements in the block, found the end of the file",
    ),
    ("msh22_binary_bad_byte_order.msh", Byte(20), "expected the integer 1 to tell the byte order"),
];

fn bad_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/data/bad_meshes")
}

#[test]
fn every_bad_mesh_gives_an_error_naming_the_file_and_the_place() {
    let mut failures = Vec::new();
    for (name, place, fragment) in CASES {
        let path = bad_dir().join(name);
        let shown = path.display().to_string();
        let message = match read_mesh(&path) {
            Ok(mesh) => {
                failures.push(format!(
                    "{name}: read without error ({} triangles)",
                    mesh.triangles.len()
                ));
                continue;
            }
            Err(error) => error.to_string(),
        };
        let prefix = match place {
            Line(line) => format!("{shown}:{line}: "),
            Byte(offset) => format!("{shown}: byte {offset}: "),
        };
        if !message.starts_with(&prefix) || !message.contains(fragment) {
            failures.push(format!("{name}: got {message:?}, expected {prefix:?} and {fragment:?}"));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn the_corpus_is_the_table_and_covers_every_format() {
    let on_disk: BTreeSet<String> = std::fs::read_dir(bad_dir())
        .unwrap()
        .map(|entry| entry.unwrap().file_name().into_string().unwrap())
        .filter(|name| name != "generate.py")
        .collect();
    let listed: BTreeSet<String> = CASES.iter().map(|(name, _, _)| name.to_string()).collect();
    assert_eq!(on_disk, listed, "every file of bad_meshes/ must be in CASES, and only those");
    assert!(listed.len() >= 20);
    for extension in ["msh", "stl", "obj", "gts", "mesh"] {
        let count = listed.iter().filter(|n| n.ends_with(&format!(".{extension}"))).count();
        assert!(count >= 5, "only {count} bad .{extension} files");
    }
}
