//! Every input the `booleans` fuzz target in `fuzz/` found failing whose minimised bytes are
//! short enough to write here, replayed as a named test (`fuzz/fuzz_targets/program.rs` decodes
//! and checks boolean programs). Named findings kept as files under
//! `tests/fuzz_findings/booleans/` are in `fuzz_findings_files.rs`; the fork runs' batches (and
//! the lists of their inputs that pass) in `fuzz_forks.rs`; the `scenes` target's findings in
//! `fuzz_findings_scenes.rs`.

#[path = "common/fuzz_replay.rs"]
mod fuzz_replay;

use fuzz_replay::{replay, replay_with};

/// Found by the one-minute `booleans` run with libFuzzer seed 1 and tiny rotations off
/// (`BSPCSG_FUZZ_NO_TINY=1 FUZZ_SEED=1`), at execution 4,357: step 3 leaves one non-manifold
/// edge and two non-manifold vertices (volume 0.711): a face pairing around a crowded edge that
/// left both sheets on one pair of vertices (see `mesh/repair/shells.rs`).
#[test]
fn non_manifold_edge_found_by_the_seed_1_minute() {
    replay_with(
        &[
            0x08, 0x06, 0x09, 0x00, 0x18, 0x79, 0x30, 0x75, 0x02, 0x00, 0x02, 0x03, 0x00, 0x0c,
            0x02, 0x00, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x16, 0x00,
            0x00, 0x2e, 0x00, 0x04, 0x00, 0x08, 0x08, 0x4e, 0x01, 0xe8, 0x80, 0x00, 0x00, 0x00,
            0x18, 0x79, 0x30, 0x75, 0x02, 0x00, 0x02, 0x03, 0x00, 0x0c, 0x02, 0x00, 0x00, 0x00,
            0x00, 0x01, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x16, 0x00, 0x00, 0x00, 0x03, 0x06,
            0x08, 0x06, 0x04, 0x00, 0x08, 0x08, 0x08,
        ],
        false,
    );
}

/// A coarse sphere (3 segments) turned freely, unioned with a box sharing its bottom plane
/// (z = −0.5), then with a box turned by 1e-9° sharing that plane too: the faces a hair off
/// coplanar left 13 (later 7) boundary edges at step 1, the two operands cutting their faces on
/// lines up to a tolerance over the angle apart. Closed since faces crossing below 1e-7 rad are
/// cut on one shared crossing line (`Polygon::split`).
#[test]
fn union_with_a_box_turned_1e_9_degrees_on_a_shared_plane() {
    replay(&[
        0x02, 0x08, 0x14, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x08, 0x08, 0x0c, 0x01, 0x00,
        0xb0, 0x02, 0x00, 0x03, 0x00, 0x41, 0x01, 0x30, 0x75, 0x30, 0x75, 0x30, 0x75, 0x01, 0x03,
        0x06, 0x08, 0x06, 0x09, 0x50, 0xc3, 0xe8, 0x03, 0x20, 0x4e, 0x00, 0x00, 0x00, 0x02, 0x20,
        0x4e, 0x01, 0xe8, 0x88, 0x18, 0x79, 0x30, 0x75, 0x02, 0x00, 0x02, 0x0c, 0x02, 0x00, 0x00,
        0x00, 0x00, 0x00, 0x00, 0x00, 0x04, 0x00, 0x08, 0x08, 0x08,
    ]);
}

/// Found by a 10-minute run of the `booleans` target (artifact crash-10f977ea…); fails the same
/// way without tiny rotations: a needle was left. It was a needle by its shell's diagonal, which the report uses, but not
/// by the smaller region where the operands met, which alone set `to_mesh`'s threshold; now
/// the shell's own size counts up to 16 times that region.
#[test]
fn a_needle_that_no_flip_or_collapse_removes() {
    replay(&[
        0x01, 0x00, 0x00, 0x00, 0x00, 0x2d, 0x00, 0xfd, 0x00, 0x00, 0x00, 0xfe, 0xec, 0xff, 0x00,
        0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xec, 0xff, 0x00, 0x00, 0x4a, 0xe2, 0x00,
        0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x08, 0x08, 0x08, 0x00, 0x01, 0x03, 0x03, 0x03, 0x00,
        0x00, 0x16, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xa6, 0xfe, 0xff, 0xff, 0xff, 0x26,
        0xa6, 0xa6, 0x01, 0x00, 0x00, 0x00, 0x55, 0x55, 0x55, 0x00, 0x60, 0x00, 0x00, 0x2e, 0x00,
        0x32, 0x0b, 0x08,
    ]);
}

/// Found by a 10-minute run of the `booleans` target (artifact crash-aa790cba…); fails the same
/// way without tiny rotations: a non-manifold edge, split since `to_mesh` pairs the faces
/// around a crowded edge so that its vertices part.
#[test]
fn a_non_manifold_edge_without_tiny_turns() {
    replay(&[
        0xc0, 0xd3, 0x51, 0x68, 0x6f, 0x6e, 0x45, 0x77, 0xb1, 0x5c, 0xa1, 0xa1, 0x63, 0x6f, 0x63,
        0x31, 0x44, 0x7a, 0x43, 0xc6, 0x31, 0x00, 0x07, 0x53, 0x53, 0x53, 0x53, 0x53, 0x01, 0x00,
        0x00, 0x00, 0x00, 0x00, 0x00, 0x30, 0x53, 0x53, 0x53, 0x53, 0x53, 0x07, 0xff, 0x7f, 0x00,
        0x00, 0x9a, 0x00, 0x08, 0x08, 0x08, 0xff, 0x17, 0x00, 0x01, 0x03, 0x44, 0xfe, 0xb3, 0x14,
        0x20, 0x8e, 0x01, 0x03, 0x00, 0x03,
    ]);
}

/// Found by a 10-minute run of the `booleans` target (artifact crash-696daaaf…); fails the same
/// way without tiny rotations: a closed shell of non-positive volume. Closed by the BSP's cell
/// planes leaving a polygon whole on each side (no cascade of slivers thinner than the weld).
#[test]
fn a_flat_shell_without_tiny_turns() {
    replay(&[
        0x44, 0xfe, 0xb3, 0x14, 0x20, 0x8e, 0x00, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x15,
        0x00, 0xcf, 0xe8, 0x61, 0x0c, 0x88, 0x79, 0x48, 0x18, 0x3b, 0xe4, 0x48, 0x18, 0x3b, 0xe4,
        0x34, 0xbc, 0x27, 0x65, 0x66, 0xf3, 0x83, 0x5b, 0x05, 0xf1, 0xb1, 0x2c, 0x12, 0x8b, 0x73,
        0x5b, 0xd2, 0x2c, 0xbf, 0x42, 0x00, 0x00, 0x00, 0x24, 0xc0, 0xd3, 0xc3, 0xfc, 0xa1, 0xe7,
        0x26, 0x10, 0xa4, 0xc7, 0x2c, 0x9e, 0xa4, 0x86, 0x08, 0xb2, 0x2a,
    ]);
}

/// Found by a 10-minute run of the `booleans` target with tiny rotations off (artifact
/// crash-82421d33…): step 0 leaves one needle (a spike 1.5e-8 long on a shell 3.5 times the
/// region the operands met in), fixed as `a_needle_that_no_flip_or_collapse_removes`.
#[test]
fn a_needle_left_at_the_first_step() {
    replay_with(
        &[
            0x02, 0x00, 0x2f, 0x08, 0x0c, 0x01, 0xae, 0x00, 0x02, 0x80, 0x01, 0x14, 0x03, 0x00,
            0x46, 0x01, 0x00, 0x30, 0x75, 0x30, 0x75, 0x30, 0x75, 0x01, 0x08, 0x00, 0x00, 0x00,
            0x01, 0x00, 0x43, 0x00, 0x31, 0x00, 0x4a, 0x4a, 0x4a, 0x4a, 0x4a, 0x4a, 0x4a, 0x4a,
            0x02, 0x08, 0x08, 0x0e, 0x01, 0x08, 0x00, 0x0d, 0x02, 0x00, 0x03, 0x00, 0x4a, 0x02,
            0x08, 0x08, 0x0e, 0x01, 0x08, 0x00, 0x0d, 0x02, 0x00, 0x03, 0x00, 0x00, 0x27, 0x30,
            0x75, 0x4a, 0xe6, 0xe6, 0xe6, 0xe6, 0xe6, 0xe6, 0xff,
        ],
        false,
    );
}

/// From the same run (artifact crash-bc7e2acc…): step 2 leaves three needles, fixed as
/// `a_needle_that_no_flip_or_collapse_removes`.
#[test]
fn three_needles_left_at_the_third_step() {
    replay_with(
        &[
            0x02, 0x00, 0x2f, 0x08, 0x0c, 0x01, 0xae, 0x00, 0x00, 0x07, 0x02, 0x80, 0x03, 0x00,
            0x46, 0x01, 0x00, 0x30, 0x75, 0x30, 0x75, 0x00, 0x08, 0x01, 0x00, 0x30, 0x00, 0x75,
            0x00, 0x00, 0x00, 0x07, 0x02, 0x80, 0x03, 0x00, 0x46, 0x01, 0x00, 0x30, 0x75, 0x30,
            0x75, 0x30, 0x75, 0x01, 0x43, 0x00, 0x30, 0x00, 0x4a, 0x4a, 0x40, 0x3a, 0x00, 0x00,
            0x00, 0x4a, 0x03, 0x00, 0x00, 0x27, 0x30, 0x75, 0x4a,
        ],
        false,
    );
}

/// From the same run (artifact crash-9e1d85b3…): at step 2 the mesh's volume is 6.8e-9 below
/// the solid's (1.33159317 against 1.33159318), beyond the check's slack of 3.4e-9. The solid
/// and its plain fan mesh agree; the needle pass takes the difference. The intersection leaves
/// a face 5·10⁻⁶ across where a sphere grazes a box's corner (−0.5, −1.25, −0.5), fanned into
/// specks; eleven collapses remove them, each moving a corner of the large facets around by
/// about 10⁻⁶ and each cutting volume off (4·10⁻¹⁰ to 2·10⁻⁹, all of one sign, so no point on
/// the collapsed edge would balance them). A collapse now keeps the volume: the merged vertex
/// moves off the kept end along the fan's normal by what puts the volume back (at most 6·10⁻⁸
/// here; `mesh/needles.rs`).
#[test]
fn mesh_volume_off_the_solid_at_the_third_step() {
    replay_with(
        &[
            0x31, 0x77, 0x77, 0x77, 0x77, 0x80, 0x80, 0x01, 0x03, 0x25, 0x00, 0x02, 0x04, 0x00,
            0x00, 0x00, 0x00, 0x77, 0x00, 0x00, 0x00, 0x00, 0x1e, 0x08, 0x08, 0x08, 0x00, 0x34,
            0x77, 0x77, 0x77, 0x38, 0x0c, 0x01, 0x00, 0x4d, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
            0x00, 0x80, 0x80, 0x80, 0x80, 0xff, 0xc9, 0x80, 0x02, 0x04, 0x00, 0x00, 0x00, 0x00,
            0x77, 0x2b, 0x02, 0x77, 0x24, 0x8c, 0xf9, 0x0e,
        ],
        false,
    );
}

/// Found by the 10-minute `booleans` run with tiny rotations on (coplanar5's artifacts; 22 of its
/// 139 were this kind), minimised to 17 bytes: a box less a box turned by a tiny angle leaves
/// slivers about the weld thick, which the weld flattened into closed shells of no volume
/// ("closed shells of non-positive volume"). The flat shell was one the flat fill of
/// `mesh/repair/cracks.rs` closed over a slit (laying a sheet on the reverse of a one-sided
/// flap), which `mesh/repair/thin.rs` keeps. Fixed by filling before any wider weld and taking
/// such a flap away instead of covering it.
#[test]
fn flat_shells_of_a_box_less_a_box_turned_a_hair() {
    replay(&[
        0x00, 0x00, 0x00, 0xff, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x13, 0x00, 0x00, 0xe1,
        0x00, 0x00,
    ]);
}

/// The same run, minimised to 29 bytes: flat shells, and needles on them. The flat shells are
/// gone (`to_mesh` drops closed shells thinner than the weld, `mesh/repair/thin.rs`), but with
/// the indexed boolean output 4 needles were left on the closed result (volume 0.406) at step 0:
/// two specks 2e-10 across, each between its edge's flat sliver (0.43 long) and a vertex where
/// every single-edge collapse failed the link condition or left the sliver flat. Removed since a
/// speck's three corners may merge into one vertex (`mesh/needles/merge.rs`).
#[test]
fn flat_shells_holding_needles() {
    replay(&[
        0x13, 0x13, 0xe1, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
        0x00, 0x00, 0xff, 0xdb, 0xf9, 0x00, 0x11, 0x0a, 0x0e, 0x01, 0x76, 0x00, 0x00, 0x4f,
    ]);
}

/// The same run (artifact crash-de16203d…), minimised to 37 bytes: a box less a box turned by a
/// tiny angle, then another step, left 2 shells with boundary edges at step 1 (volume
/// 9.8e-4): the two operands cut their nearly parallel facets on lines a rounding error over
/// the angle apart. Closed since a face within the tolerance of a nearly parallel plane is
/// coplanar only within the band by the angle (`Polygon::split`) and edges whose neighbour is
/// away from the other operand know its plane, so their cuts on the crossing line are `meet`s
/// on the same line as the other operand's (`attach_edge_planes_among`).
#[test]
fn boundary_edges_of_boxes_turned_a_hair() {
    replay(&[
        0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x46, 0x13, 0x00, 0x00, 0xe1,
        0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xff,
        0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xee,
    ]);
}

/// The same run (artifact crash-1dc6a031…), minimised to 17 bytes: at step 0 a closed 2-manifold
/// of 12 triangles and volume 7.9e-10 holds a needle: the wedge's end face, 3.9e-10 × 4.4e-5,
/// where the turned cap passes 3.9e-10 from the cube's corner. No flip applies, and collapsing
/// its short edge folds the wedge's tip (a tetrahedron 4.4e-5 long) into a sheet; fixed by
/// stretching that edge by about its length instead (`mesh/needles.rs`).
#[test]
fn needle_on_a_sliver_of_boxes_turned_a_hair() {
    replay(&[
        0x03, 0x0e, 0x00, 0x00, 0x00, 0x00, 0x22, 0x00, 0x00, 0x11, 0x22, 0x22, 0x00, 0x22, 0x22,
        0x22, 0x22,
    ]);
}

/// The same run (artifact crash-8c03190e…), minimised to 21 bytes: at step 0 the mesh's volume
/// was 0.035156250 where the solid's is 0.035481771 (0.9 % less), closed. The first repair pass
/// leaves cracks and only a wide weld closed them, sweeping more volume than the first weld
/// explains: that pass is no longer taken, and the result is left open (3 shells, boundary
/// edges), so it was refused rather than silently 0.9 % off. The solid's own volume was wrong
/// too: a 0.125 cube turned 1e-10° inside a 0.125 × 0.25 × 1.125 box sharing its x faces, the
/// union is the box (0.03515625). Closed and exact since a face within the tolerance of a
/// nearly parallel plane is coplanar only within the band by the angle (`Polygon::split`).
#[test]
fn mesh_volume_below_the_solids_after_a_tiny_turn() {
    replay(&[
        0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x37, 0x00, 0x00, 0x00,
        0x00, 0x00, 0x00, 0x00, 0x91, 0xa4,
    ]);
}

/// Found by fuzz7's 10-minute `booleans` run with tiny rotations off (`BSPCSG_FUZZ_NO_TINY=1`,
/// libFuzzer seed 7, artifact crash-a61c9b87…), minimised to 37 bytes: an OBJ box 1.125 on a
/// side less a slab 1.125 × 1.125 × 0.125 at the same place, both turned 0.044° (the free turn's
/// smallest steps) about axes 1.6e-3 apart, so their side faces are about 1.3e-6 rad off
/// coplanar. Step 0 left a flat shell (2 shells, one of no volume). With the two axes equal
/// (faces exactly coplanar) it passes: the near-coplanar kind of the tiny-rotation findings,
/// reached through the free turn. Fixed by the shared near-coplanar vertices
/// (`polygon/shared.rs`).
#[test]
fn flat_shell_of_boxes_turned_alike_about_close_axes() {
    replay_with(
        &[
            0x01, 0x08, 0x08, 0x08, 0x00, 0x00, 0x00, 0x40, 0x00, 0x00, 0x08, 0x0b, 0x08, 0x00,
            0x00, 0x00, 0x08, 0x0b, 0x08, 0x00, 0x08, 0x08, 0x00, 0x00, 0x3d, 0x00, 0x00, 0x00,
            0x00, 0x08, 0x0b, 0x08, 0x00, 0x00, 0x00, 0x08, 0x0b,
        ],
        false,
    );
}

/// The same run (seed 8, artifact crash-0cfdb580…), minimised to 70 bytes: a slab less a bar,
/// both turned 0.044° about axes 3e-2 apart (faces about 2e-5 rad off coplanar), then a small
/// cube united and a cylinder taken away: step 2 is a closed 2-manifold of genus 2 holding one
/// needle. With the two axes equal it passes: near-coplanar kind, as above. The needle (a spike
/// 2.2e-4 long, 2.5e-9 thick, its short edge 4.2e-6) had no flip (the new edge existed) and
/// its collapses moved the surface 6.7e-8, past twice its thickness: now taken within the
/// needle pass's bound when nothing applies within the thickness (`mesh/needles/fix.rs`).
#[test]
fn needle_after_boxes_turned_alike_about_close_axes() {
    replay_with(
        &[
            0x00, 0x08, 0x08, 0x00, 0x00, 0x00, 0x07, 0x00, 0x00, 0x00, 0x08, 0x0b, 0x08, 0x00,
            0x00, 0x00, 0x08, 0x0b, 0x08, 0x00, 0x08, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
            0x00, 0x08, 0x0b, 0x08, 0x00, 0x00, 0x00, 0x08, 0x0b, 0x00, 0x00, 0x00, 0x00, 0x00,
            0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x23, 0x23,
            0x23, 0x23, 0x00, 0x25, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x6f, 0x00,
        ],
        false,
    );
}

/// The same run (seed 9, artifact crash-28a239a1…), minimised to 37 bytes: a 3-sided prism less
/// a bar at the same place, both turned 0.044° about axes 1.1e-3 apart: a needle at step 0. Passes
/// with both free turns made 0: near-coplanar kind. The needle was the base, 2e-8 across, of a
/// tetrahedral shell 0.06 long (volume ~3.5e-18): no flip, collapse or merge applies to a
/// tetrahedron; such a shell is now deleted (`Work::drop_tetrahedron`, `mesh/needles`).
#[test]
fn needle_of_a_prism_less_a_bar_turned_alike() {
    replay_with(
        &[
            0xff, 0x08, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x08, 0x0b, 0x08, 0x00,
            0x00, 0x00, 0x08, 0x0b, 0x08, 0x00, 0x08, 0x00, 0x00, 0x00, 0x3d, 0x00, 0x00, 0x00,
            0x00, 0x08, 0x0b, 0x08, 0x00, 0x00, 0x00, 0x08, 0x0b,
        ],
        false,
    );
}

/// The same run (seed 10, artifact crash-99b4592a…), minimised to 74 bytes: a box united with a
/// slab, both turned 0.044° about axes 1.2e-3 apart, then three small parts united: at step 3
/// the mesh volume was 1.7e-9 below the solid's. Passes with the free turns made 0: near-coplanar,
/// fixed by the shared near-coplanar vertices (`polygon/shared.rs`).
#[test]
fn mesh_volume_off_after_boxes_turned_alike_about_close_axes() {
    replay_with(
        &[
            0x00, 0x08, 0x08, 0x8c, 0x00, 0x00, 0x00, 0x20, 0x00, 0x00, 0x08, 0x0b, 0x08, 0x00,
            0x00, 0x00, 0x08, 0x0b, 0x00, 0x00, 0x08, 0x08, 0xff, 0x00, 0x3d, 0x00, 0x00, 0x00,
            0x00, 0x08, 0x0b, 0x08, 0x00, 0x00, 0x00, 0x08, 0x0b, 0x00, 0x00, 0x00, 0x00, 0x00,
            0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x23, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
            0x00, 0x23, 0x23, 0x00, 0x00, 0x6f, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
            0x6f, 0x00, 0x6f, 0x00,
        ],
        false,
    );
}

/// The same run (seed 11, artifact crash-9658ce8b…), minimised to 41 bytes: a bar 1 long less
/// itself turned 0.13° about an axis 1.5e-5 rad off its length (its end faces end up 5e-8 rad
/// off coplanar with the unturned bar's): a needle at step 1. Passes with the turn made 0:
/// near-coplanar kind. The needle was a flat sliver 0.125 long, 5e-17 thick, whose flip made an
/// edge that existed and whose collapses failed the link condition or folded a face: widened
/// to the threshold in its fan's plane (`plan_widen`, `mesh/needles/stretch.rs`).
#[test]
fn needle_of_a_bar_less_itself_turned_about_its_length() {
    replay_with(
        &[
            0x00, 0x07, 0x00, 0x00, 0x00, 0x00, 0x00, 0xff, 0x7f, 0xff, 0x7f, 0x9b, 0x18, 0x00,
            0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
            0x00, 0x00, 0x00, 0xff, 0x00, 0xff, 0x00, 0x00, 0x00, 0x00, 0xb3, 0x00, 0x07,
        ],
        false,
    );
}

/// The same run (seed 13, artifact crash-44a374a5…), minimised to 37 bytes: a slab less a
/// 3-sided prism of the same height, both turned 0.044° about axes 1.1e-3 apart: a closed
/// genus-2 result holding a needle at step 0. Passes with the free turns made 0: near-coplanar.
/// The needle, a flat sliver 0.0625 long and 5e-13 thick, sat where both diagonals of the quad
/// around its apex already existed: nothing but widening it (`plan_widen`) keeps the topology.
#[test]
fn needle_of_a_slab_less_a_prism_turned_alike() {
    replay_with(
        &[
            0x00, 0x08, 0x08, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x08, 0x0b, 0x08, 0x00,
            0x00, 0x00, 0x08, 0x0b, 0x08, 0x27, 0x08, 0x08, 0x00, 0x00, 0x3d, 0x00, 0x00, 0x00,
            0x00, 0x08, 0x0b, 0x08, 0x00, 0x00, 0x00, 0x08, 0x0b,
        ],
        false,
    );
}

/// The same run (seed 14, artifact crash-832fe95b…), minimised to 99 bytes: boxes united, one a
/// cube 0.125 turned 0.049° inside a slab of the same width, so its faces stand 8.6e-4 rad off
/// the slab's: a needle at step 4. Passes with the turn made 0: near-coplanar kind. The last
/// needle (3.2e-8 × 6.2e-5) collapses within the needle pass's bound (2.6e-6 against 5.1e-6),
/// not within twice its thickness: taken since `mesh/needles/fix.rs` falls back to the bound.
#[test]
fn needle_of_a_cube_turned_a_little_in_a_slab() {
    replay_with(
        &[
            0x00, 0x08, 0x08, 0x08, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xff, 0x00,
            0x00, 0x00, 0x5e, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
            0x00, 0x00, 0x00, 0x0b, 0x00, 0x00, 0x07, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
            0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
            0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
            0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x22,
            0x00, 0x00, 0x00, 0x08, 0x09, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x08,
            0x0b,
        ],
        false,
    );
}

/// The same run (seed 12, artifact crash-ee5b3302…), minimised to 77 bytes: a union of boxes
/// 0.125 wide about one centre — a cube, a bar 0.5 long turned 11.25° about a near-diagonal
/// axis, a bar 1 long along y, a bar 1.125 long along z — leaves one needle at step 3 on a closed
/// genus-0 result. Not the near-coplanar kind (the turned bar's faces are 9° or more off every
/// other face): the turned bar's face passes 1.8e-6 from the cube's corner, leaving a speck
/// 1.2·10⁻⁶ of its shell's diagonal on a side (area 0.74·10⁻¹² d²) that every flip and collapse
/// removed by moving the surface 1.06·10⁻⁶ d, just past the needle pass's old bound of 10⁻⁶ d.
/// Removed since the bound covers a speck's shortest edge (`SPECK_MOVE`, `mesh/needles.rs`).
#[test]
fn needle_of_bars_united_about_one_centre_one_turned() {
    replay_with(
        &[
            0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xff, 0x00,
            0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
            0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x03, 0x00,
            0x00, 0x00, 0x00, 0x00, 0x08, 0x00, 0x1a, 0x00, 0x08, 0x00, 0x00, 0x00, 0x00, 0x00,
            0x00, 0x00, 0x4f, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
            0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x08,
        ],
        false,
    );
}

/// Found by fuzz8's 10-minute `booleans` run with tiny rotations on (libFuzzer seed 50, artifact
/// crash-5c091a2f…), and failing the same way with them off; minimised to 95 bytes: cubes 0.125
/// wide, one turned 0.016° (the free turn's small steps) about the (1, 1, 1) axis, unioned with a
/// 3-segment sphere and cut by a bar whose faces stand 2.9e-4 rad off the turned cube's. Step 4
/// leaves a needle 6.2e-9 × 0.19 whose short end lies 1.2e-12 off its long edge: no flip
/// applies and each collapse moves the surface 4e-9, far past twice its thickness. Passes with
/// the turn made 0: the near-coplanar kind. Collapsed since the needle pass falls back to its
/// bound (moving the surface 3.8e-9 against 2.3e-6) where nothing applies within the thickness.
#[test]
fn needle_where_a_bar_meets_a_cube_turned_a_hundredth_of_a_degree() {
    replay_with(
        &[
            0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
            0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
            0x20, 0x03, 0x00, 0x00, 0x01, 0xf9, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
            0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
            0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x44, 0x00, 0x00, 0x2d, 0x00, 0x00,
            0x00, 0x00, 0x00, 0x00, 0x00, 0xce, 0xf8, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
            0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x04, 0x00, 0x00, 0x08,
        ],
        false,
    );
}

/// Found by fuzz8's 10-minute `booleans` run with tiny rotations on (libFuzzer seed 45, artifact
/// crash-8c7add00…: a unit box less the same box turned a hair had volume −2e-7), minimised to
/// 33 bytes: a slab 1 × 0.125 × 1 united with itself turned 10⁻⁶° about an axis in its xz
/// plane. The union's volume was 0.1249998, 2e-7 below either operand's: the near-coplanar kind
/// (faces 1.7e-8 rad apart), corners a rounding error off the twin faces counted as on them.
/// Fixed by the narrower noise for vertices not computed on the cutting plane (`given_noise`,
/// `polygon/side.rs`).
#[test]
fn union_of_a_slab_and_itself_turned_a_hair_loses_volume() {
    replay(&[
        0x00, 0x07, 0x00, 0x07, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x08, 0x0a,
        0x08, 0x00, 0x00, 0x07, 0x00, 0x07, 0x00, 0x01, 0x12, 0xff, 0x7f, 0xff, 0xff, 0x0d, 0x00,
        0x08, 0x0a, 0x08,
    ]);
}

/// The round-20 fork run's 7f2fbc81 cut after its step 1: a 0.5 OBJ cube ∪ a 1.125 × 1.125 ×
/// 0.125 slab turned 1e-6° about (1, 1, 1) whose top crosses the cube's along the slab's
/// diagonal, ∪ a 0.625 × 0.25 × 1.5 bar. The slab's top is cut along its diagonal, the cube's
/// at the computed crossing line, up to 1.3e-9 apart: a slit the flat fill closes. Its rim
/// ran along an ear of the cube's top (a sliver of area 1.6e-10 at the bar's face), and the fill
/// laid the ear's reverse on it: a closed shell of no volume (2 shells, not closed). The ear is
/// now taken away instead (`ears_on_rim` in `mesh/repair/cracks.rs`).
#[test]
fn union_of_a_cube_a_slab_turned_1e_6_degrees_and_a_bar_leaves_no_flat_shell() {
    replay(&[
        0x01, 0x03, 0x03, 0x03, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x69,
        0x00, 0x00, 0x00, 0x08, 0x08, 0xd8, 0x01, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xa3, 0x00,
        0x40, 0x03, 0x03, 0x03, 0x30, 0xc4, 0x01, 0x3b, 0xca, 0x50, 0x00, 0x00, 0xf1, 0x00, 0x00,
        0x00, 0x00, 0x00, 0x09, 0x00,
    ]);
}

/// The round-20 fork run's 5919d466 cut to three of its five operands (its 0, 1 and 3): a
/// cylinder (radius 0.6875, 8 segments) ∪ a 0.125 × 0.5 × 1.125 cuboid ∪ a 1.375 × 0.5 × 1.125
/// cuboid turned 1e-9° whose bottom lies on the cylinder's top (y = −0.25), up to 1.5e-11 above
/// it over the contact: two shells touching across a gap thinner than the weld. Step 1 was open
/// (107 edges, 4 boundary edges, one position given two vertex ids).
///
/// Traced on 5919d466 itself (step 3, after a slab is cut away; 4 boundary edges, one position
/// given three ids): the two touching faces weld onto each other along the crowded edges where
/// the slab's cut face meets them (`split_into_shells` in `mesh/repair/shells.rs`). Each
/// crowded edge's triangles are sorted by the angle of their far corner about it, good only to
/// the weld over that corner's distance. The turned face's triangle reaches to a corner past
/// where the faces cross (1.5e-11 below the other face). Its edge is welded down onto the other
/// face, which takes away the 4e-12 … 8.4e-12 it lies above, so it read 2.3e-11 rad below
/// the other sheet (the noise there is 4.8e-11). Two half-edges of one direction then sit side
/// by side, `pair_around` pairs neither, and the vertex splits into copies whose edges have no
/// twin. In this cut the two triangles tie exactly.
///
/// Swapping two neighbours of opposite direction within that noise, where that makes the
/// edge's triangles alternate, closes both. Done in every pass it broke two unit tests in
/// `mesh/repair/mod.rs` (a 32×16 sphere less itself turned 1e-6° came out with a non-manifold
/// edge: slivers of two operands crossing on an edge tie there too, and the later passes close
/// them from the angles' order), so the repair does it only in its last passes, where no other
/// closes the mesh, taken only where it closes (`tie_repair` in `mesh/repair/pass.rs`; here
/// the quick one). Fails without them: step 1 open, 4 boundary edges.
#[test]
fn union_with_a_box_turned_1e_9_degrees_on_a_cylinder_s_top_pairs_the_touching_sheets() {
    replay(&[
        0xe7, 0xee, 0xe7, 0x4a, 0xf3, 0x5f, 0xc9, 0x1b, 0x64, 0x00, 0x41, 0x00, 0x00, 0x00, 0x00,
        0x00, 0x60, 0x00, 0x00, 0xb7, 0x98, 0x01, 0x00, 0x42, 0xf8, 0xfc, 0xd9, 0x00, 0x00, 0x08,
        0x00, 0x08, 0x00, 0x00, 0x8c, 0x8e, 0xb7, 0x98, 0x2e, 0x15, 0xea, 0xe7, 0x50, 0x07, 0x20,
        0x8e, 0xd0, 0x2a, 0x98, 0x82,
    ]);
}

/// From the round-22 CI-mode run (tiny rotations off; crash-1e2fd9e1…, minimised to 25 bytes):
/// a 0.5 × 0.5 × 0.875 box turned 7.67e-4 rad about (−0.59, −0.59, −0.55) at
/// (−0.976, −0.99991, −1) united with a 0.5 × 0.5 × 0.125 box at (−0.5, −0.5, −0.5): the union
/// (closed, genus 0, volume 0.25) kept one needle: a flat cap 1.8e-4 long, 2.1e-8 high (area
/// 1.9e-12) on the second box's bottom edge. The needle pass never saw it: the boxes' bounding
/// boxes meet in a region 0.085 across, and the pass's threshold, by the shell's diagonal (1.72)
/// capped at 16 regions (1.36), was 1.86e-12, the report's (by 1.72) 2.95e-12. The pass now
/// judges needles by the shell's own diagonal, as the report does, and bounds its moves at the
/// capped one; beyond the cap only thin needles (a hair from an edge) are its to remove, so
/// `bsp_4`'s bars (shells 10⁶ across) keep their 40 (`Work::is_needle` in
/// `mesh/needles/work.rs`): the cap goes, the mesh closed and its volume the solid's.
#[test]
fn union_with_a_box_turned_7_7e_4_rad_leaves_no_needle() {
    replay_with(
        &[
            0x00, 0xff, 0xff, 0x12, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x08, 0x08, 0x08, 0x00,
            0x01, 0x03, 0x03, 0x03, 0x00, 0x00, 0x00, 0x00, 0x00, 0xff, 0xff,
        ],
        false,
    );
}

/// The round-20 fork run's 2d7b59dd cut after its step 0 (33 bytes): a cylinder (radius 0.25,
/// 0.75 long, 8 sides) turned 1e-5° about an oblique axis, whose lower side edge lay on the
/// top of a 0.625 × 1.5 × 0.5 box, ∩ that box. Turned, the edge dips into the box by up to
/// 1.6e-8: the intersection is a tetrahedron 0.375 long, 7.5e-8 × 1.6e-8 across at its end,
/// of volume 7.3e-17 (the solid's, exactly the wedge's). Its end triangle (area 5.9e-16) is a
/// speck of its shell (10⁻¹² d² = 1.4e-13), which no operation removes without opening the
/// shell. The needle pass deleted the tetrahedron whole (volume below 10⁻¹² d³/3) and then put
/// it back: the guard held the drop to 1 % of the mesh's volume, of which it was all. Where
/// every shell is deleted whole the guard now lets the mesh go empty, and
/// `Solid::check_mesh_volume` allows what such a drop may take (`NEEDLE_AREA · d³`), so the
/// command line writes the empty mesh. Round 20's 6a886bb6, 75be2603 and 9d46e77d were the
/// same: an intersection one tetrahedron of needles.
#[test]
fn intersection_of_a_box_and_a_cylinder_turned_1e_5_degrees_on_its_top_drops_its_tetrahedron() {
    let input = [
        0xff, 0xff, 0x1d, 0x08, 0xd7, 0xd7, 0x9d, 0xd7, 0x2b, 0x28, 0x28, 0x28, 0x28, 0x01, 0x03,
        0x28, 0x28, 0x28, 0x28, 0xd7, 0x03, 0x00, 0x00, 0x00, 0xfe, 0xff, 0xff, 0xff, 0x00, 0x00,
        0x00, 0x00, 0x00,
    ];
    replay(&input);
    // The same operands built here, through the checked mesh the command line writes.
    let unit = |lo: u8, hi: u8| u16::from_le_bytes([lo, hi]) as f64 / 65535.0 - 0.5;
    let axis = bspcsg::glam::DVec3::new(unit(0xd7, 0x9d), unit(0xd7, 0x2b), unit(0x28, 0x28));
    let turn = bspcsg::glam::DQuat::from_axis_angle(axis.normalize(), 1e-5f64.to_radians());
    let cylinder = bspcsg::Solid::cylinder(0.25, 0.75, 8)
        .unwrap()
        .rotate(turn)
        .unwrap()
        .translate(bspcsg::glam::DVec3::new(-0.4375, -0.3125, 0.0))
        .unwrap();
    let block = bspcsg::Solid::cuboid(bspcsg::glam::DVec3::new(0.625, 1.5, 0.5))
        .unwrap()
        .translate(bspcsg::glam::DVec3::splat(-0.5))
        .unwrap();
    let sliver = &cylinder & &block;
    assert!(sliver.volume() > 0.0 && sliver.volume() < 1e-16);
    let mesh = sliver.to_checked_mesh().unwrap();
    assert!(mesh.is_empty(), "{}", mesh.report());
}
