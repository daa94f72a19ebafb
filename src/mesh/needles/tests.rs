//! Unit tests of the needle pass on meshes cut from booleans that left needles: patches and
//! necks of specks, a slit's tip. The volume guard's tests are in `guard`.

mod guard;

use glam::DVec3;

use super::{remove_needles, remove_needles_patched};
use crate::mesh::Mesh;

/// A mesh from OBJ-like text: `v x y z` and `f a b c` (1-based) lines.
fn read(text: &str) -> Mesh {
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for line in text.lines() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => {
                let c: Vec<f64> = words.map(|w| w.parse().unwrap()).collect();
                positions.push(DVec3::new(c[0], c[1], c[2]));
            }
            Some("f") => {
                let c: Vec<u32> = words.map(|w| w.parse::<u32>().unwrap() - 1).collect();
                triangles.push([c[0], c[1], c[2]]);
            }
            _ => {}
        }
    }
    let sources = vec![0; triangles.len()];
    Mesh {
        positions,
        triangles,
        sources,
    }
}

/// Runs the pass on `mesh` (closed, with needles) and checks it leaves none, closed, with the
/// volume it had.
fn removes_every_needle_keeping_the_volume(mesh: &mut Mesh) {
    let volume = mesh.volume();
    let left = remove_needles(mesh, None, None);
    let report = mesh.report();
    assert_eq!(left, 0, "{report}");
    assert!(
        report.is_closed_manifold() && report.needles == 0,
        "{report}"
    );
    assert!((mesh.volume() - volume).abs() < 1e-15 * volume.abs().max(1.0));
}

/// The pass on a patch around the needles gives the whole mesh's result, bit for bit, however
/// deep the patch: with no ring, every operation reads beyond it and the whole mesh's pass
/// runs; with one or more, the patch finishes on SLIT_TIP's needles (22, 49 and 64 of its 68
/// triangles at one, two and three rings) and the two speck meshes' patches hold the whole mesh.
/// (Not asserted here: which path finished; a neck cut on a patch smaller than its shell is not
/// among these meshes.)
#[test]
fn a_patch_gives_the_whole_meshs_result() {
    for text in [PATCH_OF_SPECKS, NECK_OF_SPECKS, SLIT_TIP] {
        let mut whole = read(text);
        let left = remove_needles_patched(&mut whole, None, None, usize::MAX, 0);
        for rings in [0, 1, 2, 3] {
            let mut patched = read(text);
            let patched_left = remove_needles_patched(&mut patched, None, None, 1, rings);
            assert_eq!(patched_left, left);
            assert_eq!(patched.positions, whole.positions);
            assert_eq!(patched.triangles, whole.triangles);
            assert_eq!(patched.sources, whole.sources);
        }
    }
}

/// The south pole of two spheres (radius 0.4375, 11 and 3 segments) at one centre, one turned
/// 1e-7° (the round-17 fork input e72a4a41, step 2): 14 vertices within 6.8e-10 of the pole,
/// the two apexes' crossing loop, their every edge below the speck length, and the 38 triangles
/// around them; closed here by a fan from a point 0.25 off. Every collapse of a needle's edge
/// and every merge of a needle's three corners folds a neighbour in the patch; the 12 vertices
/// the needle's short edge reaches by such edges merge into one, the volume kept.
#[test]
fn a_patch_of_specks_merges_into_one_vertex() {
    let mut mesh = read(PATCH_OF_SPECKS);
    assert!(mesh.report().is_closed_manifold());
    assert!(mesh.report().needles > 0);
    removes_every_needle_keeping_the_volume(&mut mesh);
}

/// The same south pole where the other sphere has 3 segments (the round-17 fork input
/// 75ca2fd2, step 1): 6 vertices within 9.8e-10 of the pole, every edge between them below the
/// speck length, whose 33 triangles form an annulus, not a disk: a neck between the two cones,
/// from the 11-segment sphere's pole fan (its rim one boundary cycle) to the other's (the
/// other); closed here by a fan over each cycle (crossing each other: only the patch matters),
/// put so that each cone closed alone is outward. Every collapse and merge folds a neighbour or
/// would pinch the neck into a vertex of two cones; cut, each cycle gets its own apex (here two
/// shells, the volume kept).
#[test]
fn a_neck_of_specks_is_cut() {
    let mut mesh = read(NECK_OF_SPECKS);
    let before = mesh.report();
    assert!(
        before.is_closed_manifold() && before.needles > 0,
        "{before}"
    );
    removes_every_needle_keeping_the_volume(&mut mesh);
}

const PATCH_OF_SPECKS: &str = "
v -0.2542572671091783 -0.779740861658416 -0.2974033572944101
v -0.2542572671091783 -0.784941259137637 -0.3750000000000001
v -0.2542572671091783 -0.7691738797073083 -0.23862513006705133
v -0.2542572671091783 -0.7797408616584159 -0.4525966427055901
v -0.37500000059735145 -0.8124999998579024 -0.3749999998246016
v -0.3750000005973515 -0.8124999998579024 -0.37500000018704693
v -0.3750000004742914 -0.8125 -0.3749999999739006
v -0.3750000006085716 -0.8124999998449466 -0.3749999997413204
v -0.3750000003478934 -0.8124999999270242 -0.3749999999739006
v -0.3750000004367526 -0.8124999998961057 -0.3749999998916792
v -0.3750000005750192 -0.8124999998632149 -0.3750000001688409
v -0.3750000003358958 -0.8124999999200974 -0.3749999999739006
v -0.2961442041320129 -0.7691738797073083 -0.20232989252764458
v -0.40201479119584155 -0.7691738797073083 -0.187108000135361
v -0.49930837293238384 -0.7691738797073083 -0.2315404901186687
v -0.5571349245838862 -0.7691738797073083 -0.3215203608528396
v -0.5571349245838862 -0.7691738797073083 -0.42847963914716036
v -0.4993083729323839 -0.7691738797073083 -0.5184595098813313
v -0.40201479119584155 -0.7691738797073083 -0.562891999864639
v -0.29614420413201303 -0.7691738797073083 -0.5476701074723554
v -0.37499999983144955 -0.81249999995427 -0.3749999998916792
v -0.37499999995053157 -0.8124999999728203 -0.3749999998916792
v -0.375 -0.8125 -0.375
v -0.37500000001557415 -0.8124999999750222 -0.3749999998916792
v -0.37500000009386053 -0.8124999999672861 -0.3749999998916792
v -0.37500000036890674 -0.8124999999122448 -0.3749999998916792
v -0.39023562068751283 -0.5319828783377424 -0.29579807945511477
f 5 6 7
f 7 8 5
f 7 9 10
f 7 10 8
f 9 7 6
f 11 12 9
f 6 11 9
f 2 1 21
f 21 22 23
f 21 23 2
f 3 13 22
f 1 3 22
f 22 21 1
f 22 13 14
f 24 25 23
f 24 23 22
f 14 24 22
f 14 15 25
f 25 24 14
f 15 16 5
f 26 23 25
f 8 10 26
f 8 26 25
f 8 25 15
f 15 5 8
f 5 16 17
f 17 6 5
f 26 10 9
f 12 11 23
f 12 23 26
f 26 9 12
f 6 17 18
f 23 11 6
f 18 23 6
f 18 19 23
f 23 19 20
f 4 23 20
f 2 23 4
f 1 2 27
f 3 1 27
f 13 3 27
f 14 13 27
f 15 14 27
f 16 15 27
f 17 16 27
f 18 17 27
f 19 18 27
f 20 19 27
f 4 20 27
f 2 4 27
";

const NECK_OF_SPECKS: &str = "
v -0.011096528774452157 -0.6024002323395962 -0.375
v -0.011096529527556829 -0.6024002334757852 -0.37499999929861616
v -0.009138859760936882 -0.593750000167377 -0.36748002717560874
v -0.5644430575411552 -0.5937499995508126 -0.07327103045609906
v -0.5479679869488976 -0.61277377245166 -0.07541065925868538
v -0.5389158448719502 -0.5937499995492852 -0.061613143049167526
v -0.5389158442174214 -0.5937500002927426 -0.6883868568720903
v -0.5644430568253546 -0.5937500002666135 -0.6767289695071894
v -0.5479679863113791 -0.6127737730778537 -0.6745893407143708
v -0.009138859284567976 -0.5937500001852171 -0.3825199711727684
v -0.2153097750878413 -0.7691738797073083 -0.27237332401372155
v -0.18517586413606826 -0.7691738797073083 -0.375
v -0.2961442041320129 -0.7691738797073083 -0.20232989252764458
v -0.40201479119584155 -0.7691738797073083 -0.187108000135361
v -0.49930837293238384 -0.7691738797073083 -0.2315404901186687
v -0.5571349245838862 -0.7691738797073083 -0.3215203608528396
v -0.5571349245838862 -0.7691738797073083 -0.42847963914716036
v -0.4993083729323839 -0.7691738797073083 -0.5184595098813313
v -0.40201479119584155 -0.7691738797073083 -0.562891999864639
v -0.29614420413201303 -0.7691738797073083 -0.5476701074723554
v -0.2153097750878413 -0.7691738797073083 -0.47762667598627845
v -0.375 -0.8125 -0.375
v -0.3750000000832071 -0.8124999998665531 -0.3749999994212817
v -0.3749999999991267 -0.8124999998777802 -0.37499999948105267
v -0.3750000000701228 -0.8124999998875375 -0.37499999951228496
v -0.3750000003019627 -0.8124999998947547 -0.3749999996515165
v -0.3750000004062728 -0.8124999997743078 -0.37499999914251436
v -0.375 -0.5191738797073083 -0.375
v -0.33431245540636717 -0.8492848011356944 -0.3749999997504596
f 12 11 22
f 11 13 22
f 13 14 23
f 24 25 22
f 24 22 13
f 13 23 24
f 23 14 15
f 15 26 27
f 15 27 23
f 26 22 25
f 26 15 16
f 16 22 26
f 16 17 22
f 17 18 22
f 18 19 22
f 19 20 22
f 20 21 22
f 12 22 21
f 27 5 6
f 27 6 3
f 24 23 27
f 3 2 24
f 3 24 27
f 4 5 27
f 8 4 27
f 9 8 27
f 27 26 9
f 7 9 26
f 10 7 26
f 26 25 24
f 1 10 26
f 24 2 1
f 1 26 24
f 11 12 28
f 13 11 28
f 14 13 28
f 15 14 28
f 16 15 28
f 17 16 28
f 18 17 28
f 19 18 28
f 20 19 28
f 21 20 28
f 12 21 28
f 6 5 29
f 3 6 29
f 2 3 29
f 1 2 29
f 10 1 29
f 7 10 29
f 9 7 29
f 8 9 29
f 4 8 29
f 5 4 29
";

/// A closed mesh of rings joined by strips: an hourglass whose waist is a neck of specks.
/// `rings` are closed loops of points, in one angular order about the z axis; each pair of
/// consecutive rings is joined by a strip of triangles, the first and last closed by a fan
/// from their centroid. Every triangle faces away from the axis (strips) or along ∓z (the
/// first ring's fan up, the last's down).
fn hourglass(rings: &[Vec<DVec3>]) -> Mesh {
    let mut positions: Vec<DVec3> = Vec::new();
    let mut starts = Vec::new();
    for ring in rings {
        starts.push(positions.len() as u32);
        positions.extend_from_slice(ring);
    }
    let angle = |p: DVec3| p.y.atan2(p.x).rem_euclid(std::f64::consts::TAU);
    let mut triangles: Vec<[u32; 3]> = Vec::new();
    let mut push = |t: [u32; 3], positions: &[DVec3], out: DVec3| {
        let [a, b, c] = t.map(|i| positions[i as usize]);
        let n = (b - a).cross(c - a);
        triangles.push(if n.dot(out) > 0.0 {
            t
        } else {
            [t[0], t[2], t[1]]
        });
    };
    for (k, pair) in rings.windows(2).enumerate() {
        let (s, t) = (starts[k], starts[k + 1]);
        let (n, m) = (pair[0].len(), pair[1].len());
        let (mut i, mut j) = (0, 0);
        while i < n || j < m {
            let next_i = (i < n).then(|| {
                angle(pair[0][(i + 1) % n])
                    + if i + 1 == n {
                        std::f64::consts::TAU
                    } else {
                        0.0
                    }
            });
            let next_j = (j < m).then(|| {
                angle(pair[1][(j + 1) % m])
                    + if j + 1 == m {
                        std::f64::consts::TAU
                    } else {
                        0.0
                    }
            });
            let tri = if next_j.is_none() || next_i.is_some_and(|a| a <= next_j.unwrap()) {
                i += 1;
                [s + (i - 1) as u32, s + (i % n) as u32, t + (j % m) as u32]
            } else {
                j += 1;
                [t + (j - 1) as u32, t + (j % m) as u32, s + (i % n) as u32]
            };
            let c = tri.map(|v| positions[v as usize]).iter().sum::<DVec3>() / 3.0;
            push(tri, &positions, DVec3::new(c.x, c.y, 0.0));
        }
    }
    for (ring, start, up) in [
        (0, starts[0], 1.0),
        (rings.len() - 1, *starts.last().unwrap(), -1.0),
    ] {
        let centre = rings[ring].iter().sum::<DVec3>() / rings[ring].len() as f64;
        let c = positions.len() as u32;
        positions.push(centre);
        let n = rings[ring].len() as u32;
        for i in 0..n {
            push(
                [c, start + i, start + (i + 1) % n],
                &positions,
                DVec3::Z * up,
            );
        }
    }
    let sources = vec![0; triangles.len()];
    Mesh {
        positions,
        triangles,
        sources,
    }
}

/// A neck of specks (two rings of three, 10⁻⁷ across) between a cone over a hexagon 2 across
/// and a cone over a thin triangle 2·10⁻⁵ long and 4·10⁻⁷ wide, 10⁻⁵ below: the cut splits
/// off the small cone as a tetrahedron of its own, whose thin faces are needles by the whole
/// shell's diagonal (about 3) but not by its own (2·10⁻⁵).
#[test]
fn a_neck_cut_that_splits_off_a_small_shell() {
    let ring = |n: usize, r: f64, z: f64, turn: f64| -> Vec<DVec3> {
        (0..n)
            .map(|i| {
                let a = turn + std::f64::consts::TAU * i as f64 / n as f64;
                DVec3::new(r * a.cos(), r * a.sin(), z)
            })
            .collect()
    };
    let (l, w, h) = (1e-5, 2e-7, 1e-5);
    let small = vec![
        DVec3::new(l, 0.0, -h),
        DVec3::new(-l, w, -h),
        DVec3::new(-l, -w, -h),
    ];
    let mut mesh = hourglass(&[
        ring(6, 1.0, 1.0, 0.1),
        ring(3, 1e-7, 1e-7, 0.3),
        ring(3, 1e-7, -1e-7, 0.5),
        small,
    ]);
    let before = mesh.report();
    assert!(
        before.is_closed_manifold() && before.needles > 0,
        "{before}"
    );
    let volume = mesh.volume();
    let left = remove_needles(&mut mesh, None, None);
    let report = mesh.report();
    assert!(
        report.is_closed_manifold() && report.needles == 0 && left == 0,
        "{report}"
    );
    // Two shells, the small cone a tetrahedron of volume, not folded flat; the volume kept.
    assert_eq!(report.shells.len(), 2, "{report}");
    assert!(
        report
            .shells
            .iter()
            .all(|s| s.triangles >= 4 && s.volume > 0.0),
        "{report}"
    );
    assert!((mesh.volume() - volume).abs() < 1e-15 * volume);
}

/// Where a box's face and another box's face turned 9.6e-5 rad nearly touch (the fuzz input
/// `union_slit_tip_needle_turned_1e-4_rad`, step 1, as it enters the pass): a slit between
/// them, 3.2e-10 wide where it ends on a third box's face in a needle 9.4e-6 long (vertices 15,
/// 16, 17 here, 1-based), whose apex 17 has valence three. The needle's short edge 15–16 fails
/// the link condition (its ends share 17, 21 and 28): the collapse would turn 17's two other
/// triangles (32 and 56), one on each face of the slit, into one triangle both ways round. The
/// collapse (either way) deletes them with 17, closing the slit's tip, and keeps the volume
/// and the topology; stretching the needle instead widened the slit by 4.8e-9 of volume.
#[test]
fn a_slit_tip_closes_by_a_collapse_deleting_its_apex() {
    let mut mesh = read(SLIT_TIP);
    let before = mesh.report();
    assert!(
        before.is_closed_manifold() && before.needles > 0,
        "{before}"
    );
    let work = super::work::Work::new(mesh.clone(), f64::INFINITY);
    assert!(matches!(
        work.plan(10),
        Some(super::Op::Collapse {
            from: 14 | 15,
            to: 14 | 15,
            cap: Some([31 | 55, 31 | 55]),
            ..
        })
    ));
    removes_every_needle_keeping_the_volume(&mut mesh);
    let after = mesh.report();
    assert_eq!(
        (after.shells.len(), after.genus),
        (before.shells.len(), before.genus)
    );
}

const SLIT_TIP: &str = "
v -3.125e-1 -1.1875e0 1.875e-1
v -3.125e-1 -1.1875e0 -1.1875e0
v -3.125e-1 1.875e-1 -1.1875e0
v -3.125e-1 1.875e-1 1.875e-1
v -6.25e-1 -4.375e-1 -5.625e-1
v -6.25e-1 -5.625e-1 -5.625e-1
v -6.25e-1 -5.625e-1 -4.375e-1
v -6.25e-1 -4.375e-1 -4.375e-1
v -4.375e-1 -1.1875e0 -1.1875e0
v -4.375e-1 1.875e-1 -1.1875e0
v -4.375e-1 1.875e-1 1.875e-1
v -4.375e-1 -1.1875e0 1.875e-1
v -5.625000004596581e-1 -5.625e-1 -5.625e-1
v -5.624957822476947e-1 -5.625e-1 -4.375e-1
v -4.375000003173378e-1 -5.625e-1 -5.625e-1
v -4.375e-1 -5.625e-1 -5.625e-1
v -4.375e-1 -5.625e-1 -5.624905961987774e-1
v -5.624999996826622e-1 -4.375e-1 -4.375e-1
v -5.625042178946255e-1 -4.375e-1 -5.625e-1
v -4.375e-1 -4.375e-1 -4.3751362123664117e-1
v -4.375e-1 -4.375e-1 -5.625e-1
v -4.375042177523052e-1 -4.375e-1 -5.625e-1
v -4.375e-1 -1.1875e0 -7.499449397086122e-1
v -4.375e-1 -1.1875e0 -5.253275255690423e-1
v -4.3747765903740704e-1 -1.1875e0 -5.253365909299998e-1
v -4.3748523860241484e-1 -1.1875e0 -7.499449402067044e-1
v -4.375e-1 -2.499747357518016e-1 -2.50022899198896e-1
v -4.375e-1 -7.500252646744756e-1 -7.49981318662324e-1
v -4.375e-1 -1.187477100407468e0 -2.4994493959946196e-1
v -5.625316334727665e-1 1.8747709934017087e-1 -7.500550593330445e-1
v -5.62514762027813e-1 1.8751867768816177e-1 -2.5005506134644917e-1
v -4.3751476217013335e-1 1.8752289512312448e-1 -2.500592795584077e-1
v -4.375316336150868e-1 1.8748131677513347e-1 -7.50059277545003e-1
v -5.624683663849133e-1 -1.1874813167751335e0 -2.49940722454997e-1
v -5.624852378298667e-1 -1.1875228951231245e0 -7.499407204415923e-1
v -4.3748523797218697e-1 -1.1875186776881619e0 -7.499449386535508e-1
f 1 2 3
f 3 4 1
f 5 6 7
f 7 8 5
f 2 9 10
f 10 3 2
f 11 12 1
f 1 4 11
f 13 14 7
f 6 13 7
f 15 16 17
f 8 18 19
f 5 8 19
f 20 21 22
f 19 13 6
f 6 5 19
f 15 22 21
f 21 16 15
f 7 14 18
f 7 18 8
f 23 9 2
f 1 12 24
f 1 24 25
f 2 1 25
f 2 25 26
f 2 26 23
f 3 10 11
f 11 4 3
f 27 11 10
f 21 27 10
f 16 21 10
f 28 17 16
f 28 16 10
f 28 10 9
f 28 9 23
f 11 27 29
f 11 29 12
f 29 24 12
f 27 21 20
f 30 31 32
f 30 32 33
f 13 19 30
f 34 14 13
f 13 30 35
f 34 13 35
f 31 30 19
f 31 19 18
f 31 18 14
f 31 14 34
f 36 26 25
f 33 32 27
f 33 27 20
f 33 20 22
f 28 33 22
f 28 22 15
f 15 17 28
f 35 36 25
f 24 29 34
f 24 34 35
f 35 25 24
f 23 26 36
f 30 33 28
f 35 30 28
f 35 28 23
f 35 23 36
f 27 32 31
f 34 29 27
f 31 34 27
";
