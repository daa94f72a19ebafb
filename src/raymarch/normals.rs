//! Shading normals of a triangle mesh, split at creases.
//!
//! A vertex shared by a fillet and the flat face it meets must not carry one normal averaged over
//! both: the flat face, fanned from that vertex, would then shade as a fan and the crease would
//! blur. So each triangle corner gets its own normal: the angle-weighted average of the normals
//! of the triangles around its vertex that lie within [`CREASE_DEG`] of this triangle. Across a
//! sharper edge the two sides never mix; on a smooth surface every corner at a vertex agrees.
//! Angle weights (not area) keep the result independent of how a face happens to be fanned.

use glam::DVec3;

use crate::mesh::Mesh;

/// Two triangles meeting at a vertex whose normals differ by more than this many degrees
/// belong to different smoothing groups there (a crease; shading stays sharp across it).
pub const CREASE_DEG: f64 = 30.0;

/// One shading normal per triangle corner (`[t][k]` for `mesh.triangles[t][k]`), unit length,
/// or zero for a degenerate triangle (which the caller shades by its face normal).
pub(crate) fn corner_normals(mesh: &Mesh) -> Vec<[DVec3; 3]> {
    let cos_crease = CREASE_DEG.to_radians().cos();
    let n_tri = mesh.triangles.len();
    let mut face = vec![DVec3::ZERO; n_tri];
    let mut angle = vec![[0.0f64; 3]; n_tri];
    // Corners around each vertex, in compressed rows: corners[start[v]..start[v + 1]].
    let mut start = vec![0usize; mesh.positions.len() + 1];
    for (t, tri) in mesh.triangles.iter().enumerate() {
        let Some(c) = corners(mesh, tri) else {
            continue;
        };
        face[t] = (c[1] - c[0]).cross(c[2] - c[0]).normalize_or_zero();
        if face[t] == DVec3::ZERO {
            continue;
        }
        for k in 0..3 {
            let (e1, e2) = (c[(k + 1) % 3] - c[k], c[(k + 2) % 3] - c[k]);
            angle[t][k] = e1.angle_between(e2);
            start[tri[k] as usize + 1] += 1;
        }
    }
    for v in 0..mesh.positions.len() {
        start[v + 1] += start[v];
    }
    let mut fill = start.clone();
    let mut around = vec![(0u32, 0u8); start[mesh.positions.len()]];
    for (t, tri) in mesh.triangles.iter().enumerate() {
        if face[t] == DVec3::ZERO {
            continue;
        }
        for (k, &v) in tri.iter().enumerate() {
            around[fill[v as usize]] = (t as u32, k as u8);
            fill[v as usize] += 1;
        }
    }
    let mut out = vec![[DVec3::ZERO; 3]; n_tri];
    for (t, tri) in mesh.triangles.iter().enumerate() {
        if face[t] == DVec3::ZERO {
            continue;
        }
        for (k, &v) in tri.iter().enumerate() {
            let v = v as usize;
            let mut sum = DVec3::ZERO;
            for &(u, j) in &around[start[v]..start[v + 1]] {
                let n = face[u as usize];
                if n.dot(face[t]) >= cos_crease {
                    sum += n * angle[u as usize][j as usize];
                }
            }
            out[t][k] = sum.try_normalize().unwrap_or(face[t]);
        }
    }
    out
}

/// The three corner positions of a triangle; `None` when an index is out of range.
pub(crate) fn corners(mesh: &Mesh, tri: &[u32; 3]) -> Option<[DVec3; 3]> {
    let [a, b, c] = tri.map(|i| mesh.positions.get(i as usize).copied());
    Some([a?, b?, c?])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solid::Solid;

    fn mesh_of(solid: Result<Solid, crate::error::Error>) -> Mesh {
        solid.expect("solid").to_mesh()
    }

    #[test]
    fn a_box_keeps_every_corner_on_its_face() {
        let mesh = mesh_of(Solid::cube(2.0));
        let normals = corner_normals(&mesh);
        for (t, tri) in mesh.triangles.iter().enumerate() {
            let c = corners(&mesh, tri).unwrap();
            let face = (c[1] - c[0]).cross(c[2] - c[0]).normalize();
            for n in normals[t] {
                assert!(
                    (n - face).length() < 1e-12,
                    "{n} off the face normal {face}"
                );
            }
        }
    }

    #[test]
    fn a_sphere_shares_one_normal_per_vertex_pointing_out() {
        let mesh = mesh_of(Solid::sphere(1.0, 32, 16));
        let normals = corner_normals(&mesh);
        let mut seen = vec![None::<DVec3>; mesh.positions.len()];
        for (t, tri) in mesh.triangles.iter().enumerate() {
            for (k, &v) in tri.iter().enumerate() {
                let n = normals[t][k];
                let radial = mesh.positions[v as usize].normalize();
                assert!(
                    n.dot(radial) > 0.99,
                    "corner normal {n} far from radial {radial}"
                );
                match seen[v as usize] {
                    None => seen[v as usize] = Some(n),
                    Some(m) => assert!((m - n).length() < 1e-12, "vertex {v}: {m} vs {n}"),
                }
            }
        }
    }

    #[test]
    fn a_cylinder_splits_at_its_rims_and_smooths_its_side() {
        let mesh = mesh_of(Solid::cylinder(1.0, 2.0, 24));
        let normals = corner_normals(&mesh);
        for (t, tri) in mesh.triangles.iter().enumerate() {
            let c = corners(&mesh, tri).unwrap();
            let face = (c[1] - c[0]).cross(c[2] - c[0]).normalize();
            for (k, &v) in tri.iter().enumerate() {
                let n = normals[t][k];
                if face.y.abs() > 0.99 {
                    // A cap: flat, however it is fanned.
                    assert!((n - face).length() < 1e-12, "cap corner {n}");
                } else {
                    // The side: radial at the vertex, no part of the cap's normal.
                    let p = mesh.positions[v as usize];
                    let radial = DVec3::new(p.x, 0.0, p.z).normalize();
                    assert!(
                        n.y.abs() < 1e-12 && n.dot(radial) > 0.999,
                        "side corner {n}"
                    );
                }
            }
        }
    }
}
