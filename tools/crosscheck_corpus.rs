//! Writes the corpus of the manifold3d cross-check (`tests/crosscheck/crosscheck.py`).
//!
//! ```text
//! cargo run --release --example crosscheck_corpus -- OUT_DIR [--models DIR] [--quick]
//! ```
//!
//! For every case both input meshes are written as OBJ (losslessly), read back with
//! `read_mesh` and turned into solids with `Solid::from_mesh`, so the boolean runs on exactly the
//! meshes manifold3d will load. The result goes to `OUT_DIR/out/<id>.obj`, and
//! `OUT_DIR/manifest.json` lists every case with what our own `Mesh::report` says about it.
//!
//! Cases: pairs of primitives in random rigid motions and in axis-aligned (dyadic, so exact
//! in float32) placements that make faces coincide or touch; the analytic cases with known
//! volume and area; A ∪ A, A ∩ A, A − A; and, when the shared models are found (`--models`
//! or the environment variable `BSPCSG_MODELS`), the real meshes with moved copies of
//! themselves, with primitives cutting through them, with themselves, and in their given
//! pairs; and solids touching along an edge or at a corner, as operands and as results.
//! `--quick` keeps a handful of cases per category (for trying the harness).
//!
//! The random numbers come from a fixed-seed LCG, so the corpus is the same on every run.

use std::collections::HashMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use bspcsg::glam::{DAffine3, DQuat, DVec3};
use bspcsg::{BoolOp, Mesh, Solid, read_mesh, write_mesh};
use serde_json::{Value, json};

/// The models README's reference results.
const HAVOC_UNION: f64 = 3.05989e6;
const HAVOC_INTERSECTION: f64 = 68524.4;
const CRAY_LEFT_VOLUME: f64 = 1.95686465e12;
const CRAY_LEFT_MINUS_RIGHT: f64 = 9.82418622e11;
/// Half a unit in the last digit the models README prints for each of the values above.
const HAVOC_UNION_ROUNDING: f64 = 5.0;
const HAVOC_INTERSECTION_ROUNDING: f64 = 0.05;
const CRAY_ROUNDING: f64 = 5e3 + 500.0;

/// The shared models the cross-check uses, by file stem.
const MODELS: [&str; 7] = [
    "spot",
    "fandisk",
    "rocker-arm",
    "Havocglass8_left",
    "Havocglass8_right",
    "Cray_left",
    "Cray_right",
];

/// A deterministic generator (Knuth's MMIX LCG, top 53 bits).
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }

    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }

    fn int(&mut self, lo: u32, hi: u32) -> u32 {
        lo + ((hi - lo + 1) as f64 * self.next()) as u32
    }

    fn unit(&mut self) -> DVec3 {
        loop {
            let v = DVec3::new(
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
            );
            let l = v.length();
            if l > 0.1 && l <= 1.0 {
                return v / l;
            }
        }
    }
}

/// A rigid motion, recorded so a case can be reproduced.
#[derive(Clone, Copy)]
struct Motion {
    axis: DVec3,
    degrees: f64,
    offset: DVec3,
}

impl Motion {
    const IDENTITY: Motion = Motion {
        axis: DVec3::Y,
        degrees: 0.0,
        offset: DVec3::ZERO,
    };

    fn shift(offset: DVec3) -> Motion {
        Motion {
            offset,
            ..Motion::IDENTITY
        }
    }

    fn random(rng: &mut Lcg, reach: f64) -> Motion {
        Motion {
            axis: rng.unit(),
            degrees: rng.range(0.0, 360.0),
            offset: DVec3::new(
                rng.range(-reach, reach),
                rng.range(-reach, reach),
                rng.range(-reach, reach),
            ),
        }
    }

    /// Rotation about the origin, then the offset.
    fn affine(&self) -> DAffine3 {
        DAffine3::from_translation(self.offset)
            * DAffine3::from_quat(DQuat::from_axis_angle(self.axis, self.degrees.to_radians()))
    }

    /// Rotation about `centre`, then the offset.
    fn affine_about(&self, centre: DVec3) -> DAffine3 {
        DAffine3::from_translation(centre + self.offset)
            * DAffine3::from_quat(DQuat::from_axis_angle(self.axis, self.degrees.to_radians()))
            * DAffine3::from_translation(-centre)
    }

    fn describe(&self) -> String {
        if self.degrees == 0.0 && self.offset == DVec3::ZERO {
            return String::new();
        }
        let mut s = String::new();
        if self.degrees != 0.0 {
            let a = self.axis;
            let _ = write!(
                s,
                " .rotate_axis_angle(DVec3::new({:?}, {:?}, {:?}), {:?})",
                a.x, a.y, a.z, self.degrees
            );
        }
        if self.offset != DVec3::ZERO {
            let o = self.offset;
            let _ = write!(
                s,
                " .translate(DVec3::new({:?}, {:?}, {:?}))",
                o.x, o.y, o.z
            );
        }
        s
    }
}

/// The primitive families of the pairs.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Kind {
    Box,
    Sphere,
    Cylinder,
    Cone,
    Torus,
}

const KINDS: [Kind; 5] = [
    Kind::Box,
    Kind::Sphere,
    Kind::Cylinder,
    Kind::Cone,
    Kind::Torus,
];

/// A primitive's constructor call, kept as text for reproductions.
struct Primitive {
    solid: Solid,
    call: String,
}

fn primitive(call: String, solid: bspcsg::Result<Solid>) -> Primitive {
    Primitive {
        solid: solid.unwrap_or_else(|e| panic!("{call}: {e}")),
        call,
    }
}

fn cuboid(x: f64, y: f64, z: f64) -> Primitive {
    primitive(
        format!("Solid::cuboid(DVec3::new({x:?}, {y:?}, {z:?}))"),
        Solid::cuboid(DVec3::new(x, y, z)),
    )
}

fn sphere(r: f64, seg: u32, rings: u32) -> Primitive {
    primitive(
        format!("Solid::sphere({r:?}, {seg}, {rings})"),
        Solid::sphere(r, seg, rings),
    )
}

fn cylinder(r: f64, h: f64, seg: u32) -> Primitive {
    primitive(
        format!("Solid::cylinder({r:?}, {h:?}, {seg})"),
        Solid::cylinder(r, h, seg),
    )
}

fn frustum(r0: f64, r1: f64, h: f64, seg: u32) -> Primitive {
    if r1 == 0.0 {
        primitive(
            format!("Solid::cone({r0:?}, {h:?}, {seg})"),
            Solid::cone(r0, h, seg),
        )
    } else {
        primitive(
            format!("Solid::frustum({r0:?}, {r1:?}, {h:?}, {seg})"),
            Solid::frustum(r0, r1, h, seg),
        )
    }
}

fn torus(major: f64, minor: f64, seg: u32, rings: u32) -> Primitive {
    primitive(
        format!("Solid::torus({major:?}, {minor:?}, {seg}, {rings})"),
        Solid::torus(major, minor, seg, rings),
    )
}

/// A primitive of `kind` with random size (about unit) and 12–48 segments.
fn random_primitive(kind: Kind, rng: &mut Lcg) -> Primitive {
    let seg = rng.int(12, 48);
    match kind {
        Kind::Box => cuboid(
            rng.range(0.6, 1.6),
            rng.range(0.6, 1.6),
            rng.range(0.6, 1.6),
        ),
        Kind::Sphere => sphere(rng.range(0.5, 0.9), seg, (seg / 2).max(6)),
        Kind::Cylinder => cylinder(rng.range(0.3, 0.7), rng.range(0.8, 1.6), seg),
        Kind::Cone => {
            let r0 = rng.range(0.4, 0.8);
            let r1 = if rng.next() < 0.5 {
                0.0
            } else {
                rng.range(0.1, 0.35)
            };
            frustum(r0, r1, rng.range(0.8, 1.6), seg)
        }
        Kind::Torus => torus(
            rng.range(0.5, 0.8),
            rng.range(0.15, 0.3),
            seg,
            rng.int(8, 24),
        ),
    }
}

/// A primitive of `kind` with dyadic sizes (exact in float32), axis-aligned at the origin; the
/// same `k` gives the same shape, so same-kind pairs have coincident faces.
fn dyadic_primitive(kind: Kind, k: u32) -> Primitive {
    let s = f64::from(k) / 8.0;
    match kind {
        Kind::Box => cuboid(s, s, s),
        Kind::Sphere => sphere(s / 2.0, 24, 12),
        Kind::Cylinder => cylinder(s / 2.0, s, 24),
        Kind::Cone => frustum(s / 2.0, s / 4.0, s, 24),
        Kind::Torus => torus(s / 2.0, s / 8.0, 24, 12),
    }
}

/// One input of a case: a mesh and how it was made.
struct Operand {
    name: String,
    mesh: Mesh,
    describe: String,
}

fn from_primitive(name: String, p: Primitive, motion: Motion) -> Operand {
    let solid = p
        .solid
        .transform(motion.affine())
        .unwrap_or_else(|e| panic!("{}: {e}", p.call));
    Operand {
        name,
        mesh: solid.to_mesh(),
        describe: format!("{}{}", p.call, motion.describe()),
    }
}

fn moved_mesh(mesh: &Mesh, map: DAffine3) -> Mesh {
    let mut m = mesh.clone();
    for p in &mut m.positions {
        *p = map.transform_point3(*p);
    }
    m
}

/// A case before it is run.
struct Case {
    id: String,
    category: &'static str,
    op: BoolOp,
    a: std::rc::Rc<Operand>,
    b: std::rc::Rc<Operand>,
    /// Known result volume and area (area may be unknown), with where they come from.
    expect: Option<Known>,
}

/// A known result: volume, area where known, where it comes from, and how far a value printed
/// with few digits may be from the true one (half a unit in its last digit; zero if exact).
#[derive(Clone, Copy)]
struct Known {
    volume: f64,
    area: Option<f64>,
    source: &'static str,
    rounding: f64,
}

/// A result known to full precision.
fn known(volume: f64, area: Option<f64>, source: &'static str) -> Option<Known> {
    Some(Known {
        volume,
        area,
        source,
        rounding: 0.0,
    })
}

fn op_name(op: BoolOp) -> &'static str {
    match op {
        BoolOp::Union => "union",
        BoolOp::Intersection => "intersection",
        BoolOp::Difference => "difference",
    }
}

const OPS: [BoolOp; 3] = [BoolOp::Union, BoolOp::Intersection, BoolOp::Difference];

struct Corpus {
    cases: Vec<Case>,
}

impl Corpus {
    fn push(
        &mut self,
        category: &'static str,
        op: BoolOp,
        a: &std::rc::Rc<Operand>,
        b: &std::rc::Rc<Operand>,
        expect: Option<Known>,
    ) {
        let id = format!("{category}-{:04}", self.cases.len());
        self.cases.push(Case {
            id,
            category,
            op,
            a: a.clone(),
            b: b.clone(),
            expect,
        });
    }
}

fn rc(o: Operand) -> std::rc::Rc<Operand> {
    std::rc::Rc::new(o)
}

/// The operand with its coordinates rounded to float32 (see `float32_exact`).
fn rounded(mut o: Operand) -> Operand {
    o.mesh = float32_exact(&o.mesh);
    o.describe.push_str(", coordinates rounded to float32");
    o
}

/// Random pairs: every ordered pair of kinds, every op, `motions` random placements. With
/// `float32`, the inputs' coordinates are rounded to float32, as STL and glTF files store them
/// (a tessellated flat face then becomes triangles that are coplanar only up to rounding).
fn primitive_pairs(corpus: &mut Corpus, motions: usize, float32: bool) {
    let (category, seed, prefix) = if float32 {
        ("prim-f32", 0x5eed_0004, "f32pair")
    } else {
        ("prim-random", 0x5eed_0001, "pair")
    };
    let mut rng = Lcg(seed);
    let mut n = 0;
    for ka in KINDS {
        for kb in KINDS {
            for _ in 0..motions {
                n += 1;
                let pa = random_primitive(ka, &mut rng);
                let pb = random_primitive(kb, &mut rng);
                let ma = Motion::random(&mut rng, 0.15);
                let mb = Motion::random(&mut rng, 0.5);
                let mut a = from_primitive(format!("{prefix}{n:03}_a"), pa, ma);
                let mut b = from_primitive(format!("{prefix}{n:03}_b"), pb, mb);
                if float32 {
                    (a, b) = (rounded(a), rounded(b));
                }
                let (a, b) = (rc(a), rc(b));
                for op in OPS {
                    corpus.push(category, op, &a, &b, None);
                }
            }
        }
    }
}

/// Axis-aligned pairs with dyadic sizes and offsets: coincident and touching faces.
fn aligned_pairs(corpus: &mut Corpus) {
    let mut n = 0;
    for (ia, ka) in KINDS.into_iter().enumerate() {
        for (ib, kb) in KINDS.into_iter().enumerate() {
            // Along Y (the round primitives' axis): same sizes, half a size up, so caps and
            // side faces coincide. Along X: B a bit smaller, shifted so a side face touches
            // or crosses A's.
            let variants = [
                (8, 8, DVec3::new(0.0, 0.5, 0.0)),
                (
                    8,
                    6,
                    DVec3::new(0.125 * (1 + (ia + ib) % 4) as f64, 0.0, 0.0),
                ),
            ];
            for (ka_size, kb_size, offset) in variants {
                n += 1;
                let a = rc(from_primitive(
                    format!("aligned{n:03}_a"),
                    dyadic_primitive(ka, ka_size),
                    Motion::IDENTITY,
                ));
                let b = rc(from_primitive(
                    format!("aligned{n:03}_b"),
                    dyadic_primitive(kb, kb_size),
                    Motion::shift(offset),
                ));
                for op in OPS {
                    corpus.push("prim-aligned", op, &a, &b, None);
                }
            }
        }
    }
}

/// Solids that touch along an edge or at a point, as operands and as results: the writer gives
/// each solid its own vertices there (manifold3d loads them by index) and `read_mesh` pairs the
/// faces around a shared edge by angle, so such files are closed solids both ways.
fn touching(corpus: &mut Corpus) {
    let unit = Solid::cuboid(DVec3::ONE).expect("a unit box");
    // The unit box whose lowest corner is `at`.
    let cell = |at: [f64; 3]| {
        unit.clone()
            .translate(DVec3::from(at) + 0.5)
            .expect("a placed box")
    };
    let operand = |name: &str, solid: Solid, describe: &str| {
        rc(Operand {
            name: name.to_owned(),
            mesh: solid.to_mesh(),
            describe: describe.to_owned(),
        })
    };
    let a = operand("touch_cube", cell([0.0; 3]), "cuboid(1) at [0,1]³");
    let edge = operand(
        "touch_cube_edge",
        cell([1.0, 1.0, 0.0]),
        "cuboid(1) at [1,2]²×[0,1] (an edge on the first's)",
    );
    let vertex = operand(
        "touch_cube_vertex",
        cell([1.0; 3]),
        "cuboid(1) at [1,2]³ (a corner on the first's)",
    );
    for b in [&edge, &vertex] {
        corpus.push(
            "touching",
            BoolOp::Union,
            &a,
            b,
            known(2.0, Some(12.0), "analytic"),
        );
    }
    // Four unit boxes of [0,2]³ in a checkerboard, one file whose every inner edge has four
    // faces; a box across its centre takes an eighth of each.
    let cells = [[0.0; 3], [1.0, 1.0, 0.0], [1.0, 0.0, 1.0], [0.0, 1.0, 1.0]];
    let checker = operand(
        "touch_checker",
        Solid::union_all(cells.map(cell)),
        "unit boxes at [0,0,0], [1,1,0], [1,0,1], [0,1,1] (a 2×2×2 checkerboard)",
    );
    let middle = operand(
        "touch_middle",
        unit.clone().translate(DVec3::ONE).expect("a placed box"),
        "cuboid(1) at [0.5,1.5]³",
    );
    for (op, volume) in [
        (BoolOp::Union, 4.5),
        (BoolOp::Intersection, 0.5),
        (BoolOp::Difference, 3.5),
    ] {
        corpus.push(
            "touching",
            op,
            &checker,
            &middle,
            known(volume, None, "analytic"),
        );
    }
    // A cube less itself turned 10⁻³° about (0.3, 1, 0.2): slivers touching along edges.
    let axis = DVec3::new(0.3, 1.0, 0.2).normalize();
    let turned = operand(
        "touch_cube_turned",
        unit.clone()
            .rotate(DQuat::from_axis_angle(axis, 1e-3_f64.to_radians()))
            .and_then(|s| s.translate(DVec3::splat(0.5)))
            .expect("a turned box"),
        "cuboid(1) at [0,1]³ turned 1e-3° about (0.3, 1, 0.2) through its centre",
    );
    corpus.push("touching", BoolOp::Difference, &a, &turned, None);
}

/// The core issue's analytic cases, disjoint unions and spheres.
fn analytic(corpus: &mut Corpus) {
    let op = |name: &str, p: Primitive, m: Motion| rc(from_primitive(name.to_owned(), p, m));
    let cube = |s: f64| cuboid(s, s, s);
    let x = |d: f64| Motion::shift(DVec3::new(d, 0.0, 0.0));

    // [0,1]³ ∪ [1,2]×[0,1]²: volume 2, area 10.
    let a = op("cube1_corner", cube(1.0), Motion::shift(DVec3::splat(0.5)));
    let b = op(
        "cube1_corner_x1",
        cube(1.0),
        Motion::shift(DVec3::new(1.5, 0.5, 0.5)),
    );
    corpus.push(
        "analytic",
        BoolOp::Union,
        &a,
        &b,
        known(2.0, Some(10.0), "analytic"),
    );

    // Centred cube(1) and the same moved +0.5 in x.
    let a = op("cube1", cube(1.0), Motion::IDENTITY);
    let b = op("cube1_x05", cube(1.0), x(0.5));
    corpus.push(
        "analytic",
        BoolOp::Union,
        &a,
        &b,
        known(1.5, Some(8.0), "analytic"),
    );
    corpus.push(
        "analytic",
        BoolOp::Difference,
        &a,
        &b,
        known(0.5, Some(4.0), "analytic"),
    );
    corpus.push(
        "analytic",
        BoolOp::Intersection,
        &a,
        &b,
        known(0.5, Some(4.0), "analytic"),
    );

    // cube(2) − cube(1) sharing the corner (1,1,1): volume 7, area 24.
    let big = op("cube2", cube(2.0), Motion::IDENTITY);
    let corner = op(
        "cube1_at_corner",
        cube(1.0),
        Motion::shift(DVec3::splat(0.5)),
    );
    corpus.push(
        "analytic",
        BoolOp::Difference,
        &big,
        &corner,
        known(7.0, Some(24.0), "analytic"),
    );

    // Disjoint: unions add, intersections are empty, differences keep A.
    let far = op("cube1_x3", cube(1.0), x(3.0));
    corpus.push(
        "analytic",
        BoolOp::Union,
        &a,
        &far,
        known(2.0, Some(12.0), "analytic"),
    );
    corpus.push(
        "analytic",
        BoolOp::Intersection,
        &a,
        &far,
        known(0.0, Some(0.0), "analytic"),
    );
    corpus.push(
        "analytic",
        BoolOp::Difference,
        &a,
        &far,
        known(1.0, Some(6.0), "analytic"),
    );
    let s = op("sphere1", sphere(1.0, 32, 16), Motion::IDENTITY);
    let s_far = op("sphere1_x3", sphere(1.0, 32, 16), x(3.0));
    let (vs, as_) = (s.mesh.volume(), s.mesh.area());
    let sum = known(2.0 * vs, Some(2.0 * as_), "sum of the inputs");
    corpus.push("analytic", BoolOp::Union, &s, &s_far, sum);
    let t = op("torus1", torus(1.0, 0.25, 32, 16), Motion::IDENTITY);
    let t_far = op("torus1_x3", torus(1.0, 0.25, 32, 16), x(3.0));
    let (vt, at) = (t.mesh.volume(), t.mesh.area());
    let sum = known(2.0 * vt, Some(2.0 * at), "sum of the inputs");
    corpus.push("analytic", BoolOp::Union, &t, &t_far, sum);
    let sum = known(vt + 1.0, Some(at + 6.0), "sum of the inputs");
    corpus.push("analytic", BoolOp::Union, &t, &far, sum);

    // Spheres: overlapping, nested (a cavity), containing.
    let s_half = op("sphere1_x05", sphere(1.0, 32, 16), x(0.5));
    for o in OPS {
        corpus.push("analytic", o, &s, &s_half, None);
    }
    let inner = op("sphere05", sphere(0.5, 24, 12), Motion::IDENTITY);
    let (vi, ai) = (inner.mesh.volume(), inner.mesh.area());
    let cavity = known(vs - vi, Some(as_ + ai), "outer minus inner");
    corpus.push("analytic", BoolOp::Difference, &s, &inner, cavity);
    let outer = known(vs, Some(as_), "the outer sphere");
    corpus.push("analytic", BoolOp::Union, &s, &inner, outer);
    let inner_only = known(vi, Some(ai), "the inner sphere");
    corpus.push("analytic", BoolOp::Intersection, &s, &inner, inner_only);
    corpus.push(
        "analytic",
        BoolOp::Difference,
        &inner,
        &s,
        known(0.0, Some(0.0), "empty"),
    );
    let rotated = op(
        "sphere1_rot",
        sphere(1.0, 32, 16),
        Motion {
            axis: DVec3::new(1.0, 2.0, 3.0).normalize(),
            degrees: 17.0,
            offset: DVec3::ZERO,
        },
    );
    for o in OPS {
        corpus.push("analytic", o, &s, &rotated, None);
    }
}

/// A ∪ A, A ∩ A and A − A for each kind, as made and in a random motion.
fn self_ops(corpus: &mut Corpus) {
    let mut rng = Lcg(0x5eed_0002);
    for kind in KINDS {
        for moved in [false, true] {
            let p = random_primitive(kind, &mut rng);
            let m = if moved {
                Motion::random(&mut rng, 1.0)
            } else {
                Motion::IDENTITY
            };
            let name = format!("self_{kind:?}_{}", if moved { "moved" } else { "plain" });
            let a = rc(from_primitive(name.to_lowercase(), p, m));
            self_cases(corpus, "self", &a);
        }
    }
}

fn self_cases(corpus: &mut Corpus, category: &'static str, a: &std::rc::Rc<Operand>) {
    let (v, ar) = (a.mesh.volume(), a.mesh.area());
    corpus.push(category, BoolOp::Union, a, a, known(v, Some(ar), "A"));
    corpus.push(
        category,
        BoolOp::Intersection,
        a,
        a,
        known(v, Some(ar), "A"),
    );
    corpus.push(
        category,
        BoolOp::Difference,
        a,
        a,
        known(0.0, Some(0.0), "empty"),
    );
}

/// The shared models: with moved copies, primitives, themselves, and their given pairs.
fn models(corpus: &mut Corpus, dir: &Path) -> Result<(), String> {
    let mut rng = Lcg(0x5eed_0003);
    let mut loaded: HashMap<&str, std::rc::Rc<Operand>> = HashMap::new();
    for name in MODELS {
        let path = dir.join(format!("{name}.obj"));
        let mesh = read_mesh(&path).map_err(|e| format!("{}: {e}", path.display()))?;
        loaded.insert(
            name,
            rc(Operand {
                name: name.to_owned(),
                mesh,
                describe: format!("read_mesh(\"$BSPCSG_MODELS/{name}.obj\")"),
            }),
        );
    }
    for name in MODELS {
        let a = loaded[name].clone();
        let bbox = a.mesh.bbox();
        let huge = bbox.max_abs() > 1e30;
        self_cases(corpus, "model-self", &a);

        // Moved copies: rotated about the box centre and shifted by a fraction of the box.
        // The huge box (Cray_right reaches ±f32::MAX) moves only up, so that it stays finite
        // in float32 and its moved copy contains it but for a slab.
        let motions: Vec<Motion> = if huge {
            vec![Motion::shift(DVec3::new(0.0, 0.0, 1000.0))]
        } else {
            (0..2)
                .map(|_| {
                    let mut m = Motion::random(&mut rng, 0.15 * bbox.diagonal());
                    m.degrees = rng.range(8.0, 35.0);
                    m
                })
                .collect()
        };
        for (k, m) in motions.iter().enumerate() {
            let b = rc(Operand {
                name: format!("{name}_moved{k}"),
                mesh: moved_mesh(&a.mesh, m.affine_about(bbox.center())),
                describe: format!(
                    "{} moved about its box centre {:?}:{}",
                    a.describe,
                    bbox.center(),
                    m.describe()
                ),
            });
            for op in OPS {
                corpus.push("model-moved", op, &a, &b, None);
            }
            corpus.push("model-moved", BoolOp::Difference, &b, &a, None);
        }

        // Primitives cutting through: sized and placed by the model's box (the huge box gets
        // primitives of Cray_left's size at the middle of its top face).
        let (centre, size) = if huge {
            (DVec3::new(0.0, 0.0, bbox.max.z), DVec3::splat(50000.0))
        } else {
            (bbox.center(), bbox.size())
        };
        let d = size.length();
        let prims = [
            (
                "box",
                cuboid(0.6 * size.x, 0.5 * size.y, 0.7 * size.z),
                Motion {
                    axis: DVec3::new(1.0, 1.0, 0.0).normalize(),
                    degrees: 20.0,
                    offset: centre + 0.3 * size * DVec3::new(1.0, 0.5, -0.5),
                },
            ),
            (
                "sphere",
                sphere(0.3 * d, 32, 16),
                Motion::shift(centre + 0.25 * size * DVec3::new(-1.0, 1.0, 1.0)),
            ),
            (
                "cylinder",
                cylinder(0.12 * d, 1.5 * d, 32),
                Motion {
                    axis: DVec3::new(0.3, 0.0, 1.0).normalize(),
                    degrees: 70.0,
                    offset: centre + 0.05 * size,
                },
            ),
        ];
        for (pname, p, m) in prims {
            let b = rc(from_primitive(format!("{name}_{pname}"), p, m));
            for op in OPS {
                corpus.push("model-prim", op, &a, &b, None);
            }
            corpus.push("model-prim", BoolOp::Difference, &b, &a, None);
        }
    }

    // The given pairs, both ways round, with the README's reference results.
    let (l, r) = (&loaded["Havocglass8_left"], &loaded["Havocglass8_right"]);
    let src = "models README (manifold3d)";
    corpus.push(
        "model-pair",
        BoolOp::Union,
        l,
        r,
        Some(Known {
            rounding: HAVOC_UNION_ROUNDING,
            ..known(HAVOC_UNION, None, src).expect("some")
        }),
    );
    corpus.push(
        "model-pair",
        BoolOp::Union,
        r,
        l,
        Some(Known {
            rounding: HAVOC_UNION_ROUNDING,
            ..known(HAVOC_UNION, None, src).expect("some")
        }),
    );
    let i = Some(Known {
        rounding: HAVOC_INTERSECTION_ROUNDING,
        ..known(HAVOC_INTERSECTION, None, src).expect("some")
    });
    corpus.push("model-pair", BoolOp::Intersection, l, r, i);
    corpus.push("model-pair", BoolOp::Intersection, r, l, i);
    corpus.push("model-pair", BoolOp::Difference, l, r, None);
    corpus.push("model-pair", BoolOp::Difference, r, l, None);

    let (l, r) = (&loaded["Cray_left"], &loaded["Cray_right"]);
    let src = "models README (true volume)";
    let cray = |v: f64, src| {
        Some(Known {
            rounding: CRAY_ROUNDING,
            ..known(v, None, src).expect("some")
        })
    };
    let minus = cray(CRAY_LEFT_MINUS_RIGHT, src);
    corpus.push("model-pair", BoolOp::Difference, l, r, minus);
    let src = "models README: volume(left) − true volume(left − right)";
    let inter = cray(CRAY_LEFT_VOLUME - CRAY_LEFT_MINUS_RIGHT, src);
    corpus.push("model-pair", BoolOp::Intersection, l, r, inter);
    corpus.push("model-pair", BoolOp::Intersection, r, l, inter);
    let src = "models README: volume(right) + true volume(left − right)";
    let union = cray(r.mesh.volume() + CRAY_LEFT_MINUS_RIGHT, src);
    corpus.push("model-pair", BoolOp::Union, l, r, union);
    let src = "models README: volume(right) − (volume(left) − true volume(left − right))";
    let r_minus = r.mesh.volume() - (CRAY_LEFT_VOLUME - CRAY_LEFT_MINUS_RIGHT);
    corpus.push("model-pair", BoolOp::Difference, r, l, cray(r_minus, src));
    Ok(())
}

/// The mesh with every coordinate rounded to the nearest float32.
fn float32_exact(mesh: &Mesh) -> Mesh {
    let mut m = mesh.clone();
    for p in &mut m.positions {
        *p = p.as_vec3().as_dvec3();
    }
    m
}

/// An input written and read back, as the boolean and manifold3d see it.
struct Loaded {
    file: String,
    solid: Result<Solid, String>,
}

fn load(out: &Path, op: &Operand, cache: &mut HashMap<String, Loaded>) -> Result<(), String> {
    if cache.contains_key(&op.name) {
        return Ok(());
    }
    let file = format!("inputs/{}.obj", op.name);
    let path = out.join(&file);
    write_mesh(&path, &op.mesh, &[]).map_err(|e| format!("{}: {e}", path.display()))?;
    let solid = read_mesh(&path)
        .and_then(|m| Solid::from_mesh(&m))
        .map_err(|e| e.to_string());
    cache.insert(op.name.clone(), Loaded { file, solid });
    Ok(())
}

fn run(out: &Path, case: &Case, cache: &mut HashMap<String, Loaded>) -> Result<Value, String> {
    load(out, &case.a, cache)?;
    load(out, &case.b, cache)?;
    let (la, lb) = (&cache[&case.a.name], &cache[&case.b.name]);
    let mut entry = json!({
        "id": case.id,
        "category": case.category,
        "op": op_name(case.op),
        "a": la.file,
        "b": lb.file,
        "a_describe": case.a.describe,
        "b_describe": case.b.describe,
    });
    if let Some(k) = case.expect {
        entry["expect"] = json!({ "volume": k.volume, "area": k.area, "source": k.source, "rounding": k.rounding });
    }
    let (a, b) = match (&la.solid, &lb.solid) {
        (Ok(a), Ok(b)) => (a, b),
        (Err(e), _) | (_, Err(e)) => {
            entry["error"] = json!(format!("input refused by Solid::from_mesh: {e}"));
            return Ok(entry);
        }
    };
    let t0 = Instant::now();
    let result = bspcsg::boolean(a, b, case.op);
    let mesh = result.to_mesh();
    let ms = t0.elapsed().as_secs_f64() * 1e3;
    let file = format!("out/{}.obj", case.id);
    let path = out.join(&file);
    write_mesh(&path, &mesh, &[]).map_err(|e| format!("{}: {e}", path.display()))?;
    let report = mesh.report();
    entry["out"] = json!(file);
    entry["ours"] = json!({
        "volume": mesh.volume(),
        "area": mesh.area(),
        "triangles": mesh.triangle_count(),
        "genus": report.genus,
        "shells": report.shells.len(),
        "closed_manifold": report.is_closed_manifold(),
        "report": report.to_string(),
        "ms": ms,
    });
    Ok(entry)
}

fn main() -> ExitCode {
    let mut args = std::env::args().skip(1);
    let mut out: Option<PathBuf> = None;
    let mut models_dir: Option<PathBuf> = std::env::var_os("BSPCSG_MODELS").map(PathBuf::from);
    let mut quick = false;
    while let Some(arg) = args.next() {
        match arg.as_str() {
            "--models" => models_dir = args.next().map(PathBuf::from),
            "--quick" => quick = true,
            _ if out.is_none() && !arg.starts_with('-') => out = Some(PathBuf::from(arg)),
            _ => {
                eprintln!("usage: crosscheck_corpus OUT_DIR [--models DIR] [--quick]");
                return ExitCode::from(2);
            }
        }
    }
    let Some(out) = out else {
        eprintln!("usage: crosscheck_corpus OUT_DIR [--models DIR] [--quick]");
        return ExitCode::from(2);
    };
    for sub in ["inputs", "out"] {
        if let Err(e) = std::fs::create_dir_all(out.join(sub)) {
            eprintln!("{}: {e}", out.join(sub).display());
            return ExitCode::FAILURE;
        }
    }

    let mut corpus = Corpus { cases: Vec::new() };
    primitive_pairs(&mut corpus, if quick { 1 } else { 5 }, false);
    primitive_pairs(&mut corpus, if quick { 1 } else { 2 }, true);
    aligned_pairs(&mut corpus);
    analytic(&mut corpus);
    self_ops(&mut corpus);
    let models_note = match &models_dir {
        Some(dir) if dir.is_dir() => match models(&mut corpus, dir) {
            Ok(()) => format!("models from {}", dir.display()),
            Err(e) => {
                eprintln!("cannot read the shared models: {e}");
                return ExitCode::FAILURE;
            }
        },
        Some(dir) => format!(
            "SKIPPED the model cases: {} is not a directory",
            dir.display()
        ),
        None => "SKIPPED the model cases: set BSPCSG_MODELS or pass --models DIR".to_owned(),
    };
    // After the models, so the numbering of the cases above stays as it was.
    touching(&mut corpus);
    if quick {
        // A few of each category.
        let mut seen: HashMap<&str, usize> = HashMap::new();
        corpus.cases.retain(|c| {
            let n = seen.entry(c.category).or_default();
            *n += 1;
            *n <= 6
        });
    }
    eprintln!("{models_note}");

    let mut cache = HashMap::new();
    let mut entries = Vec::with_capacity(corpus.cases.len());
    let t0 = Instant::now();
    for case in &corpus.cases {
        match run(&out, case, &mut cache) {
            Ok(e) => entries.push(e),
            Err(e) => {
                eprintln!("{}: {e}", case.id);
                return ExitCode::FAILURE;
            }
        }
    }
    let manifest = json!({
        "generator": concat!("bspcsg ", env!("CARGO_PKG_VERSION"), " tools/crosscheck_corpus.rs"),
        "models": models_note,
        "cases": entries,
    });
    let path = out.join("manifest.json");
    let text = serde_json::to_string_pretty(&manifest).expect("JSON values serialize");
    if let Err(e) = std::fs::write(&path, text) {
        eprintln!("{}: {e}", path.display());
        return ExitCode::FAILURE;
    }
    eprintln!(
        "{} cases written to {} in {:.1} s",
        corpus.cases.len(),
        out.display(),
        t0.elapsed().as_secs_f64()
    );
    ExitCode::SUCCESS
}
