//! Faces of any size as one flat list ([`FaceList`]), and [`FaceCorners`]: read access to the
//! corners of faces that the topology and the validation are written against, so that they
//! serve triangle lists (`[[usize; 3]]`) and polygon lists alike without copying.

/// Read access to a list of faces, each a counter-clockwise cycle of vertex indices.
pub trait FaceCorners {
    /// Number of faces `F`.
    fn face_count(&self) -> usize;

    /// The corners of face `f` (vertex indices, counter-clockwise), at least three on a valid
    /// mesh. Panics if `f` is out of range.
    fn corners(&self, f: usize) -> &[usize];

    /// Index of corner `c` of face `f` in the list of all corners, counted face by face:
    /// `Σ_{g<f} |g| + c`.
    fn corner_index(&self, f: usize, c: usize) -> usize;

    /// Number of corners of all faces, `Σ_f |f|`.
    fn total_corners(&self) -> usize;
}

impl FaceCorners for [[usize; 3]] {
    fn face_count(&self) -> usize {
        self.len()
    }

    fn corners(&self, f: usize) -> &[usize] {
        &self[f]
    }

    fn corner_index(&self, f: usize, c: usize) -> usize {
        3 * f + c
    }

    fn total_corners(&self) -> usize {
        3 * self.len()
    }
}

/// A triangle list in a `Vec`: its slice's answers.
impl FaceCorners for Vec<[usize; 3]> {
    fn face_count(&self) -> usize {
        self.as_slice().face_count()
    }

    fn corners(&self, f: usize) -> &[usize] {
        self.as_slice().corners(f)
    }

    fn corner_index(&self, f: usize, c: usize) -> usize {
        self.as_slice().corner_index(f, c)
    }

    fn total_corners(&self) -> usize {
        self.as_slice().total_corners()
    }
}

/// Faces of any size ≥ 3 stored flat: the corners of face `f` are
/// `corners[offsets[f]..offsets[f + 1]]` (counter-clockwise seen from outside).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FaceList {
    offsets: Vec<usize>,
    corners: Vec<usize>,
}

impl FaceList {
    /// An empty list.
    pub fn new() -> Self {
        Self {
            offsets: vec![0],
            corners: Vec::new(),
        }
    }

    /// The list of `faces`, in order.
    pub fn from_polygons<F: AsRef<[usize]>>(faces: &[F]) -> Self {
        let mut list = Self::new();
        for face in faces {
            list.push(face.as_ref());
        }
        list
    }

    /// The list of triangles `faces`, in order.
    pub fn from_triangles(faces: &[[usize; 3]]) -> Self {
        Self {
            offsets: (0..=faces.len()).map(|f| 3 * f).collect(),
            corners: faces.iter().flatten().copied().collect(),
        }
    }

    /// Appends a face with `corners`.
    pub fn push(&mut self, corners: &[usize]) {
        self.corners.extend_from_slice(corners);
        self.offsets.push(self.corners.len());
    }

    /// Number of faces.
    pub fn len(&self) -> usize {
        self.offsets.len() - 1
    }

    /// Whether the list has no face.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Number of corners of face `f`.
    pub fn face_size(&self, f: usize) -> usize {
        self.offsets[f + 1] - self.offsets[f]
    }

    /// Whether every face has exactly three corners.
    pub fn all_triangles(&self) -> bool {
        (0..self.len()).all(|f| self.face_size(f) == 3)
    }

    /// The faces as triangles, if every face has three corners.
    pub fn to_triangles(&self) -> Option<Vec<[usize; 3]>> {
        (0..self.len())
            .map(|f| <[usize; 3]>::try_from(self.corners(f)).ok())
            .collect()
    }

    /// The faces, in order.
    pub fn iter(&self) -> impl ExactSizeIterator<Item = &[usize]> + '_ {
        self.offsets.windows(2).map(|w| &self.corners[w[0]..w[1]])
    }

    /// Every corner of every face, face by face (`Σ_f |f|` entries).
    pub fn flat_corners(&self) -> &[usize] {
        &self.corners
    }

    /// The same faces with every vertex index `v` replaced by `map[v]`.
    pub fn renumbered(&self, map: &[usize]) -> Self {
        Self {
            offsets: self.offsets.clone(),
            corners: self.corners.iter().map(|&v| map[v]).collect(),
        }
    }
}

impl Default for FaceList {
    fn default() -> Self {
        Self::new()
    }
}

impl FaceCorners for FaceList {
    fn face_count(&self) -> usize {
        self.len()
    }

    fn corners(&self, f: usize) -> &[usize] {
        &self.corners[self.offsets[f]..self.offsets[f + 1]]
    }

    fn corner_index(&self, f: usize, c: usize) -> usize {
        self.offsets[f] + c
    }

    fn total_corners(&self) -> usize {
        self.corners.len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn polygons_are_stored_flat_and_read_back() {
        let list = FaceList::from_polygons(&[vec![0, 1, 2, 3], vec![3, 2, 4]]);
        assert_eq!(list.len(), 2);
        assert_eq!(list.corners(0), &[0, 1, 2, 3]);
        assert_eq!(list.corners(1), &[3, 2, 4]);
        assert_eq!(list.corner_index(1, 2), 6);
        assert_eq!(list.total_corners(), 7);
        assert!(!list.all_triangles());
        assert_eq!(list.to_triangles(), None);
        let triangles = FaceList::from_triangles(&[[0, 1, 2], [2, 1, 3]]);
        assert_eq!(triangles.to_triangles(), Some(vec![[0, 1, 2], [2, 1, 3]]));
        assert_eq!(
            triangles.renumbered(&[3, 2, 1, 0]).to_triangles(),
            Some(vec![[3, 2, 1], [1, 2, 0]])
        );
    }
}
