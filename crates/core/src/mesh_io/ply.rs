//! PLY reader: ASCII and binary (little/big endian), any element layout, polygon faces
//! triangulated as fans. Reads positions and vertex colours (Replica's `mesh.ply` has quads and
//! uchar colours); other properties and elements are skipped. No `face` element (or an empty
//! one) reads as a point cloud.

use std::path::Path;

use super::MeshGeometry;
use crate::limits::{
    MAX_MESH_FILE_BYTES, MAX_MESH_TRIANGLES, MAX_MESH_VERTICES, MAX_POLYGON_CORNERS,
};
use crate::{printable, read_limited, CoreError};

#[derive(Clone, Copy, PartialEq, Debug)]
enum Encoding {
    Ascii,
    LittleEndian,
    BigEndian,
}

#[derive(Clone, Copy, Debug)]
enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Scalar {
    fn parse(name: &str) -> Option<Self> {
        Some(match name {
            "char" | "int8" => Scalar::I8,
            "uchar" | "uint8" => Scalar::U8,
            "short" | "int16" => Scalar::I16,
            "ushort" | "uint16" => Scalar::U16,
            "int" | "int32" => Scalar::I32,
            "uint" | "uint32" => Scalar::U32,
            "float" | "float32" => Scalar::F32,
            "double" | "float64" => Scalar::F64,
            _ => return None,
        })
    }

    fn size(self) -> usize {
        match self {
            Scalar::I8 | Scalar::U8 => 1,
            Scalar::I16 | Scalar::U16 => 2,
            Scalar::I32 | Scalar::U32 | Scalar::F32 => 4,
            Scalar::F64 => 8,
        }
    }

    fn is_float(self) -> bool {
        matches!(self, Scalar::F32 | Scalar::F64)
    }
}

#[derive(Debug)]
enum Property {
    Scalar {
        name: String,
        kind: Scalar,
    },
    List {
        name: String,
        count: Scalar,
        item: Scalar,
    },
}

#[derive(Debug)]
struct Element {
    name: String,
    count: usize,
    properties: Vec<Property>,
}

struct Header {
    encoding: Encoding,
    elements: Vec<Element>,
    body_start: usize,
}

/// Reads the vertices, vertex colours and triangles of a PLY file.
pub fn read_ply(path: &Path) -> Result<MeshGeometry, CoreError> {
    let bytes = read_mesh_bytes(path)?;
    parse_ply(&bytes).map_err(|message| CoreError::bad_file(path, message))
}

/// The bytes of a mesh file, refused past [`MAX_MESH_FILE_BYTES`] before any is read.
pub fn read_mesh_bytes(path: &Path) -> Result<Vec<u8>, CoreError> {
    read_limited(path, MAX_MESH_FILE_BYTES, "a mesh file")
}

/// Parses a PLY file's bytes; the error is one line, without the file's name.
pub fn parse_ply(bytes: &[u8]) -> Result<MeshGeometry, String> {
    let mut mesh = MeshGeometry::default();
    read_elements(bytes, &mut |element, values| {
        match element.name.as_str() {
            "vertex" => read_vertices(element, values, &mut mesh)?,
            "face" => read_faces(element, values, &mut mesh)?,
            _ => return Ok(false),
        }
        Ok(true)
    })?;
    let vertex_count = mesh.positions.len();
    if let Some(i) = mesh
        .indices
        .iter()
        .position(|&i| i as usize >= vertex_count)
    {
        return Err(format!(
            "face {} refers to vertex {} but the file has {vertex_count} vertices",
            i / 3,
            mesh.indices[i]
        ));
    }
    Ok(mesh)
}

/// The names of the 'vertex' element's scalar properties, in the file's order (from the header
/// alone).
pub fn ply_vertex_properties(bytes: &[u8]) -> Result<Vec<String>, String> {
    let header = parse_header(bytes)?;
    let vertex = header.elements.iter().find(|e| e.name == "vertex");
    Ok(vertex
        .into_iter()
        .flat_map(|e| &e.properties)
        .filter_map(|p| match p {
            Property::Scalar { name, .. } => Some(name.clone()),
            Property::List { .. } => None,
        })
        .collect())
}

/// The scalar vertex properties `names`, one column of 32-bit floats per name, in the order
/// asked; every other property and element is skipped. Fails naming the first property the
/// 'vertex' element lacks.
pub fn parse_ply_vertex_columns(bytes: &[u8], names: &[&str]) -> Result<Vec<Vec<f32>>, String> {
    let mut columns = vec![Vec::new(); names.len()];
    let mut found = false;
    read_elements(bytes, &mut |element, values| {
        if element.name != "vertex" {
            return Ok(false);
        }
        found = true;
        let slots: Vec<Option<usize>> = (element.properties.iter())
            .map(|p| match p {
                Property::Scalar { name, .. } => names.iter().position(|n| n == name),
                Property::List { .. } => None,
            })
            .collect();
        if let Some(missing) = (0..names.len()).find(|i| !slots.contains(&Some(*i))) {
            return Err(format!(
                "the 'vertex' element has no '{}' property",
                names[missing]
            ));
        }
        // The count was checked against the file's size: these reservations are bounded by it.
        columns.iter_mut().for_each(|c| c.reserve(element.count));
        for record in 0..element.count {
            for (p, slot) in element.properties.iter().zip(&slots) {
                match (p, slot) {
                    (Property::Scalar { kind, .. }, Some(i)) => {
                        let x = values
                            .read(*kind)
                            .map_err(|e| truncated(element, record, e))?;
                        columns[*i].push(x as f32);
                    }
                    _ => read_property(p, values).map_err(|e| truncated(element, record, e))?,
                }
            }
        }
        Ok(true)
    })?;
    if !found {
        return Err("the file has no 'vertex' element".into());
    }
    Ok(columns)
}

/// Reads every element's records in order: `read` takes an element and returns whether it read
/// its records; the records of the others are skipped.
fn read_elements(
    bytes: &[u8],
    read: &mut dyn FnMut(&Element, &mut dyn Values) -> Result<bool, String>,
) -> Result<(), String> {
    let header = parse_header(bytes)?;
    let body = &bytes[header.body_start..];
    let mut values: Box<dyn Values> = match header.encoding {
        Encoding::Ascii => Box::new(AsciiValues::new(body)?),
        encoding => Box::new(BinaryValues {
            bytes: body,
            pos: 0,
            big: encoding == Encoding::BigEndian,
        }),
    };
    for element in &header.elements {
        check_record_count(element, header.encoding, values.as_ref())?;
        if element.properties.is_empty() && element.name != "vertex" {
            continue; // records of nothing: no bytes to read, however many
        }
        if !read(element, values.as_mut())? {
            for record in 0..element.count {
                for p in &element.properties {
                    read_property(p, values.as_mut()).map_err(|e| truncated(element, record, e))?;
                }
            }
        }
    }
    Ok(())
}

/// Where the header ends: the start of the `end_header` line and the first byte after it. The
/// words may appear earlier inside a comment (a scene called `end_header` exports one).
fn find_end_header(bytes: &[u8]) -> Option<(usize, usize)> {
    let mut start = 0;
    while start < bytes.len() {
        let end = bytes[start..]
            .iter()
            .position(|&b| b == b'\n')
            .map_or(bytes.len(), |i| start + i);
        if bytes[start..end].trim_ascii() == b"end_header" {
            return Some((start, end + 1));
        }
        start = end + 1;
    }
    None
}

fn parse_header(bytes: &[u8]) -> Result<Header, String> {
    let (end, body_start) = find_end_header(bytes).ok_or("not a PLY file: no 'end_header' line")?;
    let text = String::from_utf8_lossy(&bytes[..end]);
    let mut lines = text.lines().enumerate();
    if lines.next().map(|(_, l)| l.trim()) != Some("ply") {
        return Err("not a PLY file: the first line is not 'ply'".into());
    }
    let mut encoding = None;
    let mut elements: Vec<Element> = Vec::new();
    for (n, line) in lines {
        let words: Vec<&str> = line.split_whitespace().collect();
        let bad = |what: &str| {
            format!(
                "header line {}: {what}: '{}'",
                n + 1,
                printable(line.trim())
            )
        };
        match words.as_slice() {
            [] | ["comment", ..] | ["obj_info", ..] => {}
            ["format", f, _version] => {
                encoding = Some(match *f {
                    "ascii" => Encoding::Ascii,
                    "binary_little_endian" => Encoding::LittleEndian,
                    "binary_big_endian" => Encoding::BigEndian,
                    _ => return Err(bad("unknown format")),
                })
            }
            ["element", name, count] => elements.push(Element {
                name: name.to_string(),
                count: count.parse().map_err(|_| bad("bad element count"))?,
                properties: Vec::new(),
            }),
            ["property", "list", count, item, name] => {
                let element = element_for_property(&mut elements, name).map_err(bad)?;
                element.properties.push(Property::List {
                    name: name.to_string(),
                    count: Scalar::parse(count).ok_or_else(|| bad("unknown list count type"))?,
                    item: Scalar::parse(item).ok_or_else(|| bad("unknown list item type"))?,
                });
            }
            ["property", kind, name] => {
                let element = element_for_property(&mut elements, name).map_err(bad)?;
                element.properties.push(Property::Scalar {
                    name: name.to_string(),
                    kind: Scalar::parse(kind).ok_or_else(|| bad("unknown property type"))?,
                });
            }
            _ => return Err(bad("unrecognised header line")),
        }
    }
    Ok(Header {
        encoding: encoding.ok_or("header has no 'format' line")?,
        elements,
        body_start: body_start.min(bytes.len()),
    })
}

/// The element a `property` line declares `name` in: the last one, which must not have it yet
/// (a second column of the same name would be read as twice the records).
fn element_for_property<'a>(
    elements: &'a mut [Element],
    name: &str,
) -> Result<&'a mut Element, &'static str> {
    let element = elements.last_mut().ok_or("property before any element")?;
    let declared = element.properties.iter().any(|p| match p {
        Property::Scalar { name: n, .. } | Property::List { name: n, .. } => n == name,
    });
    if declared {
        return Err("property declared twice in one element");
    }
    Ok(element)
}

/// Refuses an element whose count the rest of the file cannot hold, before anything is
/// allocated or looped over for it: every record takes at least [`min_record_size`] bytes or
/// tokens.
fn check_record_count(
    element: &Element,
    encoding: Encoding,
    values: &dyn Values,
) -> Result<(), String> {
    let limit = match element.name.as_str() {
        "vertex" => Some(("vertices", MAX_MESH_VERTICES)),
        "face" => Some(("faces", MAX_MESH_TRIANGLES)),
        _ => None,
    };
    if let Some((what, limit)) = limit.filter(|&(_, limit)| element.count > limit) {
        return Err(format!(
            "element '{}' declares {} {what}, over the limit of {limit}",
            element.name, element.count
        ));
    }
    let record = min_record_size(element, encoding);
    let room = values.remaining().checked_div(record).unwrap_or(usize::MAX);
    if element.count > room {
        return Err(format!(
            "element '{}' declares {} records, but the rest of the file holds at most {room}",
            element.name, element.count
        ));
    }
    Ok(())
}

/// The fewest bytes (binary) or tokens (ASCII) one record of `element` takes: every scalar, and
/// the count of every list (lists may be empty).
fn min_record_size(element: &Element, encoding: Encoding) -> usize {
    element
        .properties
        .iter()
        .map(|p| match (p, encoding) {
            (_, Encoding::Ascii) => 1,
            (Property::Scalar { kind, .. }, _) => kind.size(),
            (Property::List { count, .. }, _) => count.size(),
        })
        .sum()
}

fn truncated(element: &Element, record: usize, e: String) -> String {
    format!(
        "{e} in element '{}' record {record} of {}",
        element.name, element.count
    )
}

/// The colour channel a vertex property holds, if any.
fn color_channel(name: &str) -> Option<usize> {
    match name {
        "red" | "r" | "diffuse_red" => Some(0),
        "green" | "g" | "diffuse_green" => Some(1),
        "blue" | "b" | "diffuse_blue" => Some(2),
        _ => None,
    }
}

/// Whether the element has a scalar property whose name passes `wanted`.
fn declares(element: &Element, wanted: impl Fn(&str) -> bool) -> bool {
    element
        .properties
        .iter()
        .any(|p| matches!(p, Property::Scalar { name, .. } if wanted(name)))
}

fn read_vertices(
    element: &Element,
    values: &mut dyn Values,
    mesh: &mut MeshGeometry,
) -> Result<(), String> {
    if let Some(axis) = ["x", "y", "z"]
        .into_iter()
        .find(|&axis| !declares(element, |name| name == axis))
    {
        return Err(format!("the 'vertex' element has no '{axis}' property"));
    }
    // The count was checked against the file's size: these reservations are bounded by it.
    let mut colors = (0..3)
        .all(|c| declares(element, |name| color_channel(name) == Some(c)))
        .then(|| Vec::with_capacity(element.count));
    mesh.positions.reserve(element.count);
    for record in 0..element.count {
        let mut position = [0.0f32; 3];
        let mut color = [0u8; 3];
        for p in &element.properties {
            let (name, kind) = match p {
                Property::Scalar { name, kind } => (name.as_str(), *kind),
                list => {
                    read_property(list, values).map_err(|e| truncated(element, record, e))?;
                    continue;
                }
            };
            let x = values
                .read(kind)
                .map_err(|e| truncated(element, record, e))?;
            let channel = |x: f64| {
                if kind.is_float() {
                    (x * 255.0).round().clamp(0.0, 255.0) as u8
                } else {
                    x.clamp(0.0, 255.0) as u8
                }
            };
            match name {
                "x" | "y" | "z" => {
                    let coordinate = x as f32;
                    if !coordinate.is_finite() {
                        return Err(format!(
                            "vertex {record}: coordinate {name} = {x:e} is not a finite 32-bit float"
                        ));
                    }
                    position[(name.as_bytes()[0] - b'x') as usize] = coordinate;
                }
                _ => {
                    if let Some(c) = color_channel(name) {
                        color[c] = channel(x);
                    }
                }
            }
        }
        mesh.positions.push(position);
        if let Some(colors) = &mut colors {
            colors.push(color);
        }
    }
    mesh.colors = colors;
    Ok(())
}

fn read_faces(
    element: &Element,
    values: &mut dyn Values,
    mesh: &mut MeshGeometry,
) -> Result<(), String> {
    for record in 0..element.count {
        for p in &element.properties {
            match p {
                Property::List { name, count, item }
                    if name == "vertex_indices" || name == "vertex_index" =>
                {
                    let n = values
                        .read(*count)
                        .map_err(|e| truncated(element, record, e))?;
                    if !(0.0..=MAX_POLYGON_CORNERS as f64).contains(&n) {
                        return Err(format!(
                            "face {record} has {n} corners; expected 0 to {MAX_POLYGON_CORNERS}"
                        ));
                    }
                    let n = n as usize;
                    let mut polygon = Vec::with_capacity(n);
                    for _ in 0..n {
                        let i = values
                            .read(*item)
                            .map_err(|e| truncated(element, record, e))?;
                        if i < 0.0 || i.fract() != 0.0 {
                            return Err(format!("face {record} has an invalid vertex index {i}"));
                        }
                        polygon.push(i as u32);
                    }
                    for k in 1..n.saturating_sub(1) {
                        mesh.indices
                            .extend_from_slice(&[polygon[0], polygon[k], polygon[k + 1]]);
                    }
                    if mesh.triangle_count() > MAX_MESH_TRIANGLES {
                        return Err(format!(
                            "face {record}: more than {MAX_MESH_TRIANGLES} triangles, the most a mesh may hold"
                        ));
                    }
                }
                other => read_property(other, values).map_err(|e| truncated(element, record, e))?,
            }
        }
    }
    Ok(())
}

fn read_property(p: &Property, values: &mut dyn Values) -> Result<(), String> {
    match p {
        Property::Scalar { kind, .. } => values.read(*kind).map(|_| ()),
        Property::List { count, item, .. } => {
            // Every item takes a byte or token at least: a count past the file's end fails at
            // the end, never loops on.
            let n = values.read(*count)?;
            if n < 0.0 {
                return Err(format!("list length {n} is negative"));
            }
            (0..n as usize).try_for_each(|_| values.read(*item).map(|_| ()))
        }
    }
}

/// The body as a stream of numbers.
trait Values {
    fn read(&mut self, kind: Scalar) -> Result<f64, String>;
    /// Bytes (binary) or tokens (ASCII) not read yet.
    fn remaining(&self) -> usize;
}

struct BinaryValues<'a> {
    bytes: &'a [u8],
    pos: usize,
    big: bool,
}

impl Values for BinaryValues<'_> {
    fn remaining(&self) -> usize {
        self.bytes.len() - self.pos
    }

    fn read(&mut self, kind: Scalar) -> Result<f64, String> {
        let n = kind.size();
        let raw = self
            .bytes
            .get(self.pos..self.pos + n)
            .ok_or("file ends early")?;
        self.pos += n;
        let mut b = [0u8; 8];
        b[..n].copy_from_slice(raw);
        if self.big {
            b[..n].reverse();
        }
        Ok(match kind {
            Scalar::I8 => b[0] as i8 as f64,
            Scalar::U8 => b[0] as f64,
            Scalar::I16 => i16::from_le_bytes([b[0], b[1]]) as f64,
            Scalar::U16 => u16::from_le_bytes([b[0], b[1]]) as f64,
            Scalar::I32 => i32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64,
            Scalar::U32 => u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64,
            Scalar::F32 => f32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64,
            Scalar::F64 => f64::from_le_bytes(b),
        })
    }
}

/// Tokens taken one by one from the text (a copy of each would take several times the file).
struct AsciiValues<'a> {
    tokens: std::str::SplitWhitespace<'a>,
    left: usize,
}

impl<'a> AsciiValues<'a> {
    fn new(body: &'a [u8]) -> Result<Self, String> {
        let text = std::str::from_utf8(body).map_err(|_| "ASCII body is not text")?;
        Ok(Self {
            tokens: text.split_whitespace(),
            left: text.split_whitespace().count(),
        })
    }
}

impl Values for AsciiValues<'_> {
    fn read(&mut self, _kind: Scalar) -> Result<f64, String> {
        let token = self.tokens.next().ok_or("file ends early")?;
        self.left -= 1;
        token
            .parse()
            .map_err(|_| format!("'{token}' is not a number"))
    }

    fn remaining(&self) -> usize {
        self.left
    }
}

#[cfg(test)]
mod tests;
