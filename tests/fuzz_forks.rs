//! The `booleans` fuzz target's fork runs (libFuzzer `-fork=1 -ignore_crashes=1`): every input
//! each run found failing is kept under `tests/fuzz_findings/booleans/roundNN_fork/` (named by
//! the artifact's hash, not minimised). Here are the lists of those that pass now
//! (`FORK_PASSING`, `FORK_18_PASSING`, `FORK_20_PASSING` and the named subsets), the tests that
//! replay them, the `--ignored` batches that replay the rest and print "N failing:" with the
//! ids, and the named tests of single fork inputs. Minimised cuts of fork inputs are in
//! `fuzz_findings.rs`.

#[path = "common/fuzz_replay.rs"]
mod fuzz_replay;

use fuzz_replay::{program, replay, replay_file};

// Found by a 10-minute `booleans` run in round 17 with libFuzzer's fork mode (seed 1706,
// `-fork=1 -ignore_crashes=1`, 38,826 executions in 602 s): 38 failing inputs, every one passing
// with tiny rotations off (checked one by one), so all the near-coplanar class; kept in
// `tests/fuzz_findings/booleans/round17_fork/` (named by the artifact's hash), not minimised. By
// kind: 17 not closed, 16 with the mesh's volume off the solid's, 2 closed with one needle, 3
// with the solid's volume outside its bounds — those three, the worst, also have tests of their
// own below.

/// Replays an input of the round-17 fork run (`round17_fork/<hash>.bin`).
fn replay_fork(hash: &str) {
    replay_file(&format!("round17_fork/{hash}"));
}

/// The inputs of the round-17 fork run that pass now (each closed, manifold, needle-free, the
/// mesh's volume the solid's and within the operation's bounds at every step), by hash.
///
/// 0948e42e, 1aeb92c4, 4ff3cfe7, d6e249f8, ec4e381d, f33d6823: a sliver about a tolerance
/// thick between faces crossing at 10⁻¹¹ rad (ec4e381d: a box turned 1e-9° cut from a cube,
/// intersected with another box turned 1e-9° whose face lies 10⁻¹² beside the hole's) that the
/// first weld laid flat, a fin of triangles back to back on the solid's edge, its two sides
/// paired with each other and the vertices where it met the solid split into two shells
/// (ec4e381d: 4 boundary edges). A triangle and its reverse are now dropped together before the
/// shells are split (`cancel_reversed_pairs` in `mesh/repair/fins.rs`).
///
/// 4c4a25bc, 7b9f78bf, 967a3be9, cf177d2c (the mesh's volume 10⁻⁸ off the solid's) and ea6f2083
/// (a flat shell), all starting from a cube turned 1e-7°: its corners, judged across the
/// crossing lines of faces 1.4e-9 rad apart, read ±7e-19 off them against a band of 2.6e-21
/// (`eps` times the sine), below the rounding of the lines' own position (4.4e-16 for planes
/// anchored 0.25 apart); judged within that (`Crossing::rounding` in `polygon/planes.rs`),
/// both operands count them on the lines.
///
/// 69eb964a (a unit cube united with a slab turned 1e-7°, then with a cylinder and a box turned
/// freely, less a box: step 3 a flat closed shell): a flap of several triangles that the flat
/// fill covered; taken away whole since (`flap_patch` in `mesh/repair/cracks.rs`).
///
/// e72a4a41 (two spheres of radius 0.4375 at one centre, one turned 1e-7°: step 2 closed with
/// one needle): at their south pole the two apexes, 5.6e-10 apart, cross in a tiny loop, a
/// patch of 14 vertices within 6.8e-10 of the pole whose every edge is below the speck length.
/// Every collapse of the needle's edges and the merge of its corners folded a neighbour; the
/// 12 vertices its short edge reaches by such edges now merge into one, the volume kept
/// (`Work::cluster` in `mesh/needles/merge.rs`).
///
/// 75ca2fd2 (the same two spheres, the other of 3 segments: step 1 closed, genus 7, with one
/// needle): the patch at the pole, 6 vertices within 9.8e-10, is a neck between the two cones,
/// the triangles around it an annulus; merged it would pinch the surface. It is cut, one apex
/// per boundary cycle, both at the volume-keeping point.
///
/// 9f0af865 (its own test, `union_with_a_bar_below_its_larger_operand`) and 7b3ae46a (an OBJ
/// slab united with three 0.125 cubes, one turned 1e-7°, then with a bar: step 3 open, a flat
/// shell): a sliver thinner than the tolerance between faces a hair apart, its end lying
/// across another face, lost that end's plane in the tree; it now also bounds the side it lies
/// on (`sliver_side` in `bsp/build/face.rs`).
///
/// Passing since near polygons are those within the margin of the other operand's planes, not
/// only of its boxes (b7a8df4, with the gap of 35af034): a polygon whose box meets the other's
/// but which lies wholly beyond its plane is classified whole, not cut by its tree (failing at
/// 6a0e4eb, before those; the polygons concerned not traced one by one):
///
/// - 1037da39 (cylinders, one turned 1e-9°, ∩ an OBJ slab): step 1 not closed.
/// - f4856d6f (cylinder ∪ cuboid turned 1e-7°, ∩ cube turned 1e-7°, ∪, −): step 3 not closed.
/// - f5c69f47 (cube ∪ slab turned 1e-7°, ∪ sphere, − two boxes): step 3 mesh 4.8e-5 off.
///
/// Also passing since 5982a0f, 2052e97 (the wedge; fragments labelled off a face), 95e7309 (a
/// segment nearly parallel to a face still crosses it) and 57fae4e, 99b9509 (edge cuts at the
/// shared three-plane meet below `MEET_BELOW`): the inputs not named above, not traced one by one Since
/// the polygons of one flat face of a mesh share one plane and edges of a polygon crossing a
/// nearly parallel plane are cut by their distances across the crossing line
/// (`share_face_planes` in `polygon/faces.rs`, `Polygon::split`), 37 more of the three runs'
/// inputs (round 17: 10, round 18: 14, round 20: 13), not traced one by one.
///
/// 93aab2f0 (a slab ∩ a 0.125 cube turned 1e-5°, ∪ that cube unturned, twice, ∪ a bar through
/// it, ∪ the cube: step 4 three flat shells, the solid 1.7e-4 above its mesh) since a ray
/// labelling a point judges no polygon edge within the tolerance long: the last union kept
/// pieces of the cube's faces lying in the bar's, labelled outside from two tolerances inside
/// the bar by a ray whose exit face's ring turned back by one ulp at a corner (`crossing` in
/// `bsp/surface/ray/mod.rs`; minimised in `turned_twins.rs`,
/// `union_with_a_cube_inside_a_bar_beside_its_turned_twin_changes_nothing`). With it, round
/// 20's edf27eb0 (a cylinder ∪ a bar turned 1e-3° ∪ the 0.125 cube three times, once an OBJ
/// box: step 3 the solid 2.1e-5 above its mesh), not traced.
///
/// 33894a02 (its own test, `intersection_with_a_flat_remnant_does_not_grow`): step 1 left a
/// flat closed sheet 1.5e-12 in volume, of which step 2's coplanar rule kept one side; such a
/// result is now the empty solid (`solid/flat.rs`).
const FORK_PASSING: [&str; 38] = [
    "0444665d", "0948e42e", "1037da39", "191ab237", "1aeb92c4", "2726d2e5", "32c62795", "33894a02",
    "4c4a25bc", "4f11d669", "4ff3cfe7", "56caf33f", "6674c41e", "69eb964a", "6b0e99dd", "72da0961",
    "75ca2fd2", "7b3ae46a", "7b9f78bf", "7d80d340", "93aab2f0", "967a3be9", "9e873673", "9edbc5f5",
    "9f0af865", "b9755cf2", "c2bc4de2", "c88c23a3", "cf177d2c", "d6e249f8", "e72a4a41", "ea6f2083",
    "ec4e381d", "f25a77c8", "f33d6823", "f4856d6f", "f5c69f47", "f914fc01",
];

/// Replays every input in `hashes` of the fork run kept in `run` (`round17_fork`,
/// `round18_fork`), and checks each passes without tiny rotations; the failures with tiny
/// rotations listed.
fn fork_failures(run: &str, hashes: &[&str]) -> Vec<String> {
    let mut failures = Vec::new();
    for hash in hashes {
        let path = format!(
            "{}/tests/fuzz_findings/booleans/{run}/{hash}.bin",
            env!("CARGO_MANIFEST_DIR")
        );
        let data = std::fs::read(&path).unwrap();
        assert!(
            program::run(&data, false).is_ok(),
            "{hash} fails without tiny rotations"
        );
        if let Err(e) = program::run(&data, true) {
            failures.push(format!("{hash}: {e}"));
        }
    }
    failures
}

/// Every input of the round-17 fork run passes now: [`FORK_PASSING`] is the whole run, each
/// replayed (the run's `--ignored` batch is gone since round 29).
#[test]
fn the_round_17_fork_run_inputs_that_pass() {
    assert_fork_run_passes("round17_fork", FORK_PASSING.len(), &[]);
}

/// Replays every input kept of the fork run `run` (there are `kept` of them) but those in
/// `skipped`, and fails listing those that fail (see [`fork_failures`]).
fn assert_fork_run_passes(run: &str, kept: usize, skipped: &[&str]) {
    let dir = format!(
        "{}/tests/fuzz_findings/booleans/{run}",
        env!("CARGO_MANIFEST_DIR")
    );
    let names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| {
            let name = e.unwrap().file_name().to_string_lossy().into_owned();
            name.trim_end_matches(".bin").to_owned()
        })
        .collect();
    assert_eq!(names.len(), kept);
    let mut open: Vec<&str> = names
        .iter()
        .map(String::as_str)
        .filter(|n| !skipped.contains(n))
        .collect();
    open.sort_unstable();
    let failures = fork_failures(run, &open);
    assert!(
        failures.is_empty(),
        "{} failing:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

// Found by a 10-minute `booleans` run in round 18 with libFuzzer's fork mode (seed 1801,
// `-fork=1 -ignore_crashes=1`, 84,447 executions in 604 s, on main after the fin drop and the
// crossing-line band): 69 failing inputs, every one passing with tiny rotations off, kept in
// `tests/fuzz_findings/booleans/round18_fork/` (named by the artifact's hash), not minimised.
// By kind: 37 not closed, 22 with the mesh's volume off the solid's, 8 with the solid's volume
// outside its bounds, 2 closed with one needle. 67 also fail at e991b46 (the round's start);
// the other two are named below: each came with one of this round's changes.

/// Every input of the round-18 fork run, replayed; the failures listed.
///
/// 1a668028 (a sphere ∪ a cylinder ∪ a 0.125 × 0.25 × 0.5 cuboid ∪ a 0.125 cube turned 1e-6°
/// inside it, less an OBJ 0.125 cube there: step 3 the solid 1.9e-5 above its mesh, open by
/// 4.2e-4 in +x) is traced, not fixed: the turned cube stands out of the cuboid's face
/// x = −0.4375 by up to 1e-9 on one side of the diagonal where its +x face crosses it, and the
/// cavity's wall there (1.9e-3 of the OBJ cube's face) is dropped. In step 2's tree an exact
/// face x = −0.4375 whose only polygon is a 6e-10 triangle at the cube's corner, within the
/// tolerance of the turned +x face and sent behind it, reads the wedge between the two planes
/// (behind the turned face, in front of its own) as outside: e11e6f68's case (see
/// [`FORK_20_PASSING`]) with the turned face above and the exact one below. Passing the face
/// nodes' corners down (`Corners` in `bsp/build/face.rs`), which closes e11e6f68, leaves it
/// failing with the same figures: not traced further.
#[test]
#[ignore = "open: near-coplanar — 2 inputs of round 18's fork run fail with tiny rotations on (the mesh's volume off the solid's), both pass with them off"]
fn the_round_18_fork_run_near_coplanar_inputs() {
    assert_fork_run_passes("round18_fork", 69, &FORK_18_PASSING);
}

/// The inputs of the round-18 fork run that pass now: a03b7e97 and b153683f, each with a test of
/// its own below, and 62f4302a (an OBJ box turned 1e-8° united with a cylinder turned 1e-7°, a
/// bar turned 1e-2° and a cylinder: step 2 a flat closed shell), closed since the fill takes a
/// flap of several triangles away whole; 94f4cf5d (a cylinder ∪ a 0.125 cube ∪ the cube turned
/// 1e-9° ∪ the cube ∪ a 0.125 × 0.875 × 0.125 bar: step 3 the solid's volume 2.9e-8 off the
/// mesh's), closed since steep faces ending a near-coplanar wedge also bound the side the
/// wedge's face went to (`Wedge` in `bsp/build/face.rs`; see [`FORK_20_PASSING`]); a406f929 (a
/// 0.125 × 0.625 × 0.875 slab turned 1e-9° ∪ 0.125 cubes, one in it, ∪ a box, then ∩ that
/// cube: step 3 the solid 2e-5 below its mesh, which was right), closed since a fragment
/// routed along a face of the tree is labelled across a nearly parallel face between it and
/// the point off it (`Surface::crossings_off`; see [`FORK_20_PASSING`]); a1909398 (0.125 cubes
/// at one centre, one turned 1e-5°, ∪ a box turned 1e-5°, then ∩ the exact cube: step 2 a flat
/// shell), closed since a sliver's vertex within the plane's rounding reaches neither side
/// (`sliver_side` in `bsp/build/face.rs`; its test in `turned_twins.rs`); 37e0688d (a bar turned
/// 0.298 rad ∪ a 0.125 cube and a 0.625 cube, both turned 1e-5° about their diagonal, ∩ the
/// 0.625 cube unturned: step 2 open, 4 boundary edges) and 71023f02 (the same union ∪ a
/// cylinder, less the unturned cube: step 3 open, 5 boundary edges; not traced), closed since an
/// edge whose neighbour was cut inside it by an earlier boolean takes that neighbour's plane
/// (`attach_edges_across_t_junctions` in `polygon/planes.rs`; minimised in `turned_twins.rs`):
/// its corner, 6.4e-15 off the unturned cube's face, no longer counts as made on it;
/// f35b6000 (a 0.125 × 0.625 × 0.875 box turned 1e-9° ∪ a cube ∪ an unturned box on its
/// face ∪ a 0.125 cube at its corner: step 2 open, 6 boundary edges), closed since a flat fin
/// whose two sides cover one quad along different diagonals is dropped like a reversed pair
/// (`cancel_reversed_quads` in `mesh/repair/fins.rs`); b447eea7 (a box turned 1e-6° ∪ cubes,
/// − a cylinder turned 1e-3°, − a box: step 3 closed with 2 needles; listed as passing until
/// round 27, failing since at least e991b46), passing since a needle's flip helps only where it
/// does more than move the needle along its line, the other edges' flips tried where the long
/// edge's does not (minimised in `fuzz_findings_needles.rs`); and the
/// inputs of [`FORK_18_SLIVER_ENDS`] and [`FORK_18_NEAR_PLANES`].
///
/// Also passing since the changes named at [`FORK_PASSING`]: the inputs not named above.
const FORK_18_PASSING: [&str; 67] = [
    "0052c3eb", "02530f35", "0790ea94", "0827a164", "0d0928b6", "10073393", "1520a690", "15d49cd9",
    "1790af98", "1e4064b4", "20453056", "3113dfce", "37e0688d", "37ff3bf3", "3900a850", "3cc49f00",
    "420d2bab", "5179ded6", "523bd25f", "540b19a9", "5a865123", "5bb3d708", "62f4302a", "71023f02",
    "7eef8488", "8114e14d", "81d5fe25", "8a96f30b", "94f4cf5d", "9690e076", "9afa182f", "9f600b4c",
    "a03b7e97", "a08947f3", "a1909398", "a406f929", "aa164e38", "ab676359", "b0b42816", "b0b4ab89",
    "b153683f", "b447eea7", "b4c5614a", "b69ed8aa", "bdff1088", "be4ad59a", "c0e3de16", "c7455c8d",
    "c8152ded", "c9b1a2f6", "ca3a7ad3", "ccc60bb4", "ce4b062b", "d52c6d78", "da05d311", "dd18b60b",
    "df981536", "e26cedea", "e4c5eda4", "e8b2a516", "ee10478e", "f31d7404", "f35b6000", "f74d9e2a",
    "f966a4ee", "fbbe3eb1", "fc859488",
];

/// Inputs of the round-18 fork run that pass since near polygons are chosen by the other
/// operand's planes (b7a8df4, 35af034; see [`FORK_PASSING`]), each failing at 6a0e4eb before
/// those:
///
/// - 02530f35 (box turned 1e-8° ∪ sphere − sphere − sphere): step 1 not closed.
/// - 0827a164 (cube turned freely ∪ OBJ box ∪ sphere turned 1e-9° ∩ sphere): step 2 mesh 2.9e-8
///   off.
/// - 3cc49f00 (OBJ box ∪ OBJ box turned 1e-5°, − cylinder, − box, ∩ box): step 1 not closed.
/// - 5179ded6 (OBJ slab turned 1e-8° ∪ OBJ box, − two cubes, ∪ bar): step 2 mesh 6.8e-4 off.
/// - 523bd25f (3-segment spheres at one centre, one turned 1e-9°, ∪ cylinder, −, ∪): step 3
///   not closed.
/// - 540b19a9 (cylinder ∪ cube turned 1e-6° ∪ bar ∪ cylinder): step 2 not closed.
/// - 8114e14d (3-segment spheres, one turned 1e-5°, ∪ sphere turned 1e-8°, ∪): step 1 not closed.
/// - a08947f3 (cylinder − sphere turned 1e-5° ∩ sphere turned 1e-5°, ∪ box): step 1 closed with
///   needles in 12 sliver shells.
/// - b0b42816 (slab turned 1e-8° ∪ four spheres): step 2 not closed.
/// - be4ad59a (cylinder turned 1e-5° ∩ three spheres turned 1e-5°): step 1 mesh 4e-9 off.
/// - ca3a7ad3 (3-segment spheres, one turned 1e-10°, − bar, ∪ sphere): step 3 mesh 1.3e-3 off.
/// - dd18b60b (slab ∪ sphere − sphere ∪ sphere turned 1e-4°, ∪): step 2 not closed.
/// - e8b2a516 (cylinder turned 1e-9° ∪ sphere ∪ box ∪ bar ∪ cylinder): step 3 not closed.
const FORK_18_NEAR_PLANES: [&str; 13] = [
    "02530f35", "0827a164", "3cc49f00", "5179ded6", "523bd25f", "540b19a9", "8114e14d", "a08947f3",
    "b0b42816", "be4ad59a", "ca3a7ad3", "dd18b60b", "e8b2a516",
];

/// Inputs of the round-18 fork run that pass since a sliver thinner than the tolerance across a
/// tree's face node also bounds the side it lies on (`sliver_side` in `bsp/build/face.rs`): each
/// unites exact boxes with a box turned 1e-9° or 1e-7° sharing a face, the thin wedge between
/// the near-coplanar faces ending across another face.
/// 10073393 (a cylinder turned freely ∪ a bar ∪ two 0.125 cubes, one turned 1e-9°, ∪ a prism;
/// step 3 open), 20453056 (a sphere less a cylinder ∪ a bar turned 1e-9° ∪ two boxes; step 3
/// the union below its operand), 37ff3bf3 (as 10073393 with a longer bar; step 2 the mesh's
/// volume 2.9e-6 off the solid's), 5bb3d708 (a cylinder ∪ a bar ∪ cubes one turned 1e-9° ∪ an
/// OBJ bar; step 3 open), c7455c8d (a bar ∪ a cube turned 1e-9° ∪ a bar; step 1 the mesh's
/// volume 7.8e-5 off), c9b1a2f6 (a cylinder turned 1e-7° ∪ bars, one turned 1e-9°; step 3
/// open).
const FORK_18_SLIVER_ENDS: [&str; 6] = [
    "10073393", "20453056", "37ff3bf3", "5bb3d708", "c7455c8d", "c9b1a2f6",
];

/// The inputs of the round-18 fork run that pass now ([`FORK_18_PASSING`], every one: the
/// named lists are its subsets).
#[test]
fn the_round_18_fork_run_inputs_that_pass() {
    for list in [&FORK_18_SLIVER_ENDS[..], &FORK_18_NEAR_PLANES[..]] {
        assert!(list.iter().all(|h| FORK_18_PASSING.contains(h)));
    }
    let failures = fork_failures("round18_fork", &FORK_18_PASSING);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// From the round-18 fork run (a03b7e97): a sphere (5 segments) turned 1e-9° less a sphere
/// (3) at the same centre, united with a box, then with a third sphere (3) there turned 1e-3°.
/// Step 2's mesh volume was 0.32261407249 against the solid's 0.32261407409 (1.6e-9 less) from
/// f704544 on, where a triangle and its reverse are dropped together before the shells are
/// split. Traced: the pairs dropped at the spheres' common pole were specks, four computations
/// of the pole within 2e-11 (the weld 1e-11), not fins; without them the flat fill closed the
/// pass with the copies apart, and the needles between them were removed by vertex moves that
/// took 4.4e-10 and 1.2e-9 of the volume. Kept (a pair with an edge under ten welds is not a
/// fin: `FIN_SHORTEST_WELDS` in `mesh/repair/fins.rs`), they leave cracks and the wider weld
/// joins the copies: closed, the volume right to 3e-13.
#[test]
fn a_fin_drop_takes_volume_from_the_mesh() {
    let failures = fork_failures("round18_fork", &["a03b7e97"]);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// From the round-18 fork run (b153683f): a cylinder (r 0.0625, along y) united with the 0.125
/// cube about it turned 1e-6°, then with a 0.125 × 1.25 × 0.125 bar through the cube. Step 1's
/// union, 90 triangles in 2 shells, had a closed shell of no volume (a flat one) from 70fbf14
/// on, where a vertex judged across a crossing line is on it within the line's own rounding.
/// Traced: the vertex (−0.5, −0.4999999998, −0.4375), on the bar's top and side, reads 1.5e-17
/// across the line where the bar's top crosses the cube's turned one (7.6e-10 off it in the
/// plane; the band 1.1e-16, eps × sine 3e-21): on it, one operand's cut there leaves a flap of
/// two slivers 1e-9 wide on the top face, hung on the surface by its diagonal. The flat fill
/// closed its rim by the other diagonal, so no fill triangle was a flap triangle's reverse, and
/// the flap with the fill laid on it was a flat shell, kept as the fill's. The fill now takes a
/// flap of several triangles away whole (`flap_patch` in `mesh/repair/cracks.rs`): closed, 94
/// triangles, the volume right.
#[test]
fn the_crossing_line_band_leaves_a_flat_shell() {
    let failures = fork_failures("round18_fork", &["b153683f"]);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

// Found by a 15-minute `booleans` run in round 20 with libFuzzer's fork mode (main a04b93c, seed
// 2001, `-fork=1 -ignore_crashes=1`, 106,438 executions in 903 s): 109 failing inputs, all but
// one passing with tiny rotations off, kept in `tests/fuzz_findings/booleans/round20_fork/`
// (named by the artifact's hash), not minimised. On main after this round's cluster merge and
// near polygons by planes, 12 of the 108 pass; of the 96 that fail, 44 are not closed, 28 have
// the mesh's volume off the solid's, 16 the solid's volume outside its bounds and 8 one needle
// or two. Traced (see the notes of issue 11): in those with the mesh's volume off the solid's,
// the solid's polygons do not close where near-coplanar faces meet (a piece of a face kept by
// one operand while its partner's is dropped), and the mesh is the right one; e.g. 22b67390,
// whose step 2 should be 0.21484375 exactly: the mesh has it, the solid's polygons keep a
// 1.5e-4 sliver of a face the union should have taken (it passes now: see `FORK_20_PASSING`).
// The one input failing with tiny rotations off too (11b5badf) is minimised below.

/// The inputs of the round-20 fork run that pass now: 12 on main at the run's landing, and 10
/// since a sliver thinner than the tolerance across a tree's face node also bounds the side it
/// lies on (`sliver_side` in `bsp/build/face.rs`), each a box or cylinder turned 1e-10° … 1e-5°
/// united with exact boxes on a shared face:
/// 1d7d9f8a (a slab turned 1e-10° ∪ cubes ∪ an OBJ bar; step 3 below its operand), 1f854764
/// (an OBJ slab turned 1e-5° ∪ a cube ∩ a cylinder turned 1e-10° ∪ cubes; step 3 the mesh's
/// volume 5.7e-4 off the solid's), 44bbfb06 (a cylinder turned 1e-10° ∪ copies unturned; step 1
/// 2.8e-3 off), 74027838 (a prism ∪ three 0.125 cubes at one place, one turned 1e-9°; step 2
/// open), 8116c238 (a slab turned 1e-10° ∪ cubes; step 1 1.1e-3 off), 822b0d3d (an OBJ box
/// turned 1e-6° ∪ bars, one turned 1e-10°; step 2 open), 9679585b (a slab turned 1e-5° ∪ a cube
/// less a cube turned 1e-10° ∪ bars; step 3 open), a30a743f (an OBJ box ∪ a box turned 1e-7°
/// ∪ boxes; step 3 3.8e-7 off), ce00c570 (an OBJ bar turned 1e-8° ∪ a cube ∪ boxes; step 2
/// 7.9e-5 off), e9c633a3 (an OBJ box ∪ a cube ∪ an OBJ box turned 1e-10° ∪ …; step 3 the
/// union below its operand).
///
/// 79dd0a25 (an OBJ cube ∪ a box turned 1e-4°, − a sphere, ∪ two boxes): step 1 closed, genus
/// 1, with two needles on a handle (the triangles around their corners a surface of Euler
/// characteristic −1, so every edge fails the link condition): a flat sliver 0.25 long whose
/// corners lie nearly on one line, no spike by its height, and a speck beside it, neither
/// flipped without folding nor widened within the bound. Stretched along an edge as the last
/// resort (`Work::stretch_any` in `mesh/needles/fix.rs`), each by 1.5·10⁻⁶ within its planes.
///
/// 7ee590be and c095e8fc pass since steep faces ending a near-coplanar wedge also bound the side
/// the wedge's face went to (`Wedge` in `bsp/build/face.rs`). 7ee590be: a 0.25 × 1 × 0.125 slab
/// turned 1e-10° ∪ 0.125 cubes ∪ a slab, then ∪ a 0.125 × 0.75 × 0.125 bar whose top lies in
/// a cube's (step 3: the solid 8.1e-4 below its mesh, which was right). Traced: the cube's top,
/// 5e-13 above the slab's top plane and within the tolerance of it, went in front of it by the
/// band of nearly parallel planes, while the cube's side faces ending there went behind it by
/// the tolerance; in front, the region below the cube's top was bounded along y by nothing, and
/// the bar's top 0.06 beyond the cube (coplanar with the cube's, sent behind it on the second
/// pass) was dropped as inside. c095e8fc: a cylinder ∪ a cube ∪ a cube turned 1e-6° ∪ a bar
/// turned 1e-10° ∪ a slab (step 3: the solid 8.1e-5 below its mesh).
///
/// 22b67390, 2a7dd67a and 97cf8f64 pass since a fragment routed along a face of the tree and
/// labelled by a ray from two tolerances off it counts a face crossing that one at a small
/// angle between the two points (`Surface::crossings_off` in `bsp/surface/ray/mod.rs`): the point off
/// the face lay beyond the other operand's nearly parallel face, 2.7e-13 away, and the
/// fragment, inside by the band that cut it on their crossing line, read outside, while that
/// face, outside the fragment's operand by the band, was dropped too (traced on round 18's
/// a406f929). 22b67390: an OBJ box ∪ a cube ∪ an OBJ box turned 1e-10°, less a cube (step 2:
/// the solid 1.3e-3 above its mesh, which was right: 0.21484375). 2a7dd67a: a cylinder ∪ a
/// cube turned 1e-9° ∪ a cube at the same place, ∩ that cube (step 2: 4.8e-6 below). 97cf8f64:
/// a box turned 1e-10° ∪ a cube ∪ a cylinder ∪ a bar ∪ a box (step 3: 1.4e-3 below).
///
/// edf27eb0 passes with round 17's 93aab2f0 (see [`FORK_PASSING`]).
///
/// 12758e1c (step 2: 2 shells, not closed) and 5ba8f6ed (step 1: 2 shells, not closed) pass
/// since a flat fin whose two sides cover one quad along different diagonals is dropped like a
/// reversed pair (`cancel_reversed_quads` in `mesh/repair/fins.rs`; not traced further: both
/// failed without it on the same tree).
///
/// 7f2fbc81 (step 1 a closed flat shell of two triangles) since the flat fill takes away an
/// ear of a face on a slit's rim rather than lay its reverse on it (`ears_on_rim` in
/// `mesh/repair/cracks.rs`; minimised as
/// `union_of_a_cube_a_slab_turned_1e_6_degrees_and_a_bar_leaves_no_flat_shell`). With it,
/// 12bcee43 (step 3, 3 shells) and 42b00a8c (step 2, 2 shells), both not closed, not traced.
/// The three also pass by the next change alone (`beside_the_line`, which removes the slit the
/// ear lay on); each fails only with both off, so `ears_on_rim` has no test of its own that fails
/// without it (it changes only the open 1a668028, now closed, and ed3471fb).
///
/// 25a6e85f (an OBJ box turned 1e-9° less a cuboid; step 0 the solid 1.83e-7 below its mesh,
/// which was right; minimised in `near_coplanar_corners.rs`) since a corner read on a crossing
/// line of faces at a hair only by the line's rounding is judged beside it when an edge of it
/// meets the line more than a weld away (`Polygon::beside_the_line` in `polygon/split.rs`):
/// the line passed the corner 1.56e-5 aside, one operand ended its cut at the corner, the other
/// at the meet beside it, a flat sliver between. With it, not traced one by one: 4dba1202
/// (step 1, 2.7e-7 off), 12bcee43, 42b00a8c, 60e1b472 and 7f2fbc81 (not closed), and 3ecaaeed,
/// 5927f563 and b07b43ca (the solid's volume outside its bounds; 3ecaaeed and 5927f563 united
/// a flat remnant of 7.1e-16 with a cube and lost 3.4e-6 of it).
///
/// 9ace493f (a 0.25 × 0.125 × 1.125 box less a 0.125 cube turned 1e-5° at its end, leaving a
/// notch open on the face x = −0.5625 over half its width; ∪ a bar far off; ∪ a 0.125 bar
/// filling the notch: step 3 the solid 1.07e-3 below its mesh, which was right) since a ray's
/// crossing test skips an edge running back along its neighbour (`turns_back` in
/// `bsp/surface/ray/mod.rs`): the box's face y = −0.4375, cut at two points 6.2e-12 apart on its
/// edge x = −0.5625, had a spike there, and a ray from 2 tolerances outside the box (the
/// filling bar's face piece over the notch, routed along the box's face) missed it, read one
/// crossing and labelled the piece inside. The bar's face over the notch (7.78e-3) was
/// dropped: the volume gap is that area times its lever (0.41) over 3.
///
/// 2d7b59dd, 6a886bb6, 75be2603 and 9d46e77d (step 0, 0, 0 and 2: closed, one tetrahedron of
/// volume 7.3e-17, 4.5e-19, 7.0e-16 and 1.3e-16 with a needle at its end): each an
/// intersection of an exact box with a box or cylinder turned 1e-5° whose face or edge lay on
/// the box's, a real wedge a hair deep. The needle pass deleted the tetrahedron and put it back
/// (the drop was all the mesh's volume); the mesh is now empty (minimised as
/// `intersection_of_a_box_and_a_cylinder_turned_1e_5_degrees_on_its_top_drops_its_tetrahedron`).
///
/// e5d963a7 (a 3-segment prism ∪ a 0.125 cube turned 1e-6° on its face x = −0.4375 ∪ a
/// 0.125 × 0.25 × 0.125 cuboid whose face x = −0.4375 is the prism's twin ∪ a slab: step 3 the
/// solid 3.7e-3 above its mesh, which was right) since a vertex on an edge whose plane is the
/// cutting plane's twin flipped to rounding is judged on that plane, not across the line where
/// its own plane crosses it (`flipped_twin` in `polygon/side.rs`): the cube's face, cut on the
/// prism's face in step 1 and by the cuboid's in step 2 on a line 2e-9 aside, kept the strip
/// between (6.1e-11: step 2 open in +x); the slab's union built its tree on the strip, whose
/// plane read outside across the prism, and kept 1.6e-2 of the slab's bottom inside it.
/// Minimised in `near_coplanar_corners.rs`.
///
/// 5919d466 (a cylinder ∪ a cuboid ∩ a cylinder ∪ a cuboid turned 1e-9° on the first's top,
/// less a slab: step 3 open, 4 boundary edges) since the repair's last pass orders sheets whose
/// angles about a crowded edge tie within the weld's noise to alternate (`tie_repair` in
/// `mesh/repair/pass.rs`; minimised as
/// `union_with_a_box_turned_1e_9_degrees_on_a_cylinder_s_top_pairs_the_touching_sheets`).
///
/// 3645ffb4 (step 1: closed, 1 needle): a collapse at a slit tip on a cube's edge left a fin
/// whose normals cancelled; its volume-keeping offset slid the cube's corner 0.34 out along the
/// edge, unseen by the fan's planes, and the grown box made a 4.0e-12 triangle a needle. The
/// offset now counts as a move at a slit's tip (minimised as
/// `union_with_a_slab_through_a_cube_less_a_cube_turned_1e_8_degrees_keeps_its_corner`).
///
/// 1886ef4e (a cylinder turned 1e-9° ∩ a 15×9 sphere turned 1e-9° ∩ the sphere turned 1e-9°
/// about another axis ∩ it unturned ∩ a box: step 2 open, 606 boundary edges) and 7acf667b (the
/// same with turns of 1e-9°, 1e-8° and 1e-9° about three axes: step 2 the solid's volume
/// 1.8e-8 above its operands') since the meet of three planes that all cross below
/// `NEAR_PARALLEL` is solved in double-double (`meet` in `polygon/planes.rs`): computed on one
/// of the lines where a facet's three nearly parallel planes cross (at sines near 1.5e-11), it
/// lay about 5e-6 beside another, and the cuts along them parted by up to 1e-6.
/// Minimised in `three_turned_spheres.rs`.
///
/// e3c98fcd (a 0.25 × 1 × 0.125 cuboid turned 1e-10° ∪ a cube turned freely ∪ a cuboid below
/// it ∪ a cube, less an OBJ 0.125 cube under the first: step 3 the solid 6.8e-6 below its
/// mesh, open by 4.9e-5) since a fragment routed along a face is judged against a nearly
/// parallel face through its point by its distance across their crossing line
/// (`Surface::crossings_off`): the cube's top, 2.5e-15 inside the turned cuboid's bottom at its
/// centroid beside the line, was labelled outside from two tolerances below (the solid now
/// 2.4e-15 from its mesh, closed). Named below as
/// `difference_under_a_face_turned_a_hair_keeps_the_cubes_top_beside_the_crossing_line`.
///
/// 0afdfd64 (step 1 a wedge shell of 3.5e-10 holding a needle) since a needle collapse whose
/// volume-keeping offset would move its vertex beyond the bound goes without it
/// (`needles/collapse.rs`): at the wedge's thin end the fan's two faces are nearly back to back,
/// and the offset along their nearly cancelling normal moved the vertex 1.96e-3 (the bound
/// 1.25e-6) to collapse an edge 2e-11 long. Named below as
/// `a_needle_at_a_wedges_thin_end_collapses_without_sliding_along_its_crease`.
///
/// 3c2ff807 (an OBJ 0.5 box whose top edge touches a 1.5 cube turned 1e-5° along its edge,
/// overlapping it by 9.2e-5, less a cube turned freely: step 0 closed with one needle) since
/// the needle pass judges needles by the shell's own diagonal, as the report does: the union's
/// shell (3.46 across) is larger than `NEEDLE_REGION_REACH` (16) times the region where the
/// operands met (the tolerance there, set by the coordinates' floor, makes it 0.085), so its
/// threshold was 1.86e-12 against the report's 1.2e-11, and a sliver of 7.7e-12 along the
/// cube's edge (1.5 long, 1e-11 high: a cut's vertex a hair from the edge) stayed. Its moves
/// are still bounded at the capped scale, and beyond it only thin needles are its to remove
/// (`Work::is_needle` in `mesh/needles/work.rs`). Step 0 alone is
/// `union_of_a_box_touching_a_cube_turned_1e_5_degrees_along_its_edge_leaves_no_needle`.
///
/// e11e6f68 (a box turned 1e-5° ∪ a 0.125 cube ∪ a bar beside it turned 1e-10° ∪ a cuboid ∪ a
/// slab through the cube turned 1e-8°: step 3 the solid 1.7e-5 above its mesh, open by 5.9e-4)
/// since a face node passes its corners down to the side a nearly parallel polygon went to, and
/// that polygon's node sends the steep faces ending at them to its other side too (`Corners` in
/// `bsp/build/face.rs`): the bar's bottom, 1.4e-12 rad from the cube's and behind it in the
/// tree, read the wedge between the two planes as outside across the cube, and the slab's
/// bottom, crossing the two planes on lines 3.7e-3 apart, kept the strip between over the cube
/// beside the cube's own bottom; minimised as
/// `near_coplanar_corners::a_wedge_under_a_face_turned_a_hair_stays_inside_the_face_beside_it`.
/// With that alone c095e8fc failed (step 3: the solid 2.4e-4 below its mesh): the cube's side
/// faces, following into the region above the bar's top, made a subtree there ending in an
/// unbuilt cell, and a piece of the slab's top routed along the cube's top reached it uncut by
/// the bar's side face (behind the bar's top); its centroid lay on that face, the short segment
/// of `Surface::crossings_off` grazed its edge, and the ray from beside it read inside. A routed
/// fragment whose segment grazes is now labelled from a point halfway to a corner (`label_routed`
/// in `bsp/clip.rs`).
///
/// Also passing since the changes named at [`FORK_PASSING`]: the inputs not named above.
const FORK_20_PASSING: [&str; 106] = [
    "04880fb6", "060752d1", "0afdfd64", "0bebd350", "1194b103", "12758e1c", "12bcee43", "1886ef4e",
    "1d6b6b28", "1d7d9f8a", "1f854764", "20254c75", "22568913", "22b67390", "24057533", "25a6e85f",
    "2a7dd67a", "2d7b59dd", "2f1db746", "3645ffb4", "394fbf5b", "3c2ff807", "3ecaaeed", "42b00a8c",
    "43f8dc80", "44bbfb06", "45e7cb01", "4b6fae9d", "4dba1202", "50f56fc8", "52a63048", "53fd6805",
    "54ad2229", "5919d466", "5927f563", "5ba8f6ed", "5be20e4a", "5f7ef5a2", "60e1b472", "6a886bb6",
    "6c1d9139", "6c2460ab", "74027838", "75be2603", "778ac30a", "78085500", "79dd0a25", "7acf667b",
    "7d6886ee", "7eb5e225", "7ee590be", "7f2fbc81", "7f88a284", "8116c238", "822b0d3d", "83b87dcb",
    "84cb559e", "84ce80c0", "87f26b5a", "8936dbd6", "8dea14d6", "91c935ab", "94d83441", "9530713d",
    "9679585b", "97cf8f64", "98725c3d", "9ace493f", "9d46e77d", "a30a743f", "a3a7185f", "aaf8bd05",
    "ad644dcd", "afdfb2bf", "b07b43ca", "b770c958", "c095e8fc", "c287ef50", "c724056e", "c9724cd5",
    "c9f5e09e", "c9f9a708", "ce00c570", "d116749a", "d3147b45", "d642c6e2", "d6f045bf", "d8a85c01",
    "dcbd5cd9", "de6a214f", "df3549fa", "e02e0760", "e0c0778c", "e11e6f68", "e3c98fcd", "e5d963a7",
    "e9c633a3", "ea147c0f", "eb2498a7", "ebb7181c", "edf27eb0", "ef943716", "f385f178", "fa3003dd",
    "fc4b5873", "fe9275bb",
];

/// The inputs of the round-20 fork run that pass now ([`FORK_20_PASSING`]).
#[test]
fn the_round_20_fork_run_inputs_that_pass() {
    let failures = fork_failures("round20_fork", &FORK_20_PASSING);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Every other input of the round-20 fork run, replayed; the failures listed.
///
/// ed3471fb (a cylinder ∪ a 15×9 sphere turned 1e-9°, ∩ the sphere turned 1e-9° about two other
/// axes) closes since 1886ef4e does (see [`FORK_20_PASSING`]; before, step 2 open, 85 boundary
/// edges), its mesh's volume the sphere's, but the solid's polygons are 9.5e-4 short of it: a
/// hole of 4.3e-3 in one facet of the third sphere. Traced: step 1 keeps there a triangle of
/// the first sphere's facet (8.5e-8) among the second's pieces, and in its tree the node of
/// that triangle's plane, behind the second's, reads the layer between the two planes
/// (crossing at about 1e-11 rad) outside across the whole facet; the third sphere's facet,
/// lying in that layer, is dropped with the second's pieces outside it. Replayed as it runs (ignored) as
/// `three_turned_spheres::a_cylinder_united_with_a_sphere_then_cut_by_two_turned_copies_keeps_every_facet`.
/// 0a15665e (an OBJ bar turned 1e-2° ∪ an OBJ box turned 1e-3° ∪ a cuboid ∪ a 0.125 cube at
/// their centre, less a slab whose faces are the cube's top and bottom) is open at step 3
/// because of two lone triangles of about 2e-17, one at each of two opposite corners of the
/// cube's top and bottom (z = −0.4375 and −0.5625): the cuboid is not needed. Traced: the
/// union keeps a triangle of the box's turned bottom standing 1.2e-13 out below the cube's
/// (within the tolerance, 3.1e-13, but beyond the band of the nearly parallel planes, so the
/// difference keeps it outside the slab), while the box's −x face is cut at the cube's bottom
/// by the tolerance; in the union's tree, the node of the cube's bottom behind the box's
/// bottom reads the layer between them outside, and the slab's face over the triangle is
/// dropped there: no cap. Minimised (ignored) as
/// `near_coplanar_corners::a_slab_through_a_box_turned_a_hair_caps_the_wedge_under_the_cube`.
#[test]
#[ignore = "open: near-coplanar — 2 inputs of round 20's fork run fail with tiny rotations on (1 not closed, 1 mesh volume off the solid's), both pass with them off"]
fn the_round_20_fork_run_near_coplanar_inputs() {
    assert_fork_run_passes("round20_fork", 108, &FORK_20_PASSING);
}

/// From the round-20 fork run (e3c98fcd): a 0.25 × 1 × 0.125 cuboid turned 1e-10° (its bottom
/// 1.4e-12 rad off y = −0.4375, crossing it on the diagonal x = z) ∪ a 0.125 cube turned
/// freely ∪ a cuboid below ∪ a cube, less an OBJ 0.125 cube whose top is y = −0.4375: step 3
/// dropped a strip 0.01 wide of the cube's top beside the crossing line, where the turned
/// bottom, inside the cube by the band, was dropped too (see [`FORK_20_PASSING`]).
#[test]
fn difference_under_a_face_turned_a_hair_keeps_the_cubes_top_beside_the_crossing_line() {
    replay_file("round20_fork/e3c98fcd");
}

/// From the round-20 fork run (3c2ff807), its step 0 alone (36 bytes): an OBJ 0.5 box at
/// (−0.99991, −1, −1) united with a 1.5 cube turned 1e-5° at the origin, the box's top edge
/// along the cube's bottom edge. Closed with one needle (a sliver 1.5 long, 1e-11 high, on a
/// shell 3.46 across): the needle pass judged it at 16 times the region where the operands met
/// (see [`FORK_20_PASSING`]).
#[test]
fn union_of_a_box_touching_a_cube_turned_1e_5_degrees_along_its_edge_leaves_no_needle() {
    replay(&[
        0x01, 0x03, 0x03, 0x03, 0x00, 0x00, 0x08, 0x00, 0x40, 0x03, 0x03, 0x03, 0x03, 0x03, 0x00,
        0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xd7, 0xd7, 0xd7, 0xd7, 0xd7, 0x00, 0x00, 0x00, 0x09,
        0x2b, 0x28, 0x28, 0x28, 0x28, 0x28,
    ]);
}

/// From the round-20 fork run (0afdfd64): step 1 leaves a wedge shell of 3.5e-10 whose thin end
/// holds a spike with a 2e-11 edge; collapsing it with the volume-keeping offset slid the vertex
/// 1.96e-3 along the wedge's crease, so the needle stayed (see [`FORK_20_PASSING`]).
#[test]
fn a_needle_at_a_wedges_thin_end_collapses_without_sliding_along_its_crease() {
    replay_file("round20_fork/0afdfd64");
}

/// From the fork run (crash-33894a02…, 84 bytes): a unit cube turned 1e-7° less a box turned
/// 1e-9°, intersected with another box turned 1e-9° that nearly holds the same cut: step 1's
/// solid had volume 1.5e-12 and no triangles (a flat closed sheet). Intersected with a
/// 0.625 × 0.625 × 0.125 slab turned 1e-9° at step 2 it grew to 7.9e-6, an intersection larger
/// than an operand: the slab's face lies in the sheet, and the coplanar rule kept the sheet's
/// side facing as that face does and dropped the other. Step 1 is now the empty solid
/// (`solid/flat.rs`; constructed in `flat_sheets.rs`).
#[test]
fn intersection_with_a_flat_remnant_does_not_grow() {
    replay_fork("33894a02");
}

/// From the fork run (1886ef4e): three copies of a 15×9 sphere, two turned 1e-9° about
/// different axes, intersected (with a cylinder first, a box last): step 2 was open, 606
/// boundary edges (see [`FORK_20_PASSING`]).
#[test]
fn intersection_of_three_spheres_turned_a_hair_about_different_axes_closes() {
    replay_file("round20_fork/1886ef4e");
}

/// From the fork run (7acf667b): as 1886ef4e with turns of 1e-9°, 1e-8° and 1e-9° about three
/// axes; step 2's solid was 1.8e-8 above its operands' volume (see [`FORK_20_PASSING`]).
#[test]
fn intersection_of_three_spheres_turned_a_hair_stays_within_its_operands() {
    replay_file("round20_fork/7acf667b");
}

/// From the fork run (crash-9f0af865…, 85 bytes): an OBJ slab 0.625 × 0.125 × 1.125 turned 1e-8°
/// united with a 0.125 cube at the same centre, then with a 0.125 × 0.125 × 0.875 bar there
/// unturned: step 1's union had volume 0.0878905789, 4.6e-8 below the first operand's
/// 0.0878906250. Traced: the slab's face y = −0.5625 and the cube's cross at 1.4e-10 rad, and
/// the cube stands out of the slab by a wedge up to 1.5e-13 thick, whose end on the cube's
/// bottom z = −0.5625 is a triangle of 1e-16 within the tolerance of both faces. The slab's
/// tree kept it at the node of the slab's face (and then of the cube's) as coplanar, so the
/// subtree behind the cube's face had no plane where the wedge ends and read inside below
/// z = −0.4375. The bar's face y = −0.5625, outside the slab by 1e-13 there, was dropped over a
/// triangle of 1.1e-6 while the bar's tree dropped the slab's piece on it (inside by 1.5e-13):
/// a hole. The sliver now also goes to the side it lies on (`sliver_side` in
/// `bsp/build/face.rs`): closed, the volume 0.0878906250024.
#[test]
fn union_with_a_bar_below_its_larger_operand() {
    replay_fork("9f0af865");
}

/// From the fork run (crash-c88c23a3…, 80 bytes): a unit cube turned 1e-4° united with a box
/// turned 1e-7° (2.7123164321 together), then with a cylinder of radius 0.5625 unturned at
/// (−0.5, −0.5, −0.25): step 1's union has volume 2.7123103578, 6.1e-6 below the first operand.
#[test]
fn union_with_a_cylinder_below_its_larger_operand() {
    replay_fork("c88c23a3");
}
