//! Unit tests of the needle pass's volume guard: each shell judged against its own volume and
//! the mesh's.

use glam::DVec3;

use super::super::remove_needles;
use super::read;

/// A right prism 6,666,122 long on a 6 × 3 end (its end face's two triangles, area 9, are
/// needles by its diagonal, and removing them takes half its volume) beside a cube 3,000 on a
/// side: half the prism is 0.11 % of the mesh's volume. Judged against the mesh's volume only
/// (round 23), the pass kept that removal; judged against the shell's own volume too, it redoes
/// the prism removing only the needles the kernel must (none: the end triangles are its own
/// well-shaped faces), and the prism keeps its volume.
#[test]
fn a_small_shell_beside_a_large_one_keeps_its_own_volume() {
    // The prism as the scenes' BSP route makes it (extruded from its profile).
    let mut mesh = read(
        "v 0 0 1.5\nv 0 0 -1.5\nv 6666122 0 -1.5\nv 6666122 0 1.5\nv 0 6 -1.5\nv 0 6 1.5
         f 1 2 3\nf 3 4 1\nf 4 3 5\nf 5 6 4\nf 6 5 2\nf 2 1 6\nf 5 3 2\nf 1 4 6",
    );
    let l = 6_666_122.0;
    let size = 3000.0;
    let base = mesh.positions.len() as u32;
    for k in 0..8 {
        let bit = |b: u32| f64::from((k >> b) & 1) * size;
        mesh.positions
            .push(DVec3::new(-10_000.0 + bit(0), bit(1), bit(2)));
    }
    let cube = [
        [0, 4, 6],
        [0, 6, 2],
        [1, 3, 7],
        [1, 7, 5],
        [0, 1, 5],
        [0, 5, 4],
        [2, 6, 7],
        [2, 7, 3],
        [0, 2, 3],
        [0, 3, 1],
        [4, 5, 7],
        [4, 7, 6],
    ];
    mesh.triangles
        .extend(cube.iter().map(|t: &[u32; 3]| t.map(|v| base + v)));
    mesh.sources.resize(mesh.triangles.len(), 0);
    let prism = 0.5 * 6.0 * l * 3.0;
    let cube = size * size * size;
    assert!((mesh.volume() - prism - cube).abs() < 1e-9 * cube);
    assert_eq!(mesh.report().needles, 2);
    remove_needles(&mut mesh, None, None);
    let report = mesh.report();
    assert!(
        report.is_closed_manifold() && (report.volume - cube - prism).abs() < 1e-9 * prism,
        "{report}, prism's volume {}",
        report.volume - cube
    );
}
