//! How much memory a scene's simulation will need, estimated from its element counts before
//! the simulation is built, and the refusal of a scene that does not fit in the memory the
//! machine has available (instead of an abort on a failed allocation in the middle of the
//! build or of the first step).

use flexdem_elements::Model;

/// Bytes per element (particle, connection or PFacet) of a running simulation, the model
/// included: `flexdem bench` measures about 600 B per element on the PFacet membrane from
/// 10⁴ to 10⁶ elements (bench/README.md); rounded up for the contacts of denser scenes.
pub const BYTES_PER_ELEMENT: u64 = 1024;

/// The estimated memory (bytes) of simulating `model`.
pub fn estimate_memory(model: &Model) -> u64 {
    let elements = model.particles.len() + model.connections.len() + model.pfacets.len();
    elements as u64 * BYTES_PER_ELEMENT
}

/// The memory available to a new process (bytes): `MemAvailable` of /proc/meminfo; None
/// where it cannot be read (then nothing is refused).
pub fn available_memory() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    kib.checked_mul(1024)
}

/// `x` bytes in words: `512 MiB`, `3.1 GiB`.
pub(crate) fn bytes(x: u64) -> String {
    const GIB: f64 = 1024.0 * 1024.0 * 1024.0;
    if (x as f64) < GIB {
        format!("{:.0} MiB", x as f64 / (1024.0 * 1024.0))
    } else {
        format!("{:.1} GiB", x as f64 / GIB)
    }
}

/// The message refusing `model` when its estimate exceeds `available` bytes.
pub(crate) fn too_large(model: &Model, available: Option<u64>) -> Option<String> {
    let available = available?;
    let need = estimate_memory(model);
    (need > available).then(|| {
        format!(
            "the scene so far ({} particles, {} connections, {} PFacets) needs about {} of \
             memory to simulate ({} B per element), more than the {} available: expected \
             fewer or coarser structures and spheres",
            model.particles.len(),
            model.connections.len(),
            model.pfacets.len(),
            bytes(need),
            BYTES_PER_ELEMENT,
            bytes(available)
        )
    })
}

/// The message refusing a structure of about `elements` elements (nodes, connections and
/// PFacets, from its counts) before it is built, when with the `base` bytes of the scene so
/// far ([`estimate_memory`]) it would exceed `available` bytes.
pub(crate) fn too_large_to_build(
    base: u64,
    elements: u64,
    available: Option<u64>,
) -> Option<String> {
    let available = available?;
    let need = base.saturating_add(elements.saturating_mul(BYTES_PER_ELEMENT));
    (need > available).then(|| {
        format!(
            "this structure has about {elements} elements (nodes, connections and PFacets): \
             with the rest of the scene the simulation would need about {} of memory ({} B \
             per element), more than the {} available: expected fewer cells, rings, segments \
             or subdivisions",
            bytes(need),
            BYTES_PER_ELEMENT,
            bytes(available)
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use flexdem_contact::Material;
    use flexdem_elements::builders::{chain, straight_line};
    use flexdem_elements::StructureOptions;
    use flexdem_geom::Vec3;

    #[test]
    fn a_scene_larger_than_the_memory_is_refused_with_the_estimate() {
        let mut model = Model::new();
        let mat = model.add_material(Material::new(1e7, 0.3, 1000.0, 0.5).unwrap()).unwrap();
        let points = straight_line(Vec3::zeros(), Vec3::x() * 100.0, 1000).unwrap();
        chain(&mut model, &points, &StructureOptions::new("c", 0.01, mat)).unwrap();
        // 1001 nodes + 1000 connections
        assert_eq!(estimate_memory(&model), 2001 * 1024);
        assert!(too_large(&model, Some(1 << 30)).is_none());
        assert!(too_large(&model, None).is_none());
        let message = too_large(&model, Some(1 << 20)).unwrap();
        assert!(message.contains("needs about 2 MiB"), "{message}");
        assert!(message.contains("more than the 1 MiB available"), "{message}");
        assert_eq!(bytes(3 << 30), "3.0 GiB");
        let base = estimate_memory(&model);
        let message = too_large_to_build(base, 10_000, Some(8 << 20)).unwrap();
        assert!(message.contains("about 10000 elements"), "{message}");
        assert!(message.contains("need about 12 MiB"), "{message}");
        assert!(too_large_to_build(base, 1000, Some(8 << 20)).is_none());
    }

    #[test]
    fn available_memory_is_read_on_linux() {
        if cfg!(target_os = "linux") {
            assert!(available_memory().is_some_and(|m| m > 0));
        }
    }
}
