//! Helpers of the validation test files (`validate.rs`, `validate_from_mesh.rs`,
//! `validate_models.rs`): small built meshes, a bitwise weld, and `Solid::from_mesh`'s results.

use std::collections::HashMap;

use bspcsg::{Error, FromMeshOptions, Mesh, Solid};
use glam::DVec3;

pub fn cube_mesh() -> Mesh {
    Solid::cube(1.0).unwrap().to_mesh()
}

pub fn tetra() -> Mesh {
    Mesh::new(
        vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
        vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]],
    )
}

pub fn weld(mut m: Mesh) -> Mesh {
    let mut map: HashMap<[u64; 3], u32> = HashMap::new();
    let mut positions = Vec::new();
    let remap: Vec<u32> = m
        .positions
        .iter()
        .map(|p| {
            let key = (*p + DVec3::ZERO).to_array().map(f64::to_bits);
            *map.entry(key).or_insert_with(|| {
                positions.push(*p);
                positions.len() as u32 - 1
            })
        })
        .collect();
    for t in &mut m.triangles {
        *t = t.map(|i| remap[i as usize]);
    }
    m.positions = positions;
    m
}

/// The tetrahedron with edge 0-1 split at m on one side only, and the crack closed by the
/// zero-area triangle [1, 0, m]: closed and oriented, but degenerate.
pub fn tetra_with_zero_area_triangle() -> Mesh {
    let mut m = tetra();
    m.positions.push(DVec3::new(0.5, 0.0, 0.0));
    m.triangles[0] = [0, 2, 4];
    m.triangles.push([4, 2, 1]);
    m.triangles.push([1, 0, 4]);
    m.sources.resize(m.triangles.len(), 0);
    m
}

/// The message of the `InvalidMesh` error `r` must be.
pub fn invalid_message(r: bspcsg::Result<Solid>) -> String {
    match r {
        Err(Error::InvalidMesh { path: None, defect }) => defect.to_string(),
        other => panic!("expected InvalidMesh, got {other:?}"),
    }
}

/// The solid of `m` with coplanar triangles merged into polygons.
pub fn merged(m: &Mesh) -> Solid {
    let options = FromMeshOptions::default().with_merge_coplanar(true);
    Solid::from_mesh_with(m, &options).unwrap()
}
