//! Joining the blocks' parts into one mesh.

use super::leaf::Part;
use crate::hash::FxHashMap;
use crate::mesh::Mesh;

/// Joins the blocks' parts, matching boundary vertices by grid edge.
pub(super) fn merge(parts: Vec<Part>) -> Mesh {
    let nv: usize = parts.iter().map(|p| p.positions.len()).sum();
    let nt: usize = parts.iter().map(|p| p.triangles.len()).sum();
    let ns: usize = parts.iter().map(|p| p.shared.len()).sum();
    let mut seen: FxHashMap<u64, u32> =
        FxHashMap::with_capacity_and_hasher(ns / 2 + 1, Default::default());
    let mut positions = Vec::with_capacity(nv);
    let mut triangles = Vec::with_capacity(nt);
    let mut remap: Vec<u32> = Vec::new();
    for part in parts {
        remap.clear();
        remap.resize(part.positions.len(), u32::MAX);
        // Boundary vertices first: the first block to reach a grid edge owns its vertex, also
        // among the leaf blocks of one part.
        for &(key, local) in &part.shared {
            let g = *seen.entry(key).or_insert_with(|| {
                positions.push(part.positions[local as usize]);
                (positions.len() - 1) as u32
            });
            remap[local as usize] = g;
        }
        for (i, &p) in part.positions.iter().enumerate() {
            if remap[i] == u32::MAX {
                remap[i] = positions.len() as u32;
                positions.push(p);
            }
        }
        triangles.extend(part.triangles.iter().map(|t| t.map(|v| remap[v as usize])));
    }
    Mesh::new(positions, triangles)
}
