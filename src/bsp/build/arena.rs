//! The polygons of one build, with their boxes and centroids cached, addressed by `u32` ids.

use glam::DVec3;

use super::{Focus, Ids};
use crate::geom::Aabb;
use crate::polygon::Polygon;

/// Polygons with their boxes and centroids: the solid's own, borrowed, then the split pieces,
/// appended. Borrowing spares a copy of every polygon of the operand per boolean.
pub(super) struct Arena<'a> {
    base: &'a [Polygon],
    pieces: Vec<Polygon>,
    pub(super) boxes: Vec<Aabb>,
    /// The centroids of the polygons that are not far (NaN for a far one: never read).
    pub(super) centroids: Vec<DVec3>,
    /// Per piece, the index in `base` of the polygon it was cut from.
    origins: Vec<u32>,
    /// The corners of the pieces stored since the build last charged its meter.
    pub(super) cut: u64,
}

impl<'a> Arena<'a> {
    /// The arena of `base`. With a `focus`, its boxes are the focus's `own_boxes` (the
    /// operand's surface made them, bit for bit `Polygon::bbox`'s), and the centroids are made
    /// only for the polygons it marks near: a far polygon's is never read (cell planes are
    /// placed by the near ones alone, and far ones are never cut), and on real models nearly
    /// every polygon is far (rocker-arm ∪ moved: 1.2 k near of 20 k).
    pub(super) fn new(base: &'a [Polygon], focus: Option<&Focus>) -> Self {
        // Cell splits cut the long thin triangles of tessellated CAD parts into about two
        // pieces per polygon of the solid: room for that from the start spares copying the
        // growing arena (a fifth of the build's instructions).
        let room = 2 * base.len();
        let mut boxes = Vec::with_capacity(base.len() + room);
        let mut centroids = Vec::with_capacity(base.len() + room);
        match focus {
            Some(focus) => {
                debug_assert_eq!(focus.own_boxes.len(), base.len(), "a box per polygon");
                boxes.extend_from_slice(focus.own_boxes);
                centroids.extend(
                    base.iter()
                        .zip(focus.near)
                        .map(|(p, &n)| if n { p.centroid() } else { DVec3::NAN }),
                );
            }
            None => {
                boxes.extend(base.iter().map(Polygon::bbox));
                centroids.extend(base.iter().map(Polygon::centroid));
            }
        }
        Arena {
            base,
            pieces: Vec::with_capacity(room),
            boxes,
            centroids,
            origins: Vec::with_capacity(room),
            cut: 0,
        }
    }

    pub(super) fn len(&self) -> usize {
        self.base.len() + self.pieces.len()
    }

    pub(super) fn poly(&self, id: u32) -> &Polygon {
        let id = id as usize;
        match self.base.get(id) {
            Some(p) => p,
            None => &self.pieces[id - self.base.len()],
        }
    }

    /// Whether `id` is one of the solid's own polygons, not a piece this build cut: where it
    /// tracks no edge planes, its vertices were made on no plane but those of the polygons
    /// sharing them (see [`Polygon::split_as`]).
    pub(super) fn given(&self, id: u32) -> bool {
        (id as usize) < self.base.len()
    }

    /// The index in `base` of the polygon `id` is or was cut from.
    pub(super) fn origin(&self, id: u32) -> u32 {
        match (id as usize).checked_sub(self.base.len()) {
            None => id,
            Some(k) => self.origins[k],
        }
    }

    /// Stores a piece cut from polygon `from`.
    pub(super) fn push(&mut self, p: Polygon, from: u32) -> u32 {
        self.origins.push(self.origin(from));
        self.cut += p.vertices().len() as u64;
        self.boxes.push(p.bbox());
        self.centroids.push(p.centroid());
        self.pieces.push(p);
        (self.len() - 1) as u32
    }

    pub(super) fn bbox_of(&self, ids: &[u32]) -> Aabb {
        ids.iter()
            .fold(Aabb::EMPTY, |b, &i| b.union(&self.boxes[i as usize]))
    }

    /// The box of a cell's polygons, far ones reaching out of it included: their boxes are
    /// cut down to the cell's (grown by `eps`, as far as the pieces of cut polygons reach past
    /// a plane).
    pub(super) fn bbox_in(&self, ids: &Ids, cell: &Aabb, eps: f64) -> Aabb {
        let cell = cell.expanded(eps);
        ids.far.iter().fold(self.bbox_of(&ids.near), |b, &i| {
            b.union(&self.boxes[i as usize].intersection(&cell))
        })
    }
}
