//! Boolean programs decoded from bytes, shared by the `booleans` fuzz target and the
//! regression tests that replay what it found (`tests/fuzz_findings.rs`,
//! `tests/fuzz_findings_files.rs`, `tests/fuzz_forks.rs`, through `tests/common/fuzz_replay.rs`).

use bspcsg::glam::{DQuat, DVec3};
use bspcsg::{Mesh, Solid};

/// Reads the input a byte at a time; zeros once it runs out.
struct Bytes<'a>(&'a [u8]);

impl Bytes<'_> {
    fn byte(&mut self) -> u8 {
        let (&b, rest) = self.0.split_first().unwrap_or((&0, &[]));
        self.0 = rest;
        b
    }
    /// A number in 0..=1.
    fn unit(&mut self) -> f64 {
        u16::from_le_bytes([self.byte(), self.byte()]) as f64 / 65535.0
    }
    fn empty(&self) -> bool {
        self.0.is_empty()
    }
}

/// Grid step for exact placements: multiples of 1/8 are exact in binary.
const STEP: f64 = 0.125;

/// A box of `size` centred at the origin, two triangles a face, as an OBJ file brings it.
pub(crate) fn obj_box(size: DVec3) -> Mesh {
    let p = |i: usize| {
        DVec3::new(
            if i & 1 == 0 { -0.5 } else { 0.5 },
            if i & 2 == 0 { -0.5 } else { 0.5 },
            if i & 4 == 0 { -0.5 } else { 0.5 },
        ) * size
    };
    let quads: [[u32; 4]; 6] = [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ];
    let triangles = quads
        .iter()
        .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
        .collect();
    Mesh::new((0..8).map(p).collect(), triangles)
}

/// One operand: a shape, a size on the grid, a rotation (none, tiny, free) and a placement
/// (on the grid, or free).
fn operand(b: &mut Bytes, tiny: bool) -> Option<Solid> {
    let kind = b.byte() % 4;
    let size = DVec3::new(
        (1 + b.byte() % 12) as f64 * STEP,
        (1 + b.byte() % 12) as f64 * STEP,
        (1 + b.byte() % 12) as f64 * STEP,
    );
    let segments = 3 + (b.byte() % 14) as u32;
    let solid = match kind {
        0 => Solid::cuboid(size).ok()?,
        1 => Solid::from_mesh(&obj_box(size)).ok()?,
        2 => Solid::sphere(0.5 * size.x, segments, segments / 2 + 2).ok()?,
        _ => Solid::cylinder(0.5 * size.x, size.y, segments).ok()?,
    };
    let axis = DVec3::new(b.unit() - 0.5, b.unit() - 0.5, b.unit() - 0.5)
        .try_normalize()
        .unwrap_or(DVec3::Z);
    let turn = b.byte();
    let angle = match turn % 3 {
        1 if !tiny => 0.0,
        0 => 0.0,
        // 1e-2 down to 1e-11 degrees: faces a hair off coplanar.
        1 => (10f64.powi(-2 - (turn / 3 % 10) as i32)).to_radians(),
        _ => b.unit() * std::f64::consts::TAU,
    };
    let solid = if angle == 0.0 {
        solid
    } else {
        solid.rotate(DQuat::from_axis_angle(axis, angle)).ok()?
    };
    let place = b.byte();
    let offset = if place.is_multiple_of(2) {
        DVec3::new(
            (b.byte() % 16) as f64 - 8.0,
            (b.byte() % 16) as f64 - 8.0,
            (b.byte() % 16) as f64 - 8.0,
        ) * (STEP / 2.0)
    } else {
        DVec3::new(b.unit() - 0.5, b.unit() - 0.5, b.unit() - 0.5) * 2.0
    };
    solid.translate(offset).ok()
}

/// Runs the program in `data`, checking every step; the first violation as an error. Without
/// `tiny`, operands the input turns by a tiny angle are not turned at all.
pub fn run(data: &[u8], tiny: bool) -> Result<(), String> {
    let mut b = Bytes(data);
    let Some(mut acc) = operand(&mut b, tiny) else {
        return Ok(());
    };
    for step in 0..6 {
        if b.empty() {
            break;
        }
        let op = b.byte() % 3;
        let Some(next) = operand(&mut b, tiny) else {
            return Ok(());
        };
        let (va, vb) = (acc.volume(), next.volume());
        let result = match op {
            0 => &acc | &next,
            1 => &acc & &next,
            _ => &acc - &next,
        };
        let v = result.volume();
        let slack = 1e-9 * va.max(vb).max(1.0);
        let (lo, hi) = match op {
            0 => (va.max(vb), va + vb),
            1 => (0.0, va.min(vb)),
            _ => (va - vb, va),
        };
        if !(v >= lo - slack && v <= hi + slack) {
            return Err(format!(
                "step {step}: volume {v} outside [{lo}, {hi}] (op {op}, operands {va} and {vb})"
            ));
        }
        let mesh = result.to_mesh();
        let report = mesh.report();
        if !report.is_closed_manifold() || report.needles > 0 {
            return Err(format!("step {step}: {report}"));
        }
        if (mesh.volume() - v).abs() > slack {
            return Err(format!(
                "step {step}: mesh volume {} but the solid's {v}",
                mesh.volume()
            ));
        }
        acc = result;
    }
    Ok(())
}
