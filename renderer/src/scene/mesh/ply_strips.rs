//! PLY triangle strips (`element tristrips N` with `property list int int vertex_indices`, as in
//! the Igea head and other files of its time): the reader's part that turns them into
//! triangles. Part of [`super`], in a file of its own for the length of `ply.rs`.
//!
//! Each list is a sequence of vertex indices in which −1 ends a strip and starts the next; a
//! strip does not continue from one element to the next. Triangle k (from 0) of a strip of
//! vertices v₀ v₁ … is (v_k, v_{k+1}, v_{k+2}) for even k and (v_{k+1}, v_k, v_{k+2}) for odd
//! k: the alternating winding that gives every triangle of a strip the orientation of its
//! first. A triangle that repeats an index is skipped (strips use them to turn or to join; they
//! have no area) but still counts for the alternation. A strip of fewer than 3 vertices gives
//! nothing. Any other negative index, or one at or past the vertex count, is an error. The
//! element's other properties are skipped: Mitsuba's face attributes are per `face` element
//! and do not apply to strips.

use super::*;

/// What [`read_strips`] needs besides the element: the index of its index list and the
/// number of vertices.
pub(super) struct Strips {
    pub(super) index_list: usize,
    pub(super) vertices: u64,
}

/// The index that ends a strip.
const RESTART: f64 = -1.0;

/// Reads one `tristrips` element, appending its triangles to `triangles`; `strip` is scratch
/// space.
pub(super) fn read_strips(
    source: &mut impl Source,
    element: &Element,
    strips: &Strips,
    strip: &mut Vec<u32>,
    triangles: &mut Vec<[u32; 3]>,
) -> Result<(), String> {
    let vertices = strips.vertices;
    source.begin()?;
    for (k, p) in element.properties.iter().enumerate() {
        match p.kind {
            Kind::List { len, item } if k == strips.index_list => {
                strip.clear();
                for _ in 0..source.list_len(len)? {
                    let i = source.value(item)?;
                    if i == RESTART {
                        strip_triangles(strip, triangles);
                        strip.clear();
                    } else if i < 0.0 || i >= vertices as f64 {
                        return Err(format!("index {i} out of range ({vertices} vertices)"));
                    } else {
                        strip.push(i as u32);
                    }
                }
                strip_triangles(strip, triangles);
            }
            Kind::List { len, item } => skip_list(source, len, item)?,
            Kind::Scalar(t) => {
                source.value(t)?;
            }
        }
    }
    source.end()
}

/// Appends the triangles of one strip (see the module doc), without the degenerate ones.
pub(super) fn strip_triangles(strip: &[u32], triangles: &mut Vec<[u32; 3]>) {
    for (k, w) in strip.windows(3).enumerate() {
        let t = if k % 2 == 0 {
            [w[0], w[1], w[2]]
        } else {
            [w[1], w[0], w[2]]
        };
        if t[0] != t[1] && t[1] != t[2] && t[0] != t[2] {
            triangles.push(t);
        }
    }
}

#[cfg(test)]
#[path = "ply_strips_tests.rs"]
mod tests;
