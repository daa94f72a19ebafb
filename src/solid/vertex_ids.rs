//! Which corners of an exact solid's polygons are one vertex, and which polygons are around
//! each vertex: what a boolean needs to pass its far part on indexed (see `far.rs`), made once
//! per solid rather than once per boolean.
//!
//! A solid made from a mesh carries it from the start; an exact operand without one (a
//! primitive, a moved solid) has it made by each boolean it enters.

use crate::hash::{KeyedHashMap, key};
use crate::polygon::Polygon;

/// The vertex ids of a solid's polygon corners and the polygons around each vertex.
#[derive(Debug)]
pub(crate) struct VertexIds {
    /// Polygon `i`'s corners' ids are `ids[start[i]..start[i + 1]]`. Equal ids are equal
    /// positions bit for bit (−0 taken as +0), and equal positions equal ids.
    ids: Vec<u32>,
    start: Vec<u32>,
    /// The polygons around vertex `v` are `around[around_at[v]..around_at[v + 1]]`, ascending
    /// (a polygon with a repeated corner as often as it has it).
    around: Vec<u32>,
    around_at: Vec<u32>,
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
        let n = id_of.len();
        drop(id_of);
        // A compressed table by vertex id.
        let mut around_at = vec![0u32; n + 1];
        for &id in &ids {
            around_at[id as usize + 1] += 1;
        }
        for v in 0..n {
            around_at[v + 1] += around_at[v];
        }
        let mut fill = around_at.clone();
        let mut around = vec![0u32; ids.len()];
        for (i, s) in start.windows(2).enumerate() {
            for &id in &ids[s[0] as usize..s[1] as usize] {
                around[fill[id as usize] as usize] = i as u32;
                fill[id as usize] += 1;
            }
        }
        VertexIds {
            ids,
            start,
            around,
            around_at,
        }
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
        &self.around[self.around_at[v as usize] as usize..self.around_at[v as usize + 1] as usize]
    }

    pub(crate) fn vertex_count(&self) -> usize {
        self.around_at.len() - 1
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
