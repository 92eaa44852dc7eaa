//! Variants of each format beyond the committed cube files: byte orders, sizes, line endings,
//! keyword case, polygons, relative indices, skipped elements and sections.

use flexdem_geom::Vec3;
use flexdem_mesh::{read_gts, read_medit, read_msh, read_obj, read_stl};

/// A 2.2 binary file of one triangle, with the given byte order; node tags 7, 3, 5.
fn msh22_binary(big_endian: bool) -> Vec<u8> {
    let int = |v: i32| if big_endian { v.to_be_bytes() } else { v.to_le_bytes() };
    let real = |v: f64| if big_endian { v.to_be_bytes() } else { v.to_le_bytes() };
    let mut bytes = b"$MeshFormat\n2.2 1 8\n".to_vec();
    bytes.extend(int(1));
    bytes.extend(b"\n$EndMeshFormat\n$Nodes\n3\n");
    for (tag, x, y) in [(7, 0.0, 0.0), (3, 2.0, 0.0), (5, 0.0, 3.0)] {
        bytes.extend(int(tag));
        for v in [x, y, -1.5] {
            bytes.extend(real(v));
        }
    }
    bytes.extend(b"\n$EndNodes\n$Elements\n2\n");
    // A line element (type 1, 2 tags), then a triangle (type 2, 2 tags).
    for header in [[1, 1, 2], [2, 1, 2]] {
        for v in header {
            bytes.extend(int(v));
        }
        let nodes: &[i32] = if header[0] == 1 { &[7, 3] } else { &[7, 3, 5] };
        for v in [1, 99, 1].iter().chain(nodes) {
            bytes.extend(int(*v));
        }
    }
    bytes.extend(b"\n$EndElements\n");
    bytes
}

#[test]
fn msh22_binary_reads_either_byte_order() {
    for big_endian in [false, true] {
        let mesh = read_msh(&msh22_binary(big_endian), "t.msh").unwrap();
        assert_eq!(mesh.triangles, vec![[0, 1, 2]]);
        assert_eq!(mesh.vertices[2], Vec3::new(0.0, 3.0, -1.5));
    }
}

#[test]
fn msh41_binary_with_4_byte_size_t_and_parametric_nodes() {
    let mut bytes = b"$MeshFormat\n4.1 1 4\n".to_vec();
    bytes.extend(1i32.to_le_bytes());
    bytes.extend(
        b"\n$EndMeshFormat\n$Entities\n\x00\n\x01binary junk $EndNodes\n$EndEntities\n$Nodes\n",
    );
    let size = |v: u32| v.to_le_bytes();
    for v in [1, 3, 1, 3] {
        bytes.extend(size(v));
    }
    // One block on a surface (dim 2), parametric: x y z u v per node.
    for v in [2i32, 1, 1] {
        bytes.extend(v.to_le_bytes());
    }
    bytes.extend(size(3));
    for tag in [1, 2, 3] {
        bytes.extend(size(tag));
    }
    for xyz in [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]] {
        for v in xyz.iter().chain(&[0.25, 0.75]) {
            bytes.extend(f64::to_le_bytes(*v));
        }
    }
    bytes.extend(b"\n$EndNodes\n$Elements\n");
    for v in [1, 1, 1, 1] {
        bytes.extend(size(v));
    }
    for v in [2i32, 1, 2] {
        bytes.extend(v.to_le_bytes());
    }
    bytes.extend(size(1));
    for v in [1, 3, 2, 1] {
        bytes.extend(size(v));
    }
    bytes.extend(b"\n$EndElements\n");
    let mesh = read_msh(&bytes, "t.msh").unwrap();
    assert_eq!(mesh.triangles, vec![[2, 1, 0]]);
    assert_eq!(mesh.vertices[1], Vec3::new(1.0, 0.0, 0.0));
}

#[test]
fn msh_ascii_with_crlf_parametric_nodes_and_unknown_element_types() {
    let v41 = "$MeshFormat\r\n4.1 0 8\r\n$EndMeshFormat\r\n$Nodes\r\n1 3 1 3\r\n1 1 1 3\r\n1\r\n2\r\n3\r\n\
               0 0 0 0\r\n1 0 0 0.5\r\n0 1 0 1\r\n$EndNodes\r\n$Elements\r\n2 2 1 2\r\n\
               1 1 1 1\r\n1 1 2\r\n2 1 2 1\r\n2 1 2 3\r\n$EndElements\r\n";
    let mesh = read_msh(v41.as_bytes(), "t.msh").unwrap();
    assert_eq!(mesh.triangles, vec![[0, 1, 2]]);
    // 2.2 ASCII: an element type flexdem does not know (200) is skipped whatever its length.
    let v22 = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0 0\n2 1 0 0\n3 0 1 0\n$EndNodes\n\
               $Elements\n2\n1 200 0 1 2 3 4 5 6 7\n2 2 0 3 2 1\n$EndElements\n$NodeData\nwhatever\n$EndNodeData\n";
    let mesh = read_msh(v22.as_bytes(), "t.msh").unwrap();
    assert_eq!(mesh.triangles, vec![[2, 1, 0]]);
}

#[test]
fn msh41_ascii_rejects_version_4_0() {
    let text = "$MeshFormat\n4 0 8\n$EndMeshFormat\n";
    let message = read_msh(text.as_bytes(), "old.msh").unwrap_err().to_string();
    assert_eq!(message, "old.msh:2: unsupported msh version 4 (supported: 2.2 and 4.1)");
}

#[test]
fn stl_ascii_keywords_in_any_case_several_solids_and_leading_blanks() {
    let text = "\n  SOLID a\nFacet Normal 0 0 1\n Outer Loop\n  Vertex 0 0 0\n  VERTEX 1 0 0\n  vertex 0 1 0\n \
                EndLoop\nENDFACET\nendsolid a\nsolid b\nfacet normal 0 0 0\nouter loop\nvertex 0 0 1e0\n\
                vertex 1 0 1\nvertex 0 1 1\nendloop\nendfacet\nendsolid\n";
    let mesh = read_stl(text.as_bytes(), "t.stl").unwrap();
    assert_eq!(mesh.triangles, vec![[0, 1, 2], [3, 4, 5]]);
    assert_eq!(mesh.vertices[3], Vec3::new(0.0, 0.0, 1.0));
}

#[test]
fn stl_binary_is_detected_by_size_whatever_the_header() {
    for header in [&b"solid but binary"[..], &b"anything"[..]] {
        let mut bytes = header.to_vec();
        bytes.resize(80, b' ');
        bytes.extend(1u32.to_le_bytes());
        for v in [0.0f32, 0.0, 1.0, 0.0, 0.0, 0.0, 2.0, 0.0, 0.0, 0.0, 2.0, 0.0] {
            bytes.extend(v.to_le_bytes());
        }
        bytes.extend([0, 0]);
        let mesh = read_stl(&bytes, "t.stl").unwrap();
        assert_eq!(
            mesh.vertices,
            vec![Vec3::zeros(), Vec3::new(2.0, 0.0, 0.0), Vec3::new(0.0, 2.0, 0.0)]
        );
    }
}

#[test]
fn obj_polygons_fan_relative_indices_and_forward_references() {
    // A pentagon written before its vertices (forward references), and a relative triangle.
    let text = "f 1 2 3 4 5\nv 0 0 0\nv 1 0 0\nv 2 1 0\nv 1 2 0 1.0\nv 0 1 0 # w given\n\
                f -5/1/1 -4//2 -1/3\r\nl 1 2\np 3\n";
    let mesh = read_obj(text, "t.obj").unwrap();
    assert_eq!(mesh.triangles, vec![[0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 1, 4]]);
    assert_eq!(mesh.vertices.len(), 5);
}

#[test]
fn obj_drops_vertices_no_face_uses() {
    let text = "v 9 9 9\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 2 3 4\n";
    let mesh = read_obj(text, "t.obj").unwrap();
    assert_eq!(mesh.vertices.len(), 3);
    assert_eq!(mesh.triangles, vec![[0, 1, 2]]);
}

#[test]
fn gts_with_comments_and_class_names() {
    let text = "# a triangle\n3 3 1 GtsSurface GtsFace GtsEdge GtsVertex\n0 0 0\n1 0 0\n0 1 0\n\
                # edges, some reversed\n2 1\n3 2\n1 3\n1 2 3\n";
    let mesh = read_gts(text, "t.gts").unwrap();
    assert_eq!(mesh.triangles, vec![[0, 1, 2]]);
}

#[test]
fn medit_keywords_in_any_case_free_layout_and_no_end() {
    let text = "meshversionformatted 1 dimension\n3\nVERTICES 3 0 0 0 1 1 0 0 1\n0 1 0 1\n\
                Edges 1 1 2 0\nRequiredVertices 1 1\ntriangles 1\n3 2 1 7\n";
    let mesh = read_medit(text, "t.mesh").unwrap();
    assert_eq!(mesh.triangles, vec![[2, 1, 0]]);
    assert_eq!(mesh.vertices[2], Vec3::new(0.0, 1.0, 0.0));
}

/// A strip of `n` triangles over `n + 2` nodes, as msh 2.2 ASCII, OBJ and MEDIT text.
fn large_texts(n: usize) -> [String; 3] {
    let mut msh = format!("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n{}\n", n + 2);
    let mut obj = String::new();
    let mut medit = format!("MeshVersionFormatted 2\nDimension 3\nVertices\n{}\n", n + 2);
    for k in 0..n + 2 {
        let (x, y) = ((k / 2) as f64 * 0.125, (k % 2) as f64);
        msh += &format!("{} {x} {y} 0\n", k + 1);
        obj += &format!("v {x} {y} 0\n");
        medit += &format!("{x} {y} 0 0\n");
    }
    msh += &format!("$EndNodes\n$Elements\n{n}\n");
    medit += &format!("Triangles\n{n}\n");
    for k in 1..=n {
        msh += &format!("{k} 2 2 1 1 {k} {} {}\n", k + 1, k + 2);
        obj += &format!("f {k} {} {}\n", k + 1, k + 2);
        medit += &format!("{k} {} {} 0\n", k + 1, k + 2);
    }
    msh += "$EndElements\n";
    [msh, obj, medit]
}

#[test]
fn large_files_read_in_linear_time() {
    // 200 000 triangles (several MB): quadratic work (say, counting lines from the start of
    // the file for every number) would take minutes.
    let n = 200_000;
    let [msh, obj, medit] = large_texts(n);
    let start = std::time::Instant::now();
    assert_eq!(read_msh(msh.as_bytes(), "big.msh").unwrap().triangles.len(), n);
    assert_eq!(read_obj(&obj, "big.obj").unwrap().triangles.len(), n);
    assert_eq!(read_medit(&medit, "big.mesh").unwrap().triangles.len(), n);
    let elapsed = start.elapsed();
    assert!(elapsed.as_secs_f64() < 20.0, "took {elapsed:?}");
}
