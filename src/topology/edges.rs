//! The edge table of a set of faces.

/// The half-edges of a set of faces, sorted so that the uses of each undirected edge are
/// adjacent. Each entry is `(edge key, face << 1 | forward)`, where the key packs the smaller
/// and larger vertex index and `forward` says the face runs from the smaller to the larger.
pub(crate) struct EdgeTable {
    half: Vec<(u64, usize)>,
}

/// How many edges of each kind an [`EdgeTable`] holds.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct EdgeCounts {
    pub edges: usize,
    /// Used by one face.
    pub boundary: usize,
    /// Used by more than two faces.
    pub non_manifold: usize,
    /// Used by two faces in the same direction.
    pub inconsistent: usize,
}

impl EdgeTable {
    /// The table of the faces `f` for which `include(f)` holds. Faces must have distinct
    /// indices (a repeated one would make a loop edge).
    pub fn new<F: AsRef<[u32]>>(faces: &[F], include: impl Fn(usize) -> bool) -> Self {
        let mut half = Vec::with_capacity(3 * faces.len());
        for (f, face) in faces.iter().enumerate().filter(|(f, _)| include(*f)) {
            let face = face.as_ref();
            for (k, &a) in face.iter().enumerate() {
                let b = face[(k + 1) % face.len()];
                let (lo, hi) = (a.min(b), a.max(b));
                half.push((
                    (u64::from(lo) << 32) | u64::from(hi),
                    (f << 1) | usize::from(a < b),
                ));
            }
        }
        half.sort_unstable_by_key(|h| h.0);
        EdgeTable { half }
    }

    /// The uses of each undirected edge, one slice per edge.
    pub fn runs(&self) -> impl Iterator<Item = &[(u64, usize)]> {
        self.half.chunk_by(|x, y| x.0 == y.0)
    }

    /// Counts edges by kind.
    pub fn counts(&self) -> EdgeCounts {
        let mut c = EdgeCounts::default();
        for run in self.runs() {
            c.edges += 1;
            match run {
                [_] => c.boundary += 1,
                [(_, x), (_, y)] => c.inconsistent += usize::from((x ^ y) & 1 == 0),
                _ => c.non_manifold += 1,
            }
        }
        c
    }
}
