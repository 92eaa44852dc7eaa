//! Output of a run: VTK XML PolyData frames for ParaView tied together by a `.pvd` time series,
//! a CSV series of chosen quantities, and a PNG plot of them at the end; and [`chart`], the
//! PNG line charts those plots (and the validation report's figures) are drawn with.
//!
//! What to write is plain data, [`OutputSettings`] (the scene reader fills it from a scene's
//! `[output]` table); [`Output`] writes it as a run goes and reports how far it got as
//! [`OutputProgress`], which a checkpoint stores so that a resumed run continues the same
//! files ([`Output::resume`]).
//!
//! Feature `plot` (on by default) draws the PNG files, with plotters; without it (the scene
//! reader's view of this crate) the settings, VTK and CSV remain and a plot asked for is an
//! error.
//!
//! File layout in [`OutputSettings::directory`], for a frame at step `N` (6 digits or more):
//!
//! - `particles_N.vtp`: every particle (free spheres and structure nodes) as a point with a
//!   vertex cell; point data `id`, `radius`, `velocity`, `angular_velocity`, `force` (total
//!   force at the last step), `kind` (0 sphere, 1 node), `structure` (−1 for free spheres),
//!   `material`.
//! - `connections_N.vtp`: the nodes of connections as points (point data `id`: the particle
//!   id) and one line cell per connection; cell data `radius`, `axial_force` (the link's normal
//!   force, **compression positive, tension negative**, as everywhere in flexdem),
//!   `shear_force`, `broken` (0/1), `status` (0 cohesive, 1 frictional, 2 broken),
//!   `structure`, `material`.
//! - `pfacets_N.vtp`: the nodes of PFacets as points (point data `id`) and one triangle per
//!   PFacet; cell data `radius`, `structure`, `material`.
//! - `contacts_N.vtp`: one line per contact from the centre of site 1 to the centre of site 2
//!   (the contact point for a wall site); cell data `normal_force` (compression positive),
//!   `force` (on body 2), `shear_force`, `point` (the contact point), `kind1`, `kind2` (0
//!   particle, 1 edge, 2 face, 3 wall).
//! - `flexdem.pvd`: the time series, four parts per frame at the simulated time; ParaView
//!   opens it as a multiblock data set with one block per part. It is rewritten after each of
//!   the first [`PVD_REWRITE_PERIOD`] frames, then every [`PVD_REWRITE_PERIOD`] frames, and by
//!   [`Output::finish`].
//! - `series.csv`: a header row `time_s,step,...` with units in the column names, then one row
//!   per recorded step (see [`series_columns`]).
//! - `series.png`: one panel per series, time on the x axis.
//!
//! Data arrays are Float64/Int32/Int64/UInt8, little-endian, base64 inline binary
//! (`header_type="UInt64"`), so values round-trip exactly. Every file but the CSV is written
//! to a temporary file in the same folder and renamed over the old one, so a failed write
//! leaves the files already written intact; CSV rows are appended and flushed one by one.

#[cfg(feature = "plot")]
pub mod chart;
mod error;
mod files;
mod frames;
#[cfg(feature = "plot")]
mod plot;
mod pvd;
mod series;
mod table;
pub mod triaxial;
mod vtk;
mod writer;

pub use error::OutputError;
pub use files::same_file;
pub use frames::{connections_polydata, contacts_polydata, particles_polydata, pfacets_polydata};
#[cfg(feature = "plot")]
pub use plot::plot_series;
pub use pvd::{pvd_xml, PvdEntry};
pub use series::{
    header_columns, row_values, series_columns, series_values, validate_series, OutputSettings,
    Quantity, SeriesSpec,
};
pub use table::{format_number, CsvSeries};
pub use vtk::{ArrayValues, CellKind, DataArray, PolyData};
pub use writer::{
    check_output_settings, frame_file_name, pvd_path, write_frame, Output, OutputProgress,
    OutputReport, CSV_FILE, PLOT_FILE, PVD_FILE, PVD_REWRITE_PERIOD,
};
