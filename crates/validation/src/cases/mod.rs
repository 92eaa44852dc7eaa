//! The registered validation cases, one file per case family, in report order.

pub mod brazier;
pub mod chung_ooi;
pub mod coverage;
pub mod impact;
pub mod structural;
pub mod triaxial;
pub mod yade_force_splits;
pub mod yade_side_by_side;
pub mod yade_sphere_on_net;

use crate::report::{CaseReport, Context};
use crate::ValidationError;

/// A validation case: an id, a title and the function that runs it.
#[derive(Clone, Copy, Debug)]
pub struct Case {
    /// Short identifier, used by `flexdem validate --case ID`, in file names of its figures
    /// and as the report's anchor.
    pub id: &'static str,
    /// Title of its report section.
    pub title: &'static str,
    /// Whether `flexdem validate --quick` and `cargo test` run it.
    pub in_quick_subset: bool,
    /// Runs it.
    pub run: fn(&Context) -> Result<CaseReport, ValidationError>,
}

/// Every case, in report order.
pub fn cases() -> Vec<Case> {
    vec![
        Case {
            id: "catenary",
            title: "Catenary (validation.md case 6)",
            in_quick_subset: true,
            run: structural::run_catenary,
        },
        Case {
            id: "yade_cantilever",
            title: "Cantilever against YADE 2023.02a",
            in_quick_subset: true,
            run: yade_side_by_side::run_cantilever,
        },
        Case {
            id: "yade_sphere_on_net",
            title: "Sphere on a net against YADE 2023.02a",
            in_quick_subset: false,
            run: yade_sphere_on_net::run_sphere_on_net,
        },
        Case {
            id: "yade_force_splits",
            title: "Force splits among nodes against YADE 2023.02a",
            in_quick_subset: true,
            run: yade_force_splits::run_force_splits,
        },
        Case {
            id: "chung_ooi_1",
            title: "Chung & Ooi test 1: normal impact of a sphere on a rigid wall",
            in_quick_subset: true,
            run: chung_ooi::run_test_1,
        },
        Case {
            id: "chung_ooi_2",
            title: "Chung & Ooi test 2: normal impact of two identical spheres",
            in_quick_subset: true,
            run: chung_ooi::run_test_2,
        },
        Case {
            id: "chung_ooi_4",
            title: "Chung & Ooi test 4: oblique impact on a rigid wall",
            in_quick_subset: true,
            run: chung_ooi::run_test_4,
        },
        Case {
            id: "brazier",
            title: "Brazier buckling of a PFacet tube under an end moment (paper §6)",
            in_quick_subset: true,
            run: brazier::run,
        },
        Case {
            id: "impact_solid",
            title: "Paper §7: a solid sphere hits a PFacet tube",
            in_quick_subset: true,
            run: impact::impact_solid,
        },
        Case {
            id: "impact_hollow",
            title: "Paper §7: a hollow PFacet sphere hits a PFacet tube",
            in_quick_subset: true,
            run: impact::impact_hollow,
        },
        Case {
            id: "impact_long",
            title: "Paper §7 impacts run to 1 s: energy and self-contact through the rebound",
            in_quick_subset: false,
            run: impact::impact_long,
        },
        Case {
            id: "triaxial",
            title: "Drained triaxial tests: a PFacet membrane and rigid walls",
            in_quick_subset: false,
            run: triaxial::run,
        },
    ]
}
