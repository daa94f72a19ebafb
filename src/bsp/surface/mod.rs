//! An operand's surface as a polygon set with a BVH: which polygons of the other operand come
//! near it, and whether a point away from it is inside (ray parity). The polygon set and its
//! index are here; `near` holds the near-pair tests ([`Surface::near_each_other`]), `ray` the
//! ray parts (crossing counts, segment labels, the winding fallback).

mod near;
mod ray;

use std::borrow::Cow;

use crate::geom::Aabb;
use crate::geom::bvh::Bvh;
use crate::polygon::Polygon;

pub(crate) struct Surface<'a> {
    polygons: &'a [Polygon],
    boxes: Cow<'a, [Aabb]>,
    bvh: Cow<'a, Bvh>,
    eps: f64,
}

/// A polygon set's boxes and their hierarchy, what a [`Surface`] of it is built on: made once
/// for a solid read from a mesh, rather than by every boolean it enters.
#[derive(Debug)]
pub(crate) struct SurfaceIndex {
    boxes: Vec<Aabb>,
    bvh: Bvh,
}

impl SurfaceIndex {
    /// The boxes of `polygons` and their hierarchy.
    pub(crate) fn new(polygons: &[Polygon]) -> SurfaceIndex {
        let boxes: Vec<Aabb> = polygons.iter().map(Polygon::bbox).collect();
        let bvh = Bvh::build(&boxes);
        SurfaceIndex { boxes, bvh }
    }
}

impl<'a> Surface<'a> {
    pub fn new(polygons: &'a [Polygon], eps: f64) -> Self {
        let SurfaceIndex { boxes, bvh } = SurfaceIndex::new(polygons);
        Surface {
            polygons,
            boxes: Cow::Owned(boxes),
            bvh: Cow::Owned(bvh),
            eps,
        }
    }

    /// [`Surface::new`] on the index made of these polygons before.
    pub fn indexed(polygons: &'a [Polygon], index: &'a SurfaceIndex, eps: f64) -> Self {
        debug_assert_eq!(polygons.len(), index.boxes.len());
        Surface {
            polygons,
            boxes: Cow::Borrowed(&index.boxes),
            bvh: Cow::Borrowed(&index.bvh),
            eps,
        }
    }

    /// The polygons, in order.
    pub fn polygons(&self) -> &'a [Polygon] {
        self.polygons
    }

    /// The polygons' boxes, in order (each `Polygon::bbox`).
    pub fn boxes(&self) -> &[Aabb] {
        &self.boxes
    }

    /// Polygon `g` of the surface.
    pub fn polygon(&self, g: u32) -> &Polygon {
        &self.polygons[g as usize]
    }
}
