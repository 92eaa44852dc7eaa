//! flexdem: a discrete element method engine for deformable structures (nets, geogrids,
//! cables, membranes, shells) made of spheres, cylinders and PFacets.
//!
//! This package re-exports the workspace crates so that validation tests and users can
//! depend on one name; each crate can also be used on its own.

pub use flexdem_contact as contact;
pub use flexdem_elements as elements;
pub use flexdem_geom as geom;
pub use flexdem_integrate as integrate;
pub use flexdem_io as io;
pub use flexdem_mesh as mesh;
pub use flexdem_output as output;
pub use flexdem_run as run;
pub use flexdem_scene as scene;
