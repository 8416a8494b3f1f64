//! The binary payloads the page reads: the mesh once, then a field frame after every edit.
//!
//! All numbers are little-endian.
//! - Mesh (`GET /api/mesh`): `u32` magic `"TVFM"`, `u32 V`, `u32 T`, `f32` positions (`3V`),
//!   `u32` corner indices (`3T`, counter-clockwise): the display triangulation
//!   ([`SurfaceMesh::display`]; on a polygon mesh its vertices are the mesh's, then one corner
//!   average per fanned polygon). Then the faces the fields and constraints refer to: `u32 F`,
//!   `u32 C` (corners in all), `u32` corner counts (`F`), `u32` corners (`C`, face by face,
//!   counter-clockwise, indices of the mesh's vertices), and `u32` the face of every display
//!   triangle (`T`). On a triangle mesh the faces are the display triangles.
//! - Field frame (`GET /api/field`, `POST /api/edit`): `u32` magic `"TVFF"`, `u32` length `n` of
//!   the status JSON, the JSON (UTF-8) padded with spaces to a multiple of 4 bytes, then `2F`
//!   `f32` coefficients of the field in the face frames `e1 = normalize(p1 − p0)` projected onto
//!   the face's plane (normal to its vector area), `e2 = n × e1` (pointwise values, as in
//!   `docs/conventions.md`; on a triangle `e1` lies in the plane already).
//! - Fur (`GET /api/fur`): `u32` strand count `s`, `u32` points per strand `p`, `f32` points
//!   (`3 s p`).

use crate::error::EditorError;
use tvf_core::SurfaceMesh;

/// Magic number of a mesh payload (`"TVFM"` read as a little-endian `u32`).
pub const MESH_MAGIC: u32 = u32::from_le_bytes(*b"TVFM");
/// Magic number of a field frame (`"TVFF"` read as a little-endian `u32`).
pub const FIELD_MAGIC: u32 = u32::from_le_bytes(*b"TVFF");

fn push_u32(out: &mut Vec<u8>, value: u32) {
    out.extend_from_slice(&value.to_le_bytes());
}

fn count_u32(what: &'static str, n: usize) -> Result<u32, EditorError> {
    u32::try_from(n).map_err(|_| EditorError::TooLarge { what, count: n })
}

/// The mesh payload of `mesh` (positions rounded to `f32`): its display triangulation, then its
/// faces and the face of every display triangle.
pub fn encode_mesh(mesh: &SurfaceMesh) -> Result<Vec<u8>, EditorError> {
    let display = mesh.display();
    let (triangles, corners) = (display.face_count(), mesh.faces().total_corners());
    let mut out = Vec::with_capacity(
        20 + 12 * display.vertex_count() + 16 * triangles + 4 * (mesh.face_count() + corners),
    );
    push_u32(&mut out, MESH_MAGIC);
    push_u32(&mut out, count_u32("vertices", display.vertex_count())?);
    push_u32(&mut out, count_u32("display triangles", triangles)?);
    for p in display.positions() {
        for x in p {
            out.extend_from_slice(&(*x as f32).to_le_bytes());
        }
    }
    for f in display.faces() {
        for &i in f {
            push_u32(&mut out, count_u32("vertex index", i)?);
        }
    }
    push_u32(&mut out, count_u32("faces", mesh.face_count())?);
    push_u32(&mut out, count_u32("corners", corners)?);
    for f in 0..mesh.face_count() {
        push_u32(&mut out, count_u32("corner count", mesh.face_size(f))?);
    }
    for f in 0..mesh.face_count() {
        for &i in mesh.face(f) {
            push_u32(&mut out, count_u32("vertex index", i)?);
        }
    }
    for t in 0..triangles {
        push_u32(&mut out, count_u32("face index", mesh.display_face(t))?);
    }
    Ok(out)
}

/// A field frame: the status JSON text and `2F` frame coefficients.
pub fn encode_field_frame(status_json: &str, coefficients: &[f32]) -> Vec<u8> {
    let padded = status_json.len().div_ceil(4) * 4;
    let mut out = Vec::with_capacity(8 + padded + 4 * coefficients.len());
    push_u32(&mut out, FIELD_MAGIC);
    // A status JSON longer than 4 GiB cannot occur (it lists the constraints).
    push_u32(&mut out, status_json.len() as u32);
    out.extend_from_slice(status_json.as_bytes());
    out.resize(8 + padded, b' ');
    for x in coefficients {
        out.extend_from_slice(&x.to_le_bytes());
    }
    out
}

/// A decoded field frame (for scripted clients: the tests and the latency benchmark).
#[derive(Debug, Clone, PartialEq)]
pub struct FieldFrame {
    /// The status JSON, parsed.
    pub status: serde_json::Value,
    /// `2F` coefficients in the face frames.
    pub coefficients: Vec<f32>,
}

/// Decodes a field frame; errors say what is malformed.
pub fn decode_field_frame(bytes: &[u8]) -> Result<FieldFrame, EditorError> {
    let bad = |reason: String| EditorError::BadPayload { reason };
    let word = |at: usize| -> Result<u32, EditorError> {
        bytes
            .get(at..at + 4)
            .map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
            .ok_or_else(|| bad(format!("truncated at byte {at}")))
    };
    if word(0)? != FIELD_MAGIC {
        return Err(bad("not a field frame (bad magic number)".into()));
    }
    let n = word(4)? as usize;
    let text = bytes
        .get(8..8 + n)
        .ok_or_else(|| bad(format!("status JSON of {n} bytes is truncated")))?;
    let status = serde_json::from_slice(text).map_err(|e| bad(format!("status JSON: {e}")))?;
    let start = 8 + n.div_ceil(4) * 4;
    let body = bytes
        .get(start..)
        .ok_or_else(|| bad("missing field data".into()))?;
    if body.len() % 4 != 0 {
        return Err(bad(format!(
            "field data of {} bytes is not whole f32s",
            body.len()
        )));
    }
    let coefficients = body
        .chunks_exact(4)
        .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
        .collect();
    Ok(FieldFrame {
        status,
        coefficients,
    })
}

/// The fur payload: strands of equal point count (shorter strands are not produced by
/// [`tvf_render::grow_fur`]).
pub fn encode_fur(strands: &[Vec<[f64; 3]>]) -> Result<Vec<u8>, EditorError> {
    let per = strands.first().map_or(0, Vec::len);
    let kept: Vec<&Vec<[f64; 3]>> = strands.iter().filter(|s| s.len() == per).collect();
    let mut out = Vec::with_capacity(8 + 12 * per * kept.len());
    push_u32(&mut out, count_u32("strands", kept.len())?);
    push_u32(&mut out, count_u32("points per strand", per)?);
    for strand in kept {
        for p in strand {
            for x in p {
                out.extend_from_slice(&(*x as f32).to_le_bytes());
            }
        }
    }
    Ok(out)
}
