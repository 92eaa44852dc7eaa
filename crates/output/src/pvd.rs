//! The `.pvd` collection file that makes ParaView read the frames as one time series.

use crate::vtk::escape_attribute;
use flexdem_geom::Real;

/// One data set of the time series: a part of a frame.
#[derive(Clone, Debug, PartialEq)]
pub struct PvdEntry {
    /// Simulated time of the frame (s).
    pub time: Real,
    /// Part number within the frame (0 particles, 1 connections, 2 PFacets, 3 contacts).
    pub part: u32,
    /// Name of the part (the block name in ParaView).
    pub name: String,
    /// File name, relative to the `.pvd`'s folder.
    pub file: String,
}

/// The XML of a `.pvd` file (a VTK `Collection`) listing `entries` in order, each as
/// `<DataSet timestep=".." group="" part=".." name=".." file=".."/>` with the time in
/// round-trip scientific notation.
pub fn pvd_xml(entries: &[PvdEntry]) -> String {
    let mut xml = String::from(
        "<?xml version=\"1.0\"?>\n\
         <VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n\
         <Collection>\n",
    );
    for e in entries {
        xml.push_str(&format!(
            "<DataSet timestep=\"{:e}\" group=\"\" part=\"{}\" name=\"{}\" file=\"{}\"/>\n",
            e.time,
            e.part,
            escape_attribute(&e.name),
            escape_attribute(&e.file)
        ));
    }
    xml.push_str("</Collection>\n</VTKFile>\n");
    xml
}
