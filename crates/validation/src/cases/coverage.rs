//! Where each case of `shared/spec/validation.md` is validated: a unit test (file and test
//! name) or a section of this report.

/// One row of the coverage table: validation.md case number, its name, and where it is
/// validated (Markdown).
pub const COVERAGE: [(u32, &str, &str); 16] = [
    (1, "Axial bar", "unit test `axial_bar_elongation` in `tests/structural.rs`"),
    (
        2,
        "Cantilever, tip load",
        "unit tests `cantilever_beam_mode_matches_euler_bernoulli` and \
         `cantilever_yade_mode_matches_yade` in `tests/structural.rs`; node by node against YADE \
         in [`yade_cantilever`](#yade_cantilever)",
    ),
    (3, "Torsion", "unit test `torsion_twist_angle` in `tests/structural.rs`"),
    (4, "Cantilever frequency", "unit test `cantilever_first_frequency` in `tests/structural.rs`"),
    (
        5,
        "Mass",
        "unit test `validation_case_5_chain_mass` in `crates/elements/src/builders/chain.rs`",
    ),
    (6, "Catenary", "[`catenary`](#catenary)"),
    (
        7,
        "Sphere on a cylinder",
        "unit test `sphere_on_cylinder_splits_force_one_minus_t_t` in \
         `crates/elements/src/touching/tests.rs`; against YADE in \
         [`yade_force_splits`](#yade_force_splits)",
    ),
    (
        8,
        "Sphere on a PFacet",
        "unit test `sphere_on_pfacet_splits_force_by_barycentric_weights` in \
         `crates/elements/src/touching/tests.rs`; against YADE in \
         [`yade_force_splits`](#yade_force_splits)",
    ),
    (
        9,
        "One contact at a shared node",
        "unit tests `one_contact_at_a_node_shared_by_k_elements` and \
         `one_contact_near_a_node_despite_round_off` in `crates/elements/src/touching/tests.rs`; \
         against YADE (scene `node`) in [`yade_force_splits`](#yade_force_splits)",
    ),
    (
        10,
        "Sliding across elements",
        "unit test `sliding_across_elements_has_no_jump` in `tests/contacts.rs`",
    ),
    (
        11,
        "Normal impact, linear spring",
        "unit test `normal_impact_contact_time_and_restitution` in `tests/contacts.rs`; \
         [`chung_ooi_1`](#chung_ooi_1), [`chung_ooi_2`](#chung_ooi_2)",
    ),
    (
        12,
        "Oblique impact (Chung & Ooi test 4)",
        "unit test `oblique_impact_on_a_wall_in_gross_sliding` in `tests/contacts.rs`; the sweep \
         of angles in [`chung_ooi_4`](#chung_ooi_4)",
    ),
    (
        13,
        "Cylinder–cylinder parallel and crossed",
        "unit test `crossed_and_parallel_cylinders_touch_once_at_the_right_point` in \
         `crates/elements/src/touching/tests.rs`",
    ),
    (
        14,
        "Energy",
        "unit tests `energy_is_conserved_without_damping_or_friction` and \
         `energy_balance_closes_with_damping_and_friction` in `tests/energy.rs`",
    ),
    (15, "Brazier tube bending (paper §6)", "[`brazier`](#brazier)"),
    (
        16,
        "Impact on a tube (paper §7)",
        "[`impact_solid`](#impact_solid), [`impact_hollow`](#impact_hollow)",
    ),
];

/// The coverage section of the report (heading level 2).
pub fn coverage_markdown() -> String {
    let mut s = String::from(
        "## Coverage of validation.md\n\nEvery case of `shared/spec/validation.md` and where it \
         is validated (unit tests run with `cargo test`).\n\n| # | case | validated in |\n|---|---|---|\n",
    );
    for (number, name, place) in COVERAGE {
        s.push_str(&format!("| {number} | {name} | {place} |\n"));
    }
    s.push('\n');
    s
}
