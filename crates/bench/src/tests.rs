//! Scenes build at small sizes and run; results do not depend on the thread count.

use crate::report::{csv, step_times_csv, table_header, table_row, CSV_HEADER, STEP_TIMES_HEADER};
use crate::scenes::{membrane_cells, TUBE_IMPACT_DT};
use crate::*;
use flexdem_elements::Dofs;
use flexdem_geom::Vec3;
use flexdem_integrate::{Simulation, TimeStep};
use std::time::Duration;

fn close(a: Vec3, b: Vec3) -> bool {
    (a - b).norm() < 1e-12
}

#[test]
fn every_scene_builds_small_and_runs_a_few_steps() {
    for (scene, size) in
        [(SceneKind::TubeImpact, 640), (SceneKind::Membrane, 200), (SceneKind::Packing, 90)]
    {
        let case = Case::Scene(scene, size);
        let r = run_case(&case, 1, 2, StepChoice::Fixed(3)).unwrap();
        assert_eq!((&r.case, r.threads, r.warmup_steps, r.steps), (&case, 1, 2, 3));
        assert!(r.elements() > 0 && r.wall > Duration::ZERO, "{r:?}");
        assert!(r.ms_per_step() > 0.0 && r.ns_per_element_step() > 0.0 && r.dt > 0.0);
        let pct = r.stage_percent();
        assert!(pct.iter().all(|p| (0.0..=100.0 + 1e-9).contains(p)), "{pct:?}");
        assert!(r.stages.total() <= r.wall);
    }
}

#[test]
fn membrane_counts_and_spheres_touch_it_all_along() {
    let (model, settings) = SceneKind::Membrane.build(200).unwrap();
    let n = membrane_cells(200);
    assert_eq!(n, 10);
    assert_eq!(model.pfacets.len(), 2 * n * n);
    assert_eq!(model.connections.len(), 3 * n * n + 2 * n);
    let spheres = (n / 2) * (n / 2);
    assert_eq!(model.particles.len(), (n + 1) * (n + 1) + spheres);
    let mut sim = Simulation::new(model, settings).unwrap();
    // The spheres bounce on the membrane held by its edges and posts: contacts all along.
    for _ in 0..20 {
        sim.run(25).unwrap();
        let c = sim.contacts().len();
        assert!(c > spheres / 4 && c <= 2 * spheres, "{c} contacts for {spheres} spheres");
    }
    assert_eq!(membrane_cells(1_000_000), 707);
}

#[test]
fn packing_counts_and_walls() {
    let (model, settings) = SceneKind::Packing.build(1000).unwrap();
    assert_eq!(model.particles.len(), 1000);
    assert_eq!(model.walls.len(), 5);
    let p = &model.particles;
    for w in &model.walls {
        assert!((0..p.len()).all(|i| (p.pos[i] - w.point).dot(&w.normal) >= p.radius[i] - 1e-6));
    }
    // Every sphere stands on the one below or on the floor from the first step, for a while.
    let mut sim = Simulation::new(model, settings).unwrap();
    for steps in [1, 50, 200] {
        sim.run(steps).unwrap();
        let c = sim.contacts().len();
        assert!((900..=1500).contains(&c), "{c} contacts after {} steps", sim.steps());
    }
}

#[test]
fn tube_impact_is_the_scene_file_with_a_fixed_step_and_its_node_order() {
    let (model, settings) = SceneKind::TubeImpact.build(640).unwrap();
    assert_eq!(settings.time_step, TimeStep::Fixed(TUBE_IMPACT_DT));
    assert_eq!(
        (model.particles.len(), model.connections.len(), model.pfacets.len()),
        (337, 976, 640)
    );
    // the scene file builds node (i, j) at x = 0.04 j, y = 0.1 sin θ,
    // z = −0.1 cos θ, θ = 2πi/16, as node 16 j + i, and the PFacets
    // (i, j), (i+1, j), (i, j+1) and (i+1, j), (i+1, j+1), (i, j+1) per quad, in this order.
    let pos = &model.particles.pos;
    assert!(close(pos[0], Vec3::new(0.0, 0.0, -0.1)));
    assert!(close(pos[4], Vec3::new(0.0, 0.1, 0.0)));
    assert!(close(pos[8 + 16 * 10], Vec3::new(0.4, 0.0, 0.1)));
    assert_eq!(model.pfacets[0].nodes, [0, 1, 16]);
    assert_eq!(model.pfacets[1].nodes, [1, 17, 16]);
    assert_eq!(model.pfacets[639].nodes, [16 * 19, 16 * 20, 15 + 16 * 20]);
    assert!(close(pos[336], Vec3::new(0.4, 0.0, 0.207)));
    // Both end rings clamped, nothing else.
    let clamped: Vec<usize> =
        (0..337).filter(|&i| model.particles.blocked[i] == Dofs::ALL).collect();
    let rings: Vec<usize> = (0..16).chain(320..336).collect();
    assert_eq!(clamped, rings);
    // The fixed step is below the scene file's automatic step.
    let (model, mut settings) = SceneKind::TubeImpact.build(640).unwrap();
    settings.time_step = TimeStep::Auto { safety: 0.5 };
    let sim = Simulation::new(model, settings).unwrap();
    assert!(sim.dt() >= TUBE_IMPACT_DT, "automatic step {}", sim.dt());
}

#[test]
fn tube_impact_slows_the_sphere_down() {
    let (model, settings) = tube_impact_scene();
    let mut sim = Simulation::new(model, settings).unwrap();
    let mut touched = 0;
    for _ in 0..15 {
        sim.run(50).unwrap();
        touched += usize::from(!sim.contacts().is_empty());
        // The fixed step stays well below the critical step through the impact (the
        // scene's automatic step falls later, after 0.15 s).
        sim.update_time_step().unwrap();
        assert!(sim.critical_dt() > 1.5 * TUBE_IMPACT_DT, "critical {}", sim.critical_dt());
        assert_eq!(sim.dt(), TUBE_IMPACT_DT);
    }
    assert!(sim.warnings().is_empty(), "{:?}", sim.warnings());
    let vz = sim.model().particles.vel[336].z;
    assert_eq!(SceneKind::TubeImpact.probe(&sim), Some(("impactor_vz", vz)));
    assert!(vz > -1.8 && vz < 0.0, "impactor velocity {vz} m/s after 750 steps (from -2)");
    assert!(touched >= 10, "contacts at {touched} of 15 checks");
}

fn tube_impact_scene() -> (flexdem_elements::Model, flexdem_integrate::Settings) {
    SceneKind::TubeImpact.build(640).unwrap()
}

#[test]
fn small_membrane_gives_the_same_state_with_one_and_two_threads() {
    let one =
        run_case(&Case::Scene(SceneKind::Membrane, 300), 1, 5, StepChoice::Fixed(20)).unwrap();
    let two =
        run_case(&Case::Scene(SceneKind::Membrane, 300), 2, 5, StepChoice::Fixed(20)).unwrap();
    assert!(one.contacts > 0);
    assert_eq!(one.checksum, two.checksum);
    // ... and the checksum does see a change of state.
    let longer =
        run_case(&Case::Scene(SceneKind::Membrane, 300), 1, 5, StepChoice::Fixed(21)).unwrap();
    assert_ne!(one.checksum, longer.checksum);
}

#[test]
fn plan_reuses_the_first_step_count_and_compares_checksums() {
    let mut plan = Plan::quick(&[SceneKind::Packing]);
    plan.steps = None;
    plan.adaptive = StepChoice::Adaptive { target: Duration::from_millis(20), min: 2, max: 7 };
    let mut seen = 0;
    let rows = run_plan(&plan, |_| seen += 1).unwrap();
    assert_eq!((rows.len(), seen), (2, 2));
    assert_eq!(rows[0].result.steps, rows[1].result.steps);
    assert!((2..=7).contains(&rows[0].result.steps));
    assert_eq!(rows[0].same_as_first, None);
    assert_eq!(rows[1].same_as_first, Some(true));
    let header_cols = CSV_HEADER.split(',').count();
    let text = csv(&rows);
    assert_eq!(text.lines().count(), 3);
    assert!(text.lines().all(|l| l.split(',').count() == header_cols), "{text}");
    assert!(text.lines().nth(2).unwrap().contains(",identical,"), "{text}");
    // every timed step's wall time kept, in a run's whole wall time; the median one of them
    for r in rows.iter().map(|row| &row.result) {
        assert_eq!(r.step_walls.len() as u64, r.steps);
        assert!(r.step_walls.iter().sum::<Duration>() <= r.wall);
        let mut walls: Vec<f64> = r.step_walls.iter().map(|d| d.as_secs_f64() * 1e3).collect();
        walls.sort_by(f64::total_cmp);
        assert_eq!(r.median_step_ms(), walls[(walls.len() - 1) / 2]);
    }
    let steps = step_times_csv(&rows);
    let lines: Vec<&str> = steps.lines().collect();
    assert_eq!(lines[0], STEP_TIMES_HEADER);
    assert_eq!(lines.len() as u64, 1 + rows.iter().map(|r| r.result.steps).sum::<u64>());
    assert!(lines[1].starts_with("packing,200,1,0,"), "{steps}");
    assert!(lines.iter().all(|l| l.split(',').count() == 5), "{steps}");
    let header = table_header();
    let width = header.lines().next().unwrap().chars().count();
    assert!(rows.iter().all(|r| table_row(r).chars().count() == width));
}

#[test]
fn step_choice_clamps_the_adaptive_count() {
    let c = StepChoice::Adaptive { target: Duration::from_secs(1), min: 10, max: 1000 };
    assert_eq!(c.steps(Duration::from_millis(10)), 100);
    assert_eq!(c.steps(Duration::from_secs(5)), 10);
    assert_eq!(c.steps(Duration::ZERO), 1000);
    assert_eq!(c.steps(Duration::MAX), 10);
    assert_eq!(StepChoice::Fixed(7).steps(Duration::from_secs(5)), 7);
    let adaptive = StepChoice::Adaptive { target: Duration::from_secs(100), min: 3, max: 1000 };
    assert_eq!(run_case(&Case::Scene(SceneKind::Packing, 100), 1, 0, adaptive).unwrap().steps, 3);
}

#[test]
fn bad_input_is_an_error_naming_it() {
    let msg = |e: BenchError| e.to_string();
    assert!(msg(SceneKind::TubeImpact.build(1000).unwrap_err()).contains("tube_impact"));
    assert!(msg(SceneKind::Membrane.build(2).unwrap_err()).contains("membrane: size 2"));
    assert!(msg(SceneKind::Packing.build(0).unwrap_err()).contains("packing: size 0"));
    assert!(msg(SceneKind::parse("tube").unwrap_err()).contains("\"tube\""));
    assert_eq!(SceneKind::parse("membrane").unwrap(), SceneKind::Membrane);
    assert!(run_case(&Case::Scene(SceneKind::Packing, 100), 0, 1, StepChoice::Fixed(1)).is_err());
    assert!(run_case(&Case::Scene(SceneKind::Packing, 100), 1, 1, StepChoice::Fixed(0)).is_err());
}
