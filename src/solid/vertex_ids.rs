//! Which corners of an exact solid's polygons are one vertex, and which polygons are around
//! each vertex: what a boolean needs to pass its far part on indexed (see `far.rs`), made once
//! per solid rather than once per boolean.
//!
//! A solid made from a mesh carries it from the start; an exact operand without one (a
//! primitive, a moved solid) has it made by each boolean it enters.

use std::sync::OnceLock;

use crate::hash::{KeyedHashMap, key};
use crate::polygon::Polygon;

/// The vertex ids of a solid's polygon corners and the polygons around each vertex.
#[derive(Debug)]
pub(crate) struct VertexIds {
    /// Polygon `i`'s corners' ids are `ids[start[i]..start[i + 1]]`. Equal ids are equal
    /// positions bit for bit (−0 taken as +0), and equal positions equal ids.
    ids: Vec<u32>,
    start: Vec<u32>,
    vertices: usize,
    /// Whether the polygons are discs by position (a checked mesh's: see
    /// `mesh::import::MeshPolygons::discs_if_apart`).
    discs: bool,
    /// Made when first asked: only an operand passed on indexed needs it.
    around: OnceLock<Around>,
}

/// The polygons around vertex `v` are `list[at[v]..at[v + 1]]`, ascending (a polygon with a
/// repeated corner as often as it has it).
#[derive(Debug)]
struct Around {
    list: Vec<u32>,
    at: Vec<u32>,
}

impl VertexIds {
    /// The vertex ids of `polys`.
    pub(crate) fn new(polys: &[Polygon]) -> VertexIds {
        let mut id_of: KeyedHashMap<[u64; 3], u32> =
            KeyedHashMap::with_capacity_and_hasher(polys.len(), Default::default());
        let mut start = Vec::with_capacity(polys.len() + 1);
        let mut ids = Vec::with_capacity(3 * polys.len());
        for p in polys {
            start.push(ids.len() as u32);
            for &v in p.vertices() {
                let next = id_of.len() as u32;
                ids.push(*id_of.entry(key(v)).or_insert(next));
            }
        }
        start.push(ids.len() as u32);
        VertexIds {
            ids,
            start,
            vertices: id_of.len(),
            discs: false,
            around: OnceLock::new(),
        }
    }

    /// The table of polygons around each vertex, compressed by vertex id.
    fn make_around(&self) -> Around {
        let mut at = vec![0u32; self.vertices + 1];
        for &id in &self.ids {
            at[id as usize + 1] += 1;
        }
        for v in 0..self.vertices {
            at[v + 1] += at[v];
        }
        let mut fill = at.clone();
        let mut list = vec![0u32; self.ids.len()];
        for (i, s) in self.start.windows(2).enumerate() {
            for &id in &self.ids[s[0] as usize..s[1] as usize] {
                list[fill[id as usize] as usize] = i as u32;
                fill[id as usize] += 1;
            }
        }
        Around { list, at }
    }

    /// Whether these are the vertex ids of `polys` (its polygon and corner counts match).
    pub(crate) fn fits(&self, polys: &[Polygon]) -> bool {
        self.start.len() == polys.len() + 1
            && polys
                .iter()
                .zip(self.start.windows(2))
                .all(|(p, s)| p.vertices().len() == (s[1] - s[0]) as usize)
    }

    /// Polygon `i`'s corners' vertex ids.
    #[inline]
    pub(crate) fn corners(&self, i: usize) -> &[u32] {
        &self.ids[self.start[i] as usize..self.start[i + 1] as usize]
    }

    /// The polygons around vertex `v`.
    #[inline]
    pub(crate) fn around(&self, v: u32) -> &[u32] {
        let Around { list, at } = self.around.get_or_init(|| self.make_around());
        &list[at[v as usize] as usize..at[v as usize + 1] as usize]
    }

    pub(crate) fn vertex_count(&self) -> usize {
        self.vertices
    }

    /// Marks the polygons as discs by position, or not.
    pub(crate) fn set_discs(&mut self, discs: bool) {
        self.discs = discs;
    }

    /// Whether the polygons are discs by position.
    pub(crate) fn discs(&self) -> bool {
        self.discs
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;

    #[test]
    fn equal_positions_are_one_vertex() {
        let tri = |a: DVec3, b: DVec3, c: DVec3| Polygon::new(&[a, b, c], 0).unwrap();
        let (o, x, y, z) = (DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z);
        let polys = [
            tri(o, y, x),
            tri(DVec3::new(-0.0, 0.0, 0.0), x, z),
            tri(o, z, y),
            tri(x, y, z),
        ];
        let t = VertexIds::new(&polys);
        assert!(t.fits(&polys) && !t.fits(&polys[1..]));
        assert_eq!(t.vertex_count(), 4);
        assert_eq!(t.corners(1), [0, 2, 3]);
        assert_eq!(t.around(0), [0, 1, 2]);
        assert_eq!(t.around(3), [1, 2, 3]);
    }
}
