//! A minimal VTK XML PolyData (`.vtp`) writer: points, one kind of cell, point and cell data,
//! every array inline as base64 binary (little-endian, `header_type="UInt64"`).

/// The values of a data array, in VTK's scalar types.
#[derive(Clone, Debug, PartialEq)]
pub enum ArrayValues {
    /// `Float64`.
    Float64(Vec<f64>),
    /// `Int32`.
    Int32(Vec<i32>),
    /// `Int64`.
    Int64(Vec<i64>),
    /// `UInt8`.
    UInt8(Vec<u8>),
}

impl ArrayValues {
    /// VTK's name of the scalar type.
    fn type_name(&self) -> &'static str {
        match self {
            ArrayValues::Float64(_) => "Float64",
            ArrayValues::Int32(_) => "Int32",
            ArrayValues::Int64(_) => "Int64",
            ArrayValues::UInt8(_) => "UInt8",
        }
    }

    /// Number of scalars.
    pub fn len(&self) -> usize {
        match self {
            ArrayValues::Float64(v) => v.len(),
            ArrayValues::Int32(v) => v.len(),
            ArrayValues::Int64(v) => v.len(),
            ArrayValues::UInt8(v) => v.len(),
        }
    }

    /// True when there are no scalars.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The scalars as little-endian bytes.
    fn to_le_bytes(&self) -> Vec<u8> {
        match self {
            ArrayValues::Float64(v) => v.iter().flat_map(|x| x.to_le_bytes()).collect(),
            ArrayValues::Int32(v) => v.iter().flat_map(|x| x.to_le_bytes()).collect(),
            ArrayValues::Int64(v) => v.iter().flat_map(|x| x.to_le_bytes()).collect(),
            ArrayValues::UInt8(v) => v.clone(),
        }
    }
}

/// A named data array of `components` scalars per point or cell.
#[derive(Clone, Debug, PartialEq)]
pub struct DataArray {
    /// Name shown in ParaView.
    pub name: String,
    /// Scalars per tuple (1 for a scalar field, 3 for a vector).
    pub components: usize,
    /// The scalars, tuple after tuple.
    pub values: ArrayValues,
}

impl DataArray {
    /// A scalar Float64 array.
    pub fn scalars(name: &str, values: Vec<f64>) -> Self {
        DataArray { name: name.into(), components: 1, values: ArrayValues::Float64(values) }
    }

    /// A Float64 array of 3-vectors.
    pub fn vectors(name: &str, values: impl IntoIterator<Item = [f64; 3]>) -> Self {
        let flat = values.into_iter().flatten().collect();
        DataArray { name: name.into(), components: 3, values: ArrayValues::Float64(flat) }
    }

    /// A scalar Int32 array.
    pub fn integers(name: &str, values: Vec<i32>) -> Self {
        DataArray { name: name.into(), components: 1, values: ArrayValues::Int32(values) }
    }

    /// A scalar UInt8 array (flags).
    pub fn flags(name: &str, values: Vec<u8>) -> Self {
        DataArray { name: name.into(), components: 1, values: ArrayValues::UInt8(values) }
    }
}

/// The kind of the cells of a [`PolyData`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CellKind {
    /// Vertex cells (`<Verts>`).
    Verts,
    /// Line cells (`<Lines>`).
    Lines,
    /// Polygon cells (`<Polys>`), here triangles.
    Polys,
}

impl CellKind {
    /// The XML element holding cells of this kind.
    fn element(self) -> &'static str {
        match self {
            CellKind::Verts => "Verts",
            CellKind::Lines => "Lines",
            CellKind::Polys => "Polys",
        }
    }
}

/// A poly data set with cells of one kind and one size (1 for vertices, 2 for lines, 3 for
/// triangles).
#[derive(Clone, Debug, PartialEq)]
pub struct PolyData {
    /// Point coordinates.
    pub points: Vec<[f64; 3]>,
    /// Kind of every cell.
    pub cell_kind: CellKind,
    /// Points per cell.
    pub cell_size: usize,
    /// Point indices of the cells, `cell_size` per cell.
    pub connectivity: Vec<i64>,
    /// Arrays with one tuple per point.
    pub point_data: Vec<DataArray>,
    /// Arrays with one tuple per cell.
    pub cell_data: Vec<DataArray>,
}

/// Base64 (RFC 4648, standard alphabet, with `=` padding) of `bytes`.
fn base64_encode(bytes: &[u8]) -> String {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [chunk[0], *chunk.get(1).unwrap_or(&0), *chunk.get(2).unwrap_or(&0)];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for k in 0..4 {
            if k <= chunk.len() {
                out.push(char::from(ALPHABET[((n >> (18 - 6 * k)) & 63) as usize]));
            } else {
                out.push('=');
            }
        }
    }
    out
}

/// Escapes `&`, `<`, `>` and `"` for an XML attribute value.
pub(crate) fn escape_attribute(text: &str) -> String {
    text.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}

/// One `<DataArray>` element: the byte count as a little-endian u64 followed by the data, the
/// whole base64-encoded (VTK's inline binary format without compression).
fn data_array_xml(xml: &mut String, name: &str, components: usize, values: &ArrayValues) {
    let data = values.to_le_bytes();
    let mut bytes = (data.len() as u64).to_le_bytes().to_vec();
    bytes.extend_from_slice(&data);
    xml.push_str(&format!(
        "<DataArray type=\"{}\" Name=\"{}\" NumberOfComponents=\"{}\" format=\"binary\">\n{}\n\
         </DataArray>\n",
        values.type_name(),
        escape_attribute(name),
        components,
        base64_encode(&bytes)
    ));
}

impl PolyData {
    /// Number of cells.
    pub fn cell_count(&self) -> usize {
        self.connectivity.len().checked_div(self.cell_size).unwrap_or(0)
    }

    /// The `.vtp` file's text (XML with base64 binary arrays).
    pub fn to_xml(&self) -> String {
        let cells = self.cell_count();
        let count_of = |kind: CellKind| if self.cell_kind == kind { cells } else { 0 };
        let mut xml = String::from(
            "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\" \
             byte_order=\"LittleEndian\" header_type=\"UInt64\">\n<PolyData>\n",
        );
        xml.push_str(&format!(
            "<Piece NumberOfPoints=\"{}\" NumberOfVerts=\"{}\" NumberOfLines=\"{}\" \
             NumberOfStrips=\"0\" NumberOfPolys=\"{}\">\n",
            self.points.len(),
            count_of(CellKind::Verts),
            count_of(CellKind::Lines),
            count_of(CellKind::Polys)
        ));
        for (tag, arrays) in [("PointData", &self.point_data), ("CellData", &self.cell_data)] {
            xml.push_str(&format!("<{tag}>\n"));
            for a in arrays {
                data_array_xml(&mut xml, &a.name, a.components, &a.values);
            }
            xml.push_str(&format!("</{tag}>\n"));
        }
        xml.push_str("<Points>\n");
        let coordinates = ArrayValues::Float64(self.points.iter().flatten().copied().collect());
        data_array_xml(&mut xml, "Points", 3, &coordinates);
        xml.push_str("</Points>\n");
        for kind in [CellKind::Verts, CellKind::Lines, CellKind::Polys] {
            let (connectivity, offsets) = if kind == self.cell_kind {
                let offsets = (1..=cells).map(|c| (c * self.cell_size) as i64).collect();
                (self.connectivity.clone(), offsets)
            } else {
                (Vec::new(), Vec::new())
            };
            xml.push_str(&format!("<{}>\n", kind.element()));
            data_array_xml(&mut xml, "connectivity", 1, &ArrayValues::Int64(connectivity));
            data_array_xml(&mut xml, "offsets", 1, &ArrayValues::Int64(offsets));
            xml.push_str(&format!("</{}>\n", kind.element()));
        }
        xml.push_str("</Piece>\n</PolyData>\n</VTKFile>\n");
        xml
    }
}

#[cfg(test)]
mod tests {
    use super::base64_encode;

    #[test]
    fn base64_matches_the_rfc_4648_test_vectors() {
        let cases = [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("fooba", "Zm9vYmE="),
            ("foobar", "Zm9vYmFy"),
        ];
        for (plain, encoded) in cases {
            assert_eq!(base64_encode(plain.as_bytes()), encoded);
        }
        assert_eq!(base64_encode(&[0xff, 0xfe, 0x3e]), "//4+");
    }
}
