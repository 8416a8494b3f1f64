//! Quads of a grid cut into triangles: [`grid_cell`], the corners of one cell of a grid of
//! vertices, and [`split_quad`], the two ways to cut a quad along a diagonal.

/// The diagonal along which [`split_quad`] cuts a quad `[a, b, c, d]`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Diagonal {
    /// `a–c`: triangles `[a, b, c]` and `[a, c, d]`.
    AC,
    /// `b–d`: triangles `[a, b, d]` and `[b, c, d]`.
    BD,
}

impl Diagonal {
    /// The shorter diagonal of `[a, b, c, d]` under the squared distance `distance` (`a–c` on a
    /// tie).
    pub(crate) fn shorter(
        [a, b, c, d]: [usize; 4],
        distance: impl Fn(usize, usize) -> f64,
    ) -> Self {
        if distance(a, c) <= distance(b, d) {
            Diagonal::AC
        } else {
            Diagonal::BD
        }
    }
}

/// The quad of the grid cell at `(x, y)`: `[vertex(x, y), vertex(x + 1, y), vertex(x + 1, y + 1),
/// vertex(x, y + 1)]` (counter-clockwise when `x` then `y` is).
pub(crate) fn grid_cell(vertex: impl Fn(usize, usize) -> usize, x: usize, y: usize) -> [usize; 4] {
    [
        vertex(x, y),
        vertex(x + 1, y),
        vertex(x + 1, y + 1),
        vertex(x, y + 1),
    ]
}

/// The quad `[a, b, c, d]` as two triangles with its orientation, cut along `diagonal`.
pub(crate) fn split_quad([a, b, c, d]: [usize; 4], diagonal: Diagonal) -> [[usize; 3]; 2] {
    match diagonal {
        Diagonal::AC => [[a, b, c], [a, c, d]],
        Diagonal::BD => [[a, b, d], [b, c, d]],
    }
}
