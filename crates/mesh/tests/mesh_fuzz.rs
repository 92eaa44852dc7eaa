//! Random bytes and random mutations of the valid meshes: every reader returns `Ok` or `Err`,
//! never panics, and what it returns is a well-formed mesh (indices in range, finite
//! coordinates).

mod support;

use flexdem_geom::TriMesh;
use flexdem_mesh::{read_msh, read_stl, MeshError};
use proptest::prelude::*;
use support::meshes::{reader_for, valid_bytes, well_formed, READERS, VALID};

/// A result is either an error naming the file, or a mesh that is safe to use.
fn check(result: Result<TriMesh, MeshError>, name: &str) -> Result<(), TestCaseError> {
    well_formed(result, name).map_err(TestCaseError::fail)
}

/// One edit of a file's bytes.
#[derive(Clone, Debug)]
enum Mutation {
    /// Overwrite the byte at (position modulo length).
    Set(usize, u8),
    /// Remove `len` bytes from a position.
    Delete(usize, usize),
    /// Insert bytes at a position.
    Insert(usize, Vec<u8>),
    /// Cut the file at a position.
    Truncate(usize),
    /// Replace a digit by another digit (keeps text files parseable, changes counts/indices).
    Digit(usize, u8),
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        (any::<usize>(), any::<u8>()).prop_map(|(p, b)| Mutation::Set(p, b)),
        (any::<usize>(), 1..40usize).prop_map(|(p, n)| Mutation::Delete(p, n)),
        (any::<usize>(), prop::collection::vec(any::<u8>(), 1..12))
            .prop_map(|(p, b)| Mutation::Insert(p, b)),
        (any::<usize>(), prop::sample::select(b"-0 \n$#/nanf9".to_vec()))
            .prop_map(|(p, b)| Mutation::Insert(p, vec![b])),
        any::<usize>().prop_map(Mutation::Truncate),
        (any::<usize>(), b'0'..=b'9').prop_map(|(p, d)| Mutation::Digit(p, d)),
    ]
}

fn apply(bytes: &mut Vec<u8>, mutation: &Mutation) {
    let len = bytes.len().max(1);
    match mutation {
        Mutation::Set(p, b) => {
            if let Some(slot) = bytes.get_mut(p % len) {
                *slot = *b;
            }
        }
        Mutation::Delete(p, n) => {
            let start = (p % len).min(bytes.len());
            let end = (start + n).min(bytes.len());
            bytes.drain(start..end);
        }
        Mutation::Insert(p, inserted) => {
            let at = (p % (bytes.len() + 1)).min(bytes.len());
            bytes.splice(at..at, inserted.iter().copied());
        }
        Mutation::Truncate(p) => bytes.truncate(p % len),
        Mutation::Digit(p, d) => {
            let digits: Vec<usize> = bytes
                .iter()
                .enumerate()
                .filter(|(_, b)| b.is_ascii_digit())
                .map(|(i, _)| i)
                .collect();
            if !digits.is_empty() {
                bytes[digits[p % digits.len()]] = *d;
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    #[test]
    fn random_bytes_never_panic(bytes in prop::collection::vec(any::<u8>(), 0..600)) {
        for (ext, reader) in READERS {
            let name = format!("random.{ext}");
            check(reader(&bytes, &name), &name)?;
        }
    }

    #[test]
    fn random_text_lines_never_panic(
        lines in prop::collection::vec("[ -~]{0,30}", 0..40),
        ext in prop::sample::select(vec!["msh", "stl", "obj", "gts", "mesh"]),
    ) {
        // Printable text with the keywords of the formats mixed in.
        let text = lines.join("\n");
        let text = text.replace('A', "\nv ").replace('B', "\nf ").replace('C', "\n$Nodes\n")
            .replace('D', "\n$EndNodes\n").replace('E', "\nVertices\n").replace('F', "\nTriangles\n")
            .replace('G', "\nfacet normal 0 0 1\nouter loop\n").replace('H', "\n$MeshFormat\n2.2 0 8\n$EndMeshFormat\n");
        let name = format!("text.{ext}");
        check(reader_for(&name)(text.as_bytes(), &name), &name)?;
    }

    #[test]
    fn mutated_valid_files_never_panic(
        file in prop::sample::select(VALID.to_vec()),
        mutations in prop::collection::vec(mutation(), 1..6),
    ) {
        let mut bytes = valid_bytes(file);
        for m in &mutations {
            apply(&mut bytes, m);
        }
        check(reader_for(file)(&bytes, file), file)?;
        // Other readers on the same bytes must not panic either.
        for (ext, reader) in READERS {
            let name = format!("mutated.{ext}");
            check(reader(&bytes, &name), &name)?;
        }
    }
}

#[test]
fn valid_files_pass_the_fuzz_check_unmutated() {
    for file in VALID {
        let result = reader_for(file)(&valid_bytes(file), file);
        assert!(result.is_ok(), "{file}: {:?}", result.err());
        check(result, file).unwrap();
    }
}

/// Huge declared counts in binary data are rejected from the sizes, before any allocation.
#[test]
fn huge_declared_counts_are_rejected_without_allocating() {
    // Binary STL: 4 billion triangles declared in an 84-byte file.
    let mut stl = vec![0u8; 80];
    stl.extend_from_slice(&u32::MAX.to_le_bytes());
    let message = read_stl(&stl, "huge.stl").unwrap_err().to_string();
    assert!(message.starts_with("huge.stl: byte 80: "), "{message}");
    assert!(message.contains("declares 4294967295 triangles"), "{message}");
    assert!(message.contains("but the file holds 0"), "{message}");

    // msh 4.1 binary: the first node block of the cube claims 2^60 nodes.
    let mut msh = valid_bytes("cube_v41_binary.msh");
    let nodes = msh.windows(7).position(|w| w == b"$Nodes\n").unwrap() + 7;
    // Header: 4 size_t; then block: 3 ints and the size_t count.
    let count_at = nodes + 4 * 8 + 3 * 4;
    msh[count_at..count_at + 8].copy_from_slice(&(1u64 << 60).to_le_bytes());
    let message = read_msh(&msh, "huge.msh").unwrap_err().to_string();
    assert!(message.contains("declared 1152921504606846976 nodes"), "{message}");
    assert!(message.contains("bytes follow"), "{message}");

    // msh 2.2 binary: element count line claims 10^18 elements.
    let text = valid_bytes("cube_v22_binary.msh");
    let at = text.windows(10).position(|w| w == b"$Elements\n").unwrap() + 10;
    let end = at + text[at..].iter().position(|&b| b == b'\n').unwrap();
    let mut msh = text[..at].to_vec();
    msh.extend_from_slice(b"1000000000000000000");
    msh.extend_from_slice(&text[end..]);
    assert!(read_msh(&msh, "huge22.msh").is_err());
}
