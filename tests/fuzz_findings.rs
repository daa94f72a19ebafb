//! Every input the `booleans` fuzz target in `fuzz/` found failing, replayed as a named test
//! (the bytes are the fuzz input; `fuzz/fuzz_targets/program.rs` decodes and checks boolean
//! programs). The `scenes` target's findings are in `fuzz_findings_scenes.rs`.

#[path = "../fuzz/fuzz_targets/program.rs"]
mod program;

fn replay(data: &[u8]) {
    replay_with(data, true);
}

/// Replays with tiny rotations on or off (`tiny`; the bounded CI run has them off).
fn replay_with(data: &[u8], tiny: bool) {
    if let Err(e) = program::run(data, tiny) {
        panic!("{e}");
    }
}

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

/// Replays the committed input `tests/fuzz_findings/booleans/NAME.bin`.
fn replay_file(name: &str) {
    let path = format!(
        "{}/tests/fuzz_findings/booleans/{name}.bin",
        env!("CARGO_MANIFEST_DIR")
    );
    replay(&std::fs::read(&path).unwrap_or_else(|e| panic!("{path}: {e}")));
}

// Found by fuzz11's 10.5-minute `booleans` run with tiny rotations on (main 4e5d819, 54,627
// executions, 98 failing inputs, every one passing with tiny rotations off). Each below is one
// of them, minimised by libFuzzer (`-minimize_crash=1`) where that kept the kind of failure: a
// box — the crate's cuboid or the OBJ box alike unless said — turned 1e-10° or 1e-8° about a
// skew axis, and an exact cube or slab on the 1/16 grid whose faces lie in the box's planes
// before the turn. The faces a hair off coplanar were the near-coplanar class (README,
// Robustness); five of these six now pass (see each), the needles of the sixth are open.

/// A 0.125 × 1 × 1.375 box turned 1e-10°, united with a 0.125 cube inside it whose two x faces
/// lie in the box's: the union's volume was 0.1715495, 3.3·10⁻⁴ below the box alone
/// (0.171875). The cube's x faces lay within the tolerance of the box's, so they went whole to
/// the coplanar side, while the box's faces, reaching beyond it, were cut on the crossing line:
/// neither kept the part between. Then the two operands' points on that line lay 8e-7 apart
/// (the box's interpolated along edges whose neighbours' planes were not known), a slit and a
/// flat shell. Now exact, 12 triangles (`Polygon::split`, `attach_edge_planes_among`).
#[test]
fn union_with_a_cube_inside_a_box_turned_1e_10_degrees_loses_volume() {
    replay_file("union_cube_in_box_turned_1e-10");
}

/// A box turned 1e-10° less a 0.125 cube that only touches one of its faces: the mesh had the
/// box's volume (0.1875, right) but the solid's polygons summed to 0.1871338: the cube's top
/// face, within the tolerance of the box's bottom plane, was dropped whole as coplanar, while
/// the box's bottom face was cut on the crossing line and its part inside the cube dropped,
/// a hole the repair filled. Now both are cut on that line (`Polygon::split`).
#[test]
fn difference_of_a_box_turned_1e_10_degrees_and_a_cube_on_its_face() {
    replay_file("difference_cube_on_face_turned_1e-10");
}

/// A 1.375 × 0.875 × 1.125 box turned 1e-10° less a 0.125 cube at its corner: mesh volume was
/// 1.3535156 against the solid's 1.3526505; both 1.353515625 now (`Polygon::split`).
#[test]
fn difference_of_a_box_turned_1e_10_degrees_and_a_cube_at_its_corner() {
    replay_file("difference_cube_at_corner_turned_1e-10");
}

/// A 1.375 × 0.5 × 1.375 box turned 1e-8° united with a 0.125 cube on its face: closed and
/// manifold, but with needles (slivers 0.125 long, 1e-11 thick, on the box's face). Removed by
/// collapses within the needle pass's bound (`mesh/needles/fix.rs`).
#[test]
fn union_with_a_cube_on_a_box_turned_1e_8_degrees_leaves_needles() {
    replay_file("union_cube_on_face_turned_1e-8");
}

/// An OBJ box (12 triangles) 0.5 × 1 × 0.375 turned 1e-10° less a 1.125 × 1.125 × 0.125 slab
/// touching its bottom face: the difference's volume was 0.1972656, more than the box's 0.1875
/// (the crate's own cuboid in its place passed); 0.1875 now (`Polygon::split`).
#[test]
fn difference_of_an_obj_box_turned_1e_10_degrees_and_a_slab_grows() {
    replay_file("difference_slab_under_box_turned_1e-10");
}

/// A box turned 1e-8° united with a bar sharing its bottom plane: 50 triangles, not a closed
/// 2-manifold (4 boundary edges). Closed since the box's cut points on the crossing line of the
/// bottom faces are `meet`s on the same line as the bar's, its edges knowing the planes of
/// neighbours away from the bar (`attach_edge_planes_among`).
#[test]
fn union_of_a_bar_and_a_box_turned_1e_8_degrees_is_open() {
    replay_file("union_bar_and_box_turned_1e-8");
}

// Found by fuzz12's 10-minute `booleans` run with tiny rotations on (main 1e44668, libFuzzer
// seed 0, `-fork=1 -ignore_crashes=1`): 149 failing inputs, all but one passing with tiny
// rotations off, all the near-coplanar class (faces turned 1e-5° to 1e-11° meeting another's).
// One input of each kind of failure, minimised keeping its kind; all open.

/// A 0.125 cube turned 1e-7° about the (1, 1, 1) axis, united with the same cube unturned:
/// 40 triangles, 2 shells, 4 boundary edges (volume 0.001953125, right). 65 of the 149 inputs
/// were open like this, 34 more non-manifold or holding flat shells.
///
/// Traced at the corner C = (−0.4375, −0.5625, −0.5625) of the unturned cube B: the two +x
/// faces cross at 1.4e-9 rad along the diagonal from the fixed corner F = (−0.4375)³ to C, a
/// line known only to about 7e-9 across the face (rounding 1e-17 over the angle). The turned
/// cube A's corner there is A_C = C + (0, −δ, δ), δ = 1.26e-10, whose x is exactly −0.4375: on
/// B's +x plane; C lies on A's +x plane to 6e-20. Each operand cuts its +x face by the other's
/// plane through its own corner (A along F–A_C, B along F–C), each picture consistent alone,
/// but they disagree on the order in which the crossing line meets A's −z plane (z = δ) and
/// B's −y plane (y = 0): A's line meets B's −y first, at C + (0, 0, 2δ); B's meets A's −z
/// first, at C + (0, δ, δ). `share_near_parallel_vertices` then makes each plane triple one
/// point across the two pictures (C + (0, δ, δ) → A_C, C + (0, 0, 2δ) → C), so B's piece
/// (C, Q, A_C), Q its corner (−0.4375, −0.4375, −0.5625), reaches past B's own −y edge and lies
/// folded over A's (A_C, C, P_A), P_A A's corner by (−0.4375, −0.5625, −0.4375); the mesh
/// holds two flat pillows (a triangle and its reverse, twice) and a vertex split between two
/// shells. Without the sharing it had 7 boundary edges. Now, against a nearly parallel plane of
/// the other operand, every polygon holding a vertex near it (of its own plane or by an edge in
/// a nearly parallel one) judges it by its distance across the one crossing line both operands
/// compute (the `meet` line, `Crossing` in `polygon/planes.rs`), not by its distance from the
/// plane, which cannot tell the two corners apart: closed, 0.001953125.
#[test]
fn union_of_a_cube_and_itself_turned_1e_7_degrees_is_open() {
    replay_file("union_cube_and_itself_turned_1e-7");
}

/// A 0.125 cube, united with a disjoint copy turned 1e-11°, then intersected with that copy
/// unturned: the mesh had the cube's volume 0.001953125 (right), but the solid's polygons
/// summed to 0.0013020833, two thirds of it (30 of the 149 inputs were this kind). The first
/// cube's y and z faces lie in the planes of the unturned copy's; building the union's tree,
/// the turned copy's faces (1.3e-14 off those planes at their corners) read as coplanar with
/// the first cube's faces, their vertices taken as possibly made on them, so the turned planes
/// were never splitters and the unturned copy's faces went whole to one side, while the turned
/// faces, clipped by the copy's tree, were cut on the crossing line: two of the six faces lost
/// half. A solid's own uncut polygons now count as given in the tree build as in the clip
/// (`Polygon::split_as`): 12 polygons, exact.
#[test]
fn intersection_with_a_cube_turned_1e_11_degrees_loses_a_third_of_the_solid() {
    replay_file("intersection_after_union_with_cube_turned_1e-11");
}

/// A 1.375 × 0.625 × 0.5 box turned 1e-11° united with a bar turned freely, then with a
/// 0.5 × 0.125 × 0.125 bar under the box's bottom face, flush with its −y face: the second
/// union's volume was 0.5453578, 7e-6 more than the sum of its operands (0.5453508); 17 of the
/// 149 inputs had a volume out of the operation's bounds. The bottom faces cross at 1.7e-13
/// rad, a line known only to 6e-5 across the face: banded, each was cut on it, a slot thinner
/// than the weld between them (the box and the bar alone: open, 4 boundary edges), and the
/// fragments of the box's bottom (cut by the first bar) judged the line apart: they kept
/// 5.6e-5 more area in the slot than the bar's top. Planes crossing below half the relative
/// tolerance now count as parallel (`PARALLEL_BELOW`: they part by less than half the
/// tolerance across the region): the faces touch and go, 0.5453508, closed, 60 triangles.
#[test]
fn union_with_a_box_turned_1e_11_degrees_exceeds_the_sum_of_its_operands() {
    replay_file("union_box_turned_1e-11_bar_and_bar");
}

/// A coarse sphere united in turn with a cylinder, a 0.125 cube turned 1e-5°, a 3-sided prism
/// and a 0.25 × 1.5 × 0.125 bar: step 3 is a closed 2-manifold (genus 0, 2 shells, volume
/// 0.1485451) held one needle. The one such input of the 149.
///
/// The needle lies on x = −0.375, a face of the cube turned 1e-5° whose corners moved
/// 1.26e-8: corners (−0.375, −0.1249999999254, −0.5624999874042), (−0.375, −0.1250000005976,
/// −0.5624999874042) and (−0.375, −1.26e-8, −0.5625), a spike 0.125 long on a short edge of
/// 6.7e-10 (area 4.2e-18), in a flat fan whose triangle across that edge is a sliver of
/// 3.6e-12 beside another of 3.8e-12. Collapsing the short edge moves the surface by 6.7e-10,
/// well within the needle pass's bound, but the link condition refused it: its ends shared a
/// third neighbour through a vertex of valence three beside them (its triangles the fan's
/// slivers). A neighbouring needle's collapse removed that vertex, after the spike had been
/// tried, and only the triangles an operation changed were queued again. Now the needles with
/// a corner on any of them are (their link changed): 0 needles, closed.
#[test]
fn needle_after_unions_with_a_cube_turned_1e_5_degrees() {
    replay_file("unions_with_cube_turned_1e-5_needle");
}

/// The one input of that run failing with tiny rotations off too (crash-e23bb76a…, so within
/// reach of the bounded CI run), minimised to 54 bytes, with no tiny turn left: a bar united
/// with a coarse sphere (3 segments), less a finer sphere (12 segments) of the same radius and
/// centre, both turned 1.4° about axes 2e-3 rad apart, so facets meet about 5e-5 rad off
/// coplanar. Step 1 left 9 shells, one of them read as flat: an 8-triangle sliver shell of
/// volume 1.0e-18, closed and wound outward, whose volume summed about the mesh's box centre
/// came out −9.5e-19 (rounding of ε |p − c|³ per triangle). The report now sums each shell
/// about its own first corner (`ShellReport::volume`): 9 closed shells, all positive.
#[test]
fn difference_of_spheres_turned_alike_about_close_axes_leaves_a_flat_shell() {
    replay_file("difference_of_spheres_turned_alike_about_close_axes");
}

// Found by kind1-15's 10.6-minute `booleans` run with tiny rotations on (main 3438a23, libFuzzer
// seed 2188232807, `-fork=1 -ignore_crashes=1`, 80,341 executions): 61 failing inputs, all passing
// with tiny rotations off, all the near-coplanar class. 58 failed on main before the judging by
// the crossing line too (795a405); these three passed there and fail since (not minimised).

/// 42 bytes: step 1 is not a closed 2-manifold; closed on 795a405. A 0.125 × 0.125 × 0.375 box
/// turned 1e-8° united with a 0.125 cube turned 1e-7° at the same centre, less the OBJ cube
/// there unturned. When found: 114 triangles, 2 shells, volume right to 1e-10; on main be1b9bf
/// (round 17): 123 triangles, 7 boundary edges on the cube's faces x = −0.4375 and y = −0.5625,
/// and the solid's volume 0.0039079589 is 1.7e-6 above the two end pieces' 0.00390625. It takes
/// three nearly parallel planes to a side (measured): the box less the cube, the turned cube less
/// it and the unturned box ∪ the turned cube less it all close with the volume right; the union
/// of the two turned ones, whose sides are pieces of two planes 1.7e-9 rad apart meeting on
/// their crossing line, less the exact cube does not (the crate's cuboid for the cube: 12
/// boundary edges, 8.3e-5 high). Summed by plane, the kept faces of the middle section overlap
/// where they should be complementary: on x = −0.5625 the union's and the cube's (turned
/// inward) each 0.0098 of the 0.0156 there, on x = −0.4375 0.0098 and 0.0083. A vertex is
/// judged by one crossing line (its own plane's or an edge's with the cut, the closest to
/// parallel), and where three planes cross nearly in parallel the two operands pick different
/// pairs. Instrumented: at the cube's corners, on the line where the turned cube's top face
/// crosses the exact one, the distance across that line came out ±2e-20 … ±9e-20 against a band
/// (eps times the sine, 1.7e-9) of 3.7e-22: the side is the line's own rounding, its point being
/// known only to an ulp over the sine across it.
#[test]
fn open_at_step_1_since_the_crossing_line_judgement() {
    replay_file("open_step_1_crossing_line_judgement");
}

/// 73 bytes: step 3 was not a closed 2-manifold (30 triangles, 3 shells, 4 boundary edges,
/// volume 0.0019531250 right); closed on 795a405. Closed since a triangle and its reverse,
/// a fin the weld laid flat, are dropped together (`cancel_reversed_pairs` in
/// `mesh/repair/fins.rs`).
#[test]
fn flat_fin_at_step_3_since_the_crossing_line_judgement() {
    replay_file("open_step_3_crossing_line_judgement");
}

/// 72 bytes: at step 3 the mesh's volume 0.13228829119 was off the solid's 0.13228829240 (9e-9
/// relative, beyond the check's slack); within it on 795a405, and again since the polygons of
/// one flat face of a mesh share one plane (`share_face_planes` in `polygon/faces.rs`).
#[test]
fn mesh_volume_off_at_step_3_since_the_crossing_line_judgement() {
    replay_file("mesh_volume_step_3_crossing_line_judgement");
}

/// Found by a 10-minute run of the `booleans` target in round 17 (libFuzzer seed 1701, artifact
/// crash-62760edd…, after 2,037 executions at about 14 s), not minimised; passes with tiny
/// rotations off. A 1 × 1.5 × 1 box is nicked at its corner (−0.5, 0, −0.5) by a unit cube
/// turned 0.17 rad (9e-11 of volume), then less a 1 × 0.125 × 1 slab through its middle turned
/// 1e-6° (1.7e-8 rad), whose four sides lie a hair off the box's. Step 2's solid has volume
/// 1.3645833 where the two pieces make 1.375: 1/96 short. Traced to its polygons: above y = 0 the
/// box's face z = −0.5 lost the slab's strip (0.6875 left, right) while the slab's own face there
/// was kept, turned inward (area 0.0625, normal +z at z = −0.5): each judged inside the other,
/// and (1/3)(0.5)(0.0625) = 1/96 is the volume it takes. On the other three sides both were kept
/// (a double layer: volume right, not manifold). The plain box (no nick) less the same slab is
/// closed with volume right to 1e-10, so the nick's small polygons at that corner, on the slab's
/// crossing lines, are part of it. Traced further (round 21): the slab's face z = −0.5 (turned
/// inward) beyond its crossing line with the box's, 2e-10 … 8e-10 in front of the box's
/// bottom, is cut there by the box's tree and its front piece lands in an unbuilt cell whose only
/// polygon is the nick's piece of that bottom (x −0.5 … −0.46, y 0.44 … 0.75), far from it. It
/// is labelled from the last point labelled in that cell (`label_whole`: a chain of three points
/// 2e-10 … 4e-10 in front of the bottom, all Inside) where a ray from it says Outside: the
/// chain's first label is wrong, and the cell's one polygon lets every later one copy it.
/// Traced further (round 22): that first point, 3.3e-11 inside the box's −x face, was labelled
/// by a segment from a point of the neighbouring cell outside it (right), which crosses that
/// face running along it at 8.6e-10 rad; `crossing` took any plane within 1e-9 of the
/// direction for parallel and the crossing for a miss. Counted now (`bsp/surface/ray/mod.rs`): passes.
#[test]
fn nicked_box_less_a_slab_turned_1e_6_degrees() {
    replay_file("nicked_box_less_slab_turned_1e-6");
}

/// Found by a second `booleans` run in round 17 (libFuzzer seed 1705, artifact crash-0d0e67ae…,
/// after 2,198 executions at about 7 s), not minimised; passes with tiny rotations off. A 0.125
/// cube at (−0.5, −0.5, −0.5), cut by two boxes turned freely (steps 0 and 1: 0.0019243 left), then
/// united with a 0.125 × 0.125 × 1.125 bar turned 1e-9° (1.7e-11 rad) whose face x = −0.4375
/// lies a hair off the cube's. Step 2 has the right volume (0.0195024018, the sum to 5e-14) but
/// 4 boundary edges: a slit on x = −0.4375, two vertices at (−0.4375, −0.5625, −0.54112) not
/// joined, each ending the edges to (−0.4375, −0.5625, −0.4375) and (−0.4375, −0.52016, −0.4375).
/// The solid keeps, where the two faces overlap, both a piece of the cube's face (normal +x) and
/// two of the bar's (normal −x, their corner 1.7e-12 from the cube's): a union should drop both
/// there; the mesh's repair leaves the double layer's rim as the slit. Passes on main 85811eb
/// (found so in round 21, before the sliver change below; the change that closed it was not
/// traced).
#[test]
fn union_with_a_bar_turned_1e_9_degrees_on_a_cut_cube() {
    replay_file("union_with_bar_turned_1e-9_on_a_cut_cube");
}

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
/// `bsp/surface/ray/mod.rs`; minimised in `robustness.rs`,
/// `union_with_a_cube_inside_a_bar_beside_its_turned_twin_changes_nothing`). With it, round
/// 20's edf27eb0 (a cylinder ∪ a bar turned 1e-3° ∪ the 0.125 cube three times, once an OBJ
/// box: step 3 the solid 2.1e-5 above its mesh), not traced.
const FORK_PASSING: [&str; 37] = [
    "0444665d", "0948e42e", "1037da39", "191ab237", "1aeb92c4", "2726d2e5", "32c62795", "4c4a25bc",
    "4f11d669", "4ff3cfe7", "56caf33f", "6674c41e", "69eb964a", "6b0e99dd", "72da0961", "75ca2fd2",
    "7b3ae46a", "7b9f78bf", "7d80d340", "93aab2f0", "967a3be9", "9e873673", "9edbc5f5", "9f0af865",
    "b9755cf2", "c2bc4de2", "c88c23a3", "cf177d2c", "d6e249f8", "e72a4a41", "ea6f2083", "ec4e381d",
    "f25a77c8", "f33d6823", "f4856d6f", "f5c69f47", "f914fc01",
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

/// The inputs of the round-17 fork run that pass now ([`FORK_PASSING`]).
#[test]
fn the_round_17_fork_run_inputs_that_pass() {
    let failures = fork_failures("round17_fork", &FORK_PASSING);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Every other input of the round-17 fork run, replayed; the failures listed.
#[test]
#[ignore = "open: near-coplanar — 1 input of round 17's fork run fails with tiny rotations on (volume out of bounds), all pass with them off"]
fn the_round_17_fork_run_near_coplanar_inputs() {
    assert_fork_run_passes("round17_fork", 38, &FORK_PASSING);
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
#[test]
#[ignore = "open: near-coplanar — 3 inputs of round 18's fork run fail with tiny rotations on (2 mesh volume off the solid's, 1 closed with 2 needles: b447eea7, listed as passing until round 27, when this list was first replayed whole; it fails at the round's start too), all pass with them off"]
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
/// (`sliver_side` in `bsp/build/face.rs`; its test in `robustness.rs`); 37e0688d (a bar turned
/// 0.298 rad ∪ a 0.125 cube and a 0.625 cube, both turned 1e-5° about their diagonal, ∩ the
/// 0.625 cube unturned: step 2 open, 4 boundary edges) and 71023f02 (the same union ∪ a
/// cylinder, less the unturned cube: step 3 open, 5 boundary edges; not traced), closed since an
/// edge whose neighbour was cut inside it by an earlier boolean takes that neighbour's plane
/// (`attach_edges_across_t_junctions` in `polygon/planes.rs`; minimised in `robustness.rs`):
/// its corner, 6.4e-15 off the unturned cube's face, no longer counts as made on it;
/// f35b6000 (a 0.125 × 0.625 × 0.875 box turned 1e-9° ∪ a cube ∪ an unturned box on its
/// face ∪ a 0.125 cube at its corner: step 2 open, 6 boundary edges), closed since a flat fin
/// whose two sides cover one quad along different diagonals is dropped like a reversed pair
/// (`cancel_reversed_quads` in `mesh/repair/fins.rs`); and the
/// inputs of [`FORK_18_SLIVER_ENDS`] and [`FORK_18_NEAR_PLANES`].
///
/// Also passing since the changes named at [`FORK_PASSING`]: the inputs not named above.
const FORK_18_PASSING: [&str; 66] = [
    "0052c3eb", "02530f35", "0790ea94", "0827a164", "0d0928b6", "10073393", "1520a690", "15d49cd9",
    "1790af98", "1e4064b4", "20453056", "3113dfce", "37e0688d", "37ff3bf3", "3900a850", "3cc49f00",
    "420d2bab", "5179ded6", "523bd25f", "540b19a9", "5a865123", "5bb3d708", "62f4302a", "71023f02",
    "7eef8488", "8114e14d", "81d5fe25", "8a96f30b", "94f4cf5d", "9690e076", "9afa182f", "9f600b4c",
    "a03b7e97", "a08947f3", "a1909398", "a406f929", "aa164e38", "ab676359", "b0b42816", "b0b4ab89",
    "b153683f", "b4c5614a", "b69ed8aa", "bdff1088", "be4ad59a", "c0e3de16", "c7455c8d", "c8152ded",
    "c9b1a2f6", "ca3a7ad3", "ccc60bb4", "ce4b062b", "d52c6d78", "da05d311", "dd18b60b", "df981536",
    "e26cedea", "e4c5eda4", "e8b2a516", "ee10478e", "f31d7404", "f35b6000", "f74d9e2a", "f966a4ee",
    "fbbe3eb1", "fc859488",
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
/// Also passing since the changes named at [`FORK_PASSING`]: the inputs not named above.
const FORK_20_PASSING: [&str; 97] = [
    "04880fb6", "060752d1", "0bebd350", "1194b103", "12758e1c", "12bcee43", "1d6b6b28", "1d7d9f8a",
    "1f854764", "20254c75", "22568913", "22b67390", "24057533", "25a6e85f", "2a7dd67a", "2d7b59dd",
    "2f1db746", "394fbf5b", "3ecaaeed", "42b00a8c", "43f8dc80", "44bbfb06", "45e7cb01", "4b6fae9d",
    "4dba1202", "50f56fc8", "52a63048", "53fd6805", "54ad2229", "5927f563", "5ba8f6ed", "5be20e4a",
    "5f7ef5a2", "60e1b472", "6a886bb6", "6c1d9139", "6c2460ab", "74027838", "75be2603", "778ac30a",
    "78085500", "79dd0a25", "7d6886ee", "7eb5e225", "7ee590be", "7f2fbc81", "7f88a284", "8116c238",
    "822b0d3d", "83b87dcb", "84cb559e", "84ce80c0", "87f26b5a", "8936dbd6", "8dea14d6", "91c935ab",
    "94d83441", "9530713d", "9679585b", "97cf8f64", "98725c3d", "9ace493f", "9d46e77d", "a30a743f",
    "a3a7185f", "aaf8bd05", "ad644dcd", "afdfb2bf", "b07b43ca", "b770c958", "c095e8fc", "c287ef50",
    "c724056e", "c9724cd5", "c9f5e09e", "c9f9a708", "ce00c570", "d116749a", "d3147b45", "d642c6e2",
    "d6f045bf", "d8a85c01", "dcbd5cd9", "de6a214f", "df3549fa", "e02e0760", "e0c0778c", "e9c633a3",
    "ea147c0f", "eb2498a7", "ebb7181c", "edf27eb0", "ef943716", "f385f178", "fa3003dd", "fc4b5873",
    "fe9275bb",
];

/// The inputs of the round-20 fork run that pass now ([`FORK_20_PASSING`]).
#[test]
fn the_round_20_fork_run_inputs_that_pass() {
    let failures = fork_failures("round20_fork", &FORK_20_PASSING);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Every other input of the round-20 fork run, replayed; the failures listed.
///
/// Traced, not fixed: 5919d466 (step 3 open) is two touching sheets whose triangles tie in
/// angle about a crowded edge. It is minimised as
/// `union_with_a_box_turned_1e_9_degrees_on_a_cylinder_s_top_pairs_the_touching_sheets`.
/// 0a15665e (an OBJ bar turned 1e-2° ∪ an OBJ box turned 1e-3° ∪ a cuboid ∪ a 0.125 cube at
/// their centre, less a slab whose faces are the cube's top and bottom) is open at step 3
/// because of two lone triangles of about 2e-17, one at each of two opposite corners of the
/// cube's top and bottom (z = −0.4375 and −0.5625). Neither has a neighbour. Each is bounded by
/// the cube's two faces and by the line where the box turned 1e-3° crosses that plane
/// (diagonal, at a sine of about 1.4e-5), 6.7e-9 on a side: a piece of a thin wedge whose
/// other face the clip did not keep, not a repair defect; not traced to that clip decision.
#[test]
#[ignore = "open: near-coplanar — 11 inputs of round 20's fork run fail with tiny rotations on (4 not closed, 3 mesh volume off the solid's, 1 volume out of bounds, 3 needles), all pass with them off"]
fn the_round_20_fork_run_near_coplanar_inputs() {
    assert_fork_run_passes("round20_fork", 108, &FORK_20_PASSING);
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
/// it over the contact: two shells touching across a gap thinner than the weld. Step 1 is open
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
/// edge's triangles alternate, closes both (and 5919d466, nothing else of the fork runs changed;
/// branch `forks28a-fix`). But it breaks two unit tests in `mesh/repair/mod.rs`: a 32×16
/// sphere less itself turned 1e-6° comes out with a non-manifold edge, and the 16×8 one at
/// 1e-6° closes after 4 passes, not 5 or more. Slivers of two operands crossing on an edge
/// also tie there, and their order is not a gap's, so the swap needs a test that tells a gap
/// between two shells from such a crossing before it can go in.
#[test]
#[ignore = "open: not closed — step 1 has 4 boundary edges: the triangles of two touching sheets, welded onto each other, tie in angle about a crowded edge and do not alternate"]
fn union_with_a_box_turned_1e_9_degrees_on_a_cylinder_s_top_pairs_the_touching_sheets() {
    replay(&[
        0xe7, 0xee, 0xe7, 0x4a, 0xf3, 0x5f, 0xc9, 0x1b, 0x64, 0x00, 0x41, 0x00, 0x00, 0x00, 0x00,
        0x00, 0x60, 0x00, 0x00, 0xb7, 0x98, 0x01, 0x00, 0x42, 0xf8, 0xfc, 0xd9, 0x00, 0x00, 0x08,
        0x00, 0x08, 0x00, 0x00, 0x8c, 0x8e, 0xb7, 0x98, 0x2e, 0x15, 0xea, 0xe7, 0x50, 0x07, 0x20,
        0x8e, 0xd0, 0x2a, 0x98, 0x82,
    ]);
}

/// From the round-20 fork run (11b5badf), failing with tiny rotations off too, so within reach
/// of the bounded CI run; minimised to 38 bytes: a cylinder (radius 0.125, 6 segments) less a
/// 0.125 × 0.125 × 0.875 bar turned 9.6e-5 rad about an oblique axis, united with a 1.5 × 0.125
/// × 0.125 bar. Step 1 is closed (genus 2) with one needle: a cap of sides 5.3e-7, 5.3e-7 and
/// 1.06e-6 (height 6.5e-9, area 3.4e-15 against a bar of 2.6e-12) where the turned bar's faces
/// meet the cylinder's; the needle pass leaves it.
///
/// Traced: the turned bar's wall grazes the cylinder's side edge at (−0.5625, −0.4375, −0.4375),
/// where the other bar's edge runs too, and the needle sits on a handle there. Its apex (33) and
/// long edge (20–16) with vertex 37, 1.1e-4 along that bar's edge, span four triangles of which
/// only two are the mesh's (the needle and its neighbour 16–20–37): the flip would make the
/// edge 33–37 a second time. Every edge fails the link condition (its ends also share 37 or
/// the cylinder's corner, 0.25 off), the other edges' flips fold, the corners' star and the
/// cluster's (16, 17, 20, 33) are surfaces of Euler characteristic −1 (neither a disk to merge
/// nor an annulus to cut), widening needs 7.2e-6 against the bound 3.2e-6, and every stretch
/// moves a large triangle's corner 2.9e-4 off its plane. Removing it changes the topology at
/// the handle: no operation of the pass does that.
#[test]
#[ignore = "open: needle — a cap on a handle (its corners' star of Euler characteristic −1): its flip makes an existing edge, every collapse fails the link condition, widening needs 7.2e-6 against the bound 3.2e-6"]
fn needle_where_a_bar_turned_1e_4_rad_meets_a_cylinder() {
    let path = format!(
        "{}/tests/fuzz_findings/booleans/cylinder_less_bar_turned_1e-4_rad_needle.bin",
        env!("CARGO_MANIFEST_DIR")
    );
    replay_with(&std::fs::read(&path).unwrap(), false);
}

/// From the fork run (crash-33894a02…, 84 bytes): a unit cube turned 1e-7° less a box turned
/// 1e-9°, intersected with another box turned 1e-9° that nearly holds the same cut: step 1's
/// solid has volume 1.5e-12 and no triangles (a sliver of flat shells). Intersected with a
/// 0.625 × 0.625 × 0.125 slab turned 1e-9° at step 2 it grows to 7.9e-6: an intersection larger
/// than an operand.
#[test]
#[ignore = "open: near-coplanar — an intersection with a flat 1.5e-12 remnant comes out 7.9e-6"]
fn intersection_with_a_flat_remnant_grows() {
    replay_fork("33894a02");
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

/// From the round-21 CI-mode run (tiny rotations off; crash-deed344d…, minimised to 47 bytes):
/// a 0.25 × 0.125 × 0.125 box at (−0.5, −0.5, −0.5) united with a 0.125 × 1.375 × 1.375 box at
/// (−0.375, −0.5, −0.5), then with a 0.125 × 1.375 × 0.5 box turned 9.6e-5 rad. Between the
/// second box's −x face and the turned box's +x face lies a wedge-shaped slit, 3.2e-10 wide
/// where it ends on the first box's −y face in a needle 9.4e-6 long. Step 1's mesh had volume
/// 0.32323803083746, 4.8e-9 below the solid's 0.32323803567004 (exact: 0.323238035670042):
/// no collapse closed the slit's tip (the link condition refused it, the collapse turning two
/// triangles across the slit into a fin pair), so the needle pass stretched the needle across
/// the slit by 1.24e-6, widening it over the turned face.
#[test]
fn union_slit_tip_needle_turned_1e_4_rad_loses_volume() {
    let path = format!(
        "{}/tests/fuzz_findings/booleans/union_slit_tip_needle_turned_1e-4_rad.bin",
        env!("CARGO_MANIFEST_DIR")
    );
    replay_with(&std::fs::read(&path).unwrap(), false);
}

/// From the round-22 CI-mode run (tiny rotations off; crash-1e2fd9e1…, minimised to 25 bytes):
/// a 0.5 × 0.5 × 0.875 box turned 7.67e-4 rad about (−0.59, −0.59, −0.55) at
/// (−0.976, −0.99991, −1) united with a 0.5 × 0.5 × 0.125 box at (−0.5, −0.5, −0.5): the union
/// (closed, genus 0, volume 0.25) kept one needle: a flat cap 1.8e-4 long, 2.1e-8 high (area
/// 1.9e-12) on the second box's bottom edge. The needle pass never saw it: the boxes' bounding
/// boxes meet in a region 0.085 across, and the pass's threshold, by the shell's diagonal (1.72)
/// capped at 16 regions (1.36), was 1.86e-12, the report's (by 1.72) 2.95e-12. With
/// `NEEDLE_REGION_REACH` at 64 the pass flips it (volume unchanged; cross-check 900/900, the
/// benchmarks' outputs identical), but then `to_mesh` also edits the whole bars of the scene
/// `bsp_4` (shells 10⁶ across): 24 needles left of its 40, which that test counts on keeping.
#[test]
#[ignore = "open: needle — a flat cap (area 1.9e-12) on a shell 20 regions across: to_mesh caps the needle threshold's diagonal at NEEDLE_REGION_REACH (16) regions, 1.86e-12, below the report's 2.95e-12; reach 64 takes it but edits bsp_4's whole bars"]
fn union_with_a_box_turned_7_7e_4_rad_keeps_a_needle() {
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
