//! Overlapping shells taken as their union, when asked
//! ([`FromMeshOptions::union_shells`](crate::FromMeshOptions::union_shells)).
//!
//! A file of two boxes written into one mesh is closed and manifold but bounds no solid: its
//! shells cross. What its author meant is mostly their union. Each shell (with the cavities
//! inside it) is built as a solid on its own and the solids are united — only where every
//! shell is a solid on its own: a shell that crosses itself has no inside to unite, and is
//! refused naming the crossing.

use glam::DVec3;

use crate::disjoint_sets::DisjointSets;
use crate::error::{Error, MeshDefect, Result};
use crate::mesh::Mesh;
use crate::mesh::import::{FromMeshOptions, polygons_from_mesh};
use crate::mesh::self_intersect::{MAX_CROSSING_PAIRS, crossing_pairs};
use crate::topology::EdgeTable;

use super::{BoolOp, Containment, PointClassifier, Solid, boolean_all};

/// The solid bounded by `mesh`, after the checks [`FromMeshOptions`] asks for; crossing
/// shells united where [`union_shells`](FromMeshOptions::union_shells) says so.
pub(crate) fn solid_from_mesh(mesh: &Mesh, options: &FromMeshOptions) -> Result<Solid> {
    match polygons_from_mesh(mesh, options) {
        Err(Error::InvalidMesh {
            defect: MeshDefect::SelfIntersecting { .. },
            ..
        }) if options.union_shells => {
            // A search stopped at its budget cannot say which shells cross themselves.
            let crossing = crossing_pairs(&mesh.positions, &mesh.triangles);
            if !crossing.complete {
                return Err(Error::mesh(MeshDefect::CrossingCheckOverBudget {
                    triangles: mesh.triangles.len(),
                    candidates: crossing.offered,
                }));
            }
            union_of_shells(mesh, options, &crossing.pairs)
        }
        other => other.map(Solid::from_mesh_polygons),
    }
}

/// The union of the shells of a closed mesh whose shells cross (`crossing`: its crossing
/// triangle pairs, not empty), each shell with its cavities a solid of its own.
pub(crate) fn union_of_shells(
    mesh: &Mesh,
    options: &FromMeshOptions,
    crossing: &[(u32, u32)],
) -> Result<Solid> {
    let shell = shell_of_each_triangle(mesh);
    let within: Vec<_> = crossing
        .iter()
        .filter(|&&(t, u)| shell[t as usize] == shell[u as usize])
        .collect();
    if let Some(&&(t, u)) = within.first() {
        return Err(Error::mesh(MeshDefect::ShellCrossesItself {
            pairs: within.len(),
            more: crossing.len() >= MAX_CROSSING_PAIRS,
            first: [t as usize, u as usize],
        }));
    }
    // Each shell as a mesh of its own, sharing the positions.
    let mut shells: Vec<Mesh> = Vec::new();
    let mut index = vec![usize::MAX; mesh.triangles.len()];
    for (t, &s) in shell.iter().enumerate() {
        if index[s] == usize::MAX {
            index[s] = shells.len();
            shells.push(Mesh {
                positions: mesh.positions.clone(),
                triangles: Vec::new(),
                sources: Vec::new(),
            });
        }
        let m = &mut shells[index[s]];
        m.triangles.push(mesh.triangles[t]);
        m.sources.push(mesh.sources[t]);
    }
    // Outward shells stand alone; a cavity (negative volume) joins the smallest outward shell
    // around all of it (one that only some other shell's overlap closes is refused: no shell
    // with its cavities would be a solid on its own).
    let count = shells.len();
    let (outer, cavities): (Vec<Mesh>, Vec<Mesh>) =
        shells.into_iter().partition(|m| m.volume() > 0.0);
    let single = FromMeshOptions {
        union_shells: false,
        ..*options
    };
    let mut parts: Vec<(Mesh, Solid)> = outer
        .into_iter()
        .map(|m| polygons_from_mesh(&m, &single).map(|p| (m, Solid::from_mesh_polygons(p))))
        .collect::<Result<_>>()?;
    // Judged against the outward shells alone, before any takes a cavity in.
    let around: Vec<(PointClassifier, f64)> = parts
        .iter()
        .map(|(_, s)| (s.classifier(), s.volume()))
        .collect();
    for cavity in cavities {
        let corners: Vec<DVec3> = cavity
            .triangles
            .iter()
            .flatten()
            .map(|&i| cavity.positions[i as usize])
            .collect();
        let parent = around
            .iter()
            .enumerate()
            .filter(|(_, (c, _))| {
                corners
                    .iter()
                    .all(|&p| c.classify(p) != Containment::Outside)
            })
            .min_by(|(_, (_, x)), (_, (_, y))| x.total_cmp(y))
            .map(|(i, _)| i);
        let Some(i) = parent else {
            return Err(Error::mesh(MeshDefect::InsideOut {
                inverted_shells: 1,
                shells: count,
            }));
        };
        let m = &mut parts[i].0;
        m.triangles.extend_from_slice(&cavity.triangles);
        m.sources.extend_from_slice(&cavity.sources);
        parts[i].1 = Solid::from_mesh_polygons(polygons_from_mesh(m, &single)?);
    }
    Ok(boolean_all(
        parts.into_iter().map(|(_, s)| s),
        BoolOp::Union,
    ))
}

/// Each triangle's shell: triangles joined across edges used by exactly two (the mesh is
/// closed), named by the shell's first triangle.
fn shell_of_each_triangle(mesh: &Mesh) -> Vec<usize> {
    let table = EdgeTable::new(&mesh.triangles, |_| true);
    let mut sets = DisjointSets::new(mesh.triangles.len());
    for run in table.runs() {
        if let &[(_, x), (_, y)] = run {
            sets.union(x >> 1, y >> 1);
        }
    }
    (0..mesh.triangles.len()).map(|t| sets.find(t)).collect()
}
