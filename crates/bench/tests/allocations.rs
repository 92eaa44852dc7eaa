//! A step allocates no memory once the run is under way (a small fixed cost per step: no
//! per-step allocation): the engine's buffers keep their memory from step to step and only
//! grow when a scene holds more (pairs, contacts, touchings) than it ever did. Counted by
//! dhat's allocator in its testing mode, on the benchmark scenes, in a one-thread pool as
//! `flexdem bench` runs them. Before the buffers were kept: 4 to 6 allocations per step.

use flexdem_bench::scenes::{membrane, packing, tube_impact};
use flexdem_elements::Model;
use flexdem_integrate::{Settings, Simulation};

/// Allocations a rebuild of the candidate pairs may make in these scenes of about a
/// thousand elements (measured 46 for the packing, 13 for the membrane and the tube): its
/// lists, its chunks' buffers, one array of contacts per block of 512 candidates.
const BUILD_LIMIT: f64 = 100.0;

#[global_allocator]
static ALLOC: dhat::Alloc = dhat::Alloc;

/// Allocations over `steps` steps after `warmup`, in a pool of `threads`: per step that did not
/// rebuild the candidate pairs, and per rebuild (the steps that did), with the rebuilds.
fn allocations(
    scene: (Model, Settings),
    threads: usize,
    warmup: usize,
    steps: usize,
) -> (f64, f64, u64) {
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
    pool.install(|| {
        let (model, settings) = scene;
        let mut sim = Simulation::new(model, settings).unwrap();
        for _ in 0..warmup {
            sim.step().unwrap();
        }
        let (mut plain, mut plain_steps, mut at_builds, mut builds) = (0, 0, 0, 0);
        for _ in 0..steps {
            let (blocks, built) = (dhat::HeapStats::get().total_blocks, sim.collider().builds);
            sim.step().unwrap();
            let made = dhat::HeapStats::get().total_blocks - blocks;
            if sim.collider().builds > built {
                at_builds += made;
                builds += 1;
            } else {
                plain += made;
                plain_steps += 1;
            }
        }
        let per_build = if builds > 0 { at_builds as f64 / builds as f64 } else { 0.0 };
        (plain as f64 / plain_steps.max(1) as f64, per_build, builds)
    })
}

#[test]
fn steps_allocate_nothing() {
    let _profiler = dhat::Profiler::builder().testing().build();
    for (name, scene) in [
        ("packing", packing(1000).unwrap()),
        ("membrane", membrane(1000).unwrap()),
        ("tube_impact", tube_impact().unwrap()),
    ] {
        let (per_step, per_build, builds) = allocations(scene, 1, 300, 1000);
        println!("{name}: {per_step} allocations per step, {per_build} per rebuild ({builds})");
        // a step that keeps its candidate pairs allocates next to nothing (measured 0.085,
        // 0.009 and 0.058): a block of contacts growing or shrunk at a layout, a buffer
        // growing once or twice (the tube is crushed all along, its buffers grow with it)
        assert!(per_step < 0.1, "{name}: {per_step} allocations per step: a buffer not kept?");
        // a rebuild makes its pair lists (the free spheres' become the neighbour list's
        // keys), its chunks' buffers and the contacts' blocks anew: memory a large scene
        // gives back between builds; a bounded number of arrays, not one per pair
        assert!(per_build < BUILD_LIMIT, "{name}: {per_build} allocations per rebuild");
    }
    // at 2 threads, in scenes of several chunks whose loops share their items by the
    // particles' homes (`homes.rs`, their pieces on the stack) and step the pairs in parts:
    // nothing more than at one thread. (A settling packing of 10⁴ spheres gives its blocks
    // of contacts room back and takes it again at their layouts: 0.740 allocations per step
    // at 1 thread, 0.755 at 2; one profiler per process, so here.)
    for (name, scene) in [("packing", packing(10_000)), ("membrane", membrane(10_000))] {
        let scene = scene.unwrap();
        let (one, _, _) = allocations(scene.clone(), 1, 50, 200);
        let (two, _, builds) = allocations(scene, 2, 50, 200);
        println!("{name}: {one} allocations per step at 1 thread, {two} at 2 ({builds} rebuilds)");
        assert!(two <= one + 0.05, "{name}: {two} allocations per step at 2 threads, {one} at 1");
    }
}
