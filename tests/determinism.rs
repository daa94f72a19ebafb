//! The same boolean gives the same mesh, bit for bit, however rayon shares out the work.
//!
//! Clipping labels a fragment that ends in an unbuilt cell of the tree from a point already
//! labelled by the same rayon job (`Scratch` in `bsp::clip`), so which point that is depends
//! on how the work was split and stolen. On grazing and coplanar input a different starting
//! point must still give the same label; these cases run each boolean repeatedly on pools of
//! one, two and four threads (inputs past the clip's parallel threshold) and compare every run
//! with the first: triangle count, every vertex position and index, source ids, and the volume.
//! The sphere moved half a radius and the touching shells turned by a hair each label some
//! thousands of fragments in unbuilt cells inside the parallel clip (counted when the test
//! was written); the others clip in parallel with every fragment reaching a built leaf.

use bspcsg::glam::DVec3;
use bspcsg::{Mesh, Solid};

/// Runs per pool size.
const RUNS: usize = 4;

/// One run's output, compared whole: the mesh and the solid's volume as bits.
#[derive(PartialEq)]
struct Outcome {
    positions: Vec<[u64; 3]>,
    triangles: Vec<[u32; 3]>,
    sources: Vec<u32>,
    volume: u64,
    polygons: usize,
}

impl Outcome {
    fn of(solid: &Solid) -> Outcome {
        let mesh: Mesh = solid.to_mesh();
        Outcome {
            positions: mesh
                .positions
                .iter()
                .map(|p| [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()])
                .collect(),
            triangles: mesh.triangles,
            sources: mesh.sources,
            volume: solid.volume().to_bits(),
            polygons: solid.polygon_count(),
        }
    }

    /// What differs from `other`, for the failure message.
    fn difference(&self, other: &Outcome) -> String {
        let moved = self
            .positions
            .iter()
            .zip(&other.positions)
            .filter(|(a, b)| a != b)
            .count();
        format!(
            "polygons {} vs {}, triangles {} vs {}, vertices {} vs {} ({moved} differ), \
             volume {:e} vs {:e}",
            self.polygons,
            other.polygons,
            self.triangles.len(),
            other.triangles.len(),
            self.positions.len(),
            other.positions.len(),
            f64::from_bits(self.volume),
            f64::from_bits(other.volume),
        )
    }
}

/// Runs `op` [`RUNS`] times on pools of one, two and four threads and asserts every outcome is
/// the first's (one thread: `to_mesh`'s joined halves and parallel blocks run in sequence).
fn assert_repeatable(name: &str, op: impl Fn() -> Solid + Sync) {
    let mut first: Option<Outcome> = None;
    for threads in [1, 2, 4] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        for run in 0..RUNS {
            let outcome = pool.install(|| Outcome::of(&op()));
            assert!(outcome.polygons > 0, "{name}: empty result");
            match &first {
                None => first = Some(outcome),
                Some(f) => assert!(
                    *f == outcome,
                    "{name}: run {run} on {threads} threads differs from the first: {}",
                    f.difference(&outcome)
                ),
            }
        }
    }
}

/// A slab of `n` × `n` unit boxes, each sharing its side faces with its neighbours.
fn boxes(n: usize) -> Vec<Solid> {
    let mut out = Vec::new();
    for i in 0..n {
        for j in 0..n {
            let b = Solid::cube(1.0)
                .unwrap()
                .translate(DVec3::new(i as f64 + 0.5, j as f64 + 0.5, 0.5))
                .unwrap();
            out.push(b);
        }
    }
    out
}

/// The union of [`boxes`]: one slab whose top and bottom stay in tile-sized pieces.
fn tiles(n: usize) -> Solid {
    Solid::union_all(boxes(n))
}

/// [`boxes`] as they are, one solid of `n²` shells each touching its neighbours face to face.
fn shells(n: usize) -> Solid {
    Solid::from_polygons(
        boxes(n)
            .into_iter()
            .flat_map(Solid::into_polygons)
            .collect(),
    )
}

#[test]
fn sphere_union_moved_copy_is_repeatable() {
    // Moved half a radius: the fragments near the crossing curve are over a thousand.
    let a = Solid::sphere(1.0, 128, 64).unwrap();
    let b = a.clone().translate(DVec3::new(0.5, 0.0, 0.0)).unwrap();
    assert_repeatable("sphere | sphere moved 0.5", || &a | &b);
    // The difference flips B: its far polygons (the core among them) are turned while the
    // output is assembled in parallel, their vertex ids laid out reversed.
    assert_repeatable("sphere - sphere moved 0.5", || &a - &b);
}

#[test]
fn sphere_union_copy_moved_by_a_hair_is_repeatable() {
    // Moved 1e-7 along a skew direction: every face grazes its copy.
    let a = Solid::sphere(1.0, 64, 32).unwrap();
    let b = a
        .clone()
        .translate(DVec3::new(0.3, 1.0, 0.2) * 1e-7)
        .unwrap();
    assert!(a.polygon_count() > 512);
    assert_repeatable("sphere | sphere moved 1e-7", || &a | &b);
    assert_repeatable("sphere & sphere moved 1e-7", || &a & &b);
}

/// The same at 128 x 64: the indexed repair welds over 8,192 distinct positions, many of them
/// cut points close together, so on more than one thread its grid pass marks the lone ones in
/// parallel and walks the rest; the one-thread pool walks them all.
#[test]
fn a_larger_sphere_union_copy_moved_by_a_hair_is_repeatable() {
    let a = Solid::sphere(1.0, 128, 64).unwrap();
    let b = a
        .clone()
        .translate(DVec3::new(0.3, 1.0, 0.2) * 1e-7)
        .unwrap();
    assert_repeatable("sphere 128 x 64 | sphere moved 1e-7", || &a | &b);
}

#[test]
fn sphere_less_copy_turned_by_a_hair_is_repeatable() {
    let a = Solid::sphere(1.0, 64, 32).unwrap();
    let b = a
        .clone()
        .rotate_axis_angle(DVec3::new(0.3, 1.0, 0.2), 1e-6)
        .unwrap();
    assert_repeatable("sphere - sphere turned 1e-6 deg", || &a - &b);
}

#[test]
fn tiles_sharing_faces_are_repeatable() {
    // Tiles against tiles moved half a tile along x: every z face and every y side face is
    // coplanar with one of the other operand's.
    assert_repeatable("union of 16 x 16 boxes", || tiles(16));
    let a = tiles(16);
    assert!(a.polygon_count() > 512, "{}", a.polygon_count());
    let b = tiles(16).translate(DVec3::new(0.5, 0.0, 0.0)).unwrap();
    assert_repeatable("tiles | tiles moved half a tile", || &a | &b);
    assert_repeatable("tiles - tiles moved half a tile", || &a - &b);
    assert_repeatable("tiles & tiles moved half a tile", || &a & &b);
}

#[test]
fn shells_less_shells_turned_by_a_hair_is_repeatable() {
    // Turned 1e-6 degrees about a skew axis: every face grazes its own turned copy, and the
    // faces shared between shells meet the other operand's shared faces.
    let a = shells(12);
    assert!(a.polygon_count() > 512);
    let b = shells(12)
        .rotate_axis_angle(DVec3::new(1.0, 0.1, -0.4), 1e-6)
        .unwrap();
    assert_repeatable("shells - shells turned 1e-6 deg", || &a - &b);
    assert_repeatable("shells | shells turned 1e-6 deg", || &a | &b);
}

#[test]
fn shells_and_shells_moved_are_repeatable() {
    let a = shells(12);
    let b = shells(12).translate(DVec3::new(0.5, 0.0, 0.0)).unwrap();
    assert_repeatable("shells | shells moved half a tile", || &a | &b);
    assert_repeatable("shells & shells moved half a tile", || &a & &b);
}

#[test]
fn sphere_with_itself_is_repeatable() {
    // Every face coplanar with its copy, facing the same way.
    let s = Solid::sphere(1.0, 64, 32).unwrap();
    let t = s.clone();
    assert_repeatable("sphere | itself", || &s | &t);
    assert_repeatable("sphere & itself", || &s & &t);
}

/// A solid of no boolean has no vertex ids, so its mesh comes from the full repair pass, whose
/// exact weld (130,000 corners here) and edge sort run in two halves on more than one thread,
/// and whose grid pass walks only the positions that are not lone (see `weld::grid`): the
/// one-thread pool runs them serially, the reference.
#[test]
fn a_large_sphere_alone_is_repeatable() {
    let s = Solid::sphere(1.0, 256, 128).unwrap();
    assert_repeatable("sphere 256 x 128 alone", || s.clone());
}
