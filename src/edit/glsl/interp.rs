//! A tiny interpreter of the generated code, in f64: every helper of `prelude.glsl` written out
//! again line by line, and the statements of [`Code`] run as the printed GLSL runs them. The
//! tests compare it with the scene's own distance and material, so a wrong transform, constant,
//! operand order or helper in the shader fails here rather than on the page.

use glam::{DVec2, DVec3};

use super::ir::{Call, Call2, Code, Combine, Stmt, Stmt2};
use crate::solid::BoolOp;

const EMPTY: f64 = 1e30;

fn max0(v: DVec3) -> DVec3 {
    v.max(DVec3::ZERO)
}

fn sd_box(p: DVec3, h: DVec3) -> f64 {
    let q = p.abs() - h;
    max0(q).length() + q.x.max(q.y.max(q.z)).min(0.0)
}

fn xz(p: DVec3) -> DVec2 {
    DVec2::new(p.x, p.z)
}

fn sd_cylinder(p: DVec3, r: f64, hh: f64) -> f64 {
    let d = DVec2::new(xz(p).length() - r, p.y.abs() - hh);
    d.x.max(d.y).min(0.0) + d.max(DVec2::ZERO).length()
}

fn sd_cone(p: DVec3, h: f64, r1: f64, r2: f64) -> f64 {
    let q = DVec2::new(xz(p).length(), p.y);
    let k1 = DVec2::new(r2, h);
    let k2 = DVec2::new(r2 - r1, 2.0 * h);
    let ca = DVec2::new(
        q.x - q.x.min(if q.y < 0.0 { r1 } else { r2 }),
        q.y.abs() - h,
    );
    let cb = q - k1 + k2 * ((k1 - q).dot(k2) / k2.dot(k2)).clamp(0.0, 1.0);
    let s = if cb.x < 0.0 && ca.y < 0.0 { -1.0 } else { 1.0 };
    s * ca.dot(ca).min(cb.dot(cb)).sqrt()
}

fn sd_pyramid_unit(p: DVec3, h: f64) -> f64 {
    let m2 = h * h + 0.25;
    let (mut x, y, mut z) = (p.x.abs(), p.y, p.z.abs());
    if z > x {
        std::mem::swap(&mut x, &mut z);
    }
    x -= 0.5;
    z -= 0.5;
    let q = DVec3::new(z, h * y - 0.5 * x, h * x + 0.5 * y);
    let s = (-q.x).max(0.0);
    let t = ((q.y - 0.5 * z) / (m2 + 0.25)).clamp(0.0, 1.0);
    let a = m2 * (q.x + s) * (q.x + s) + q.y * q.y;
    let b = m2 * (q.x + 0.5 * t) * (q.x + 0.5 * t) + (q.y - m2 * t) * (q.y - m2 * t);
    let d2 = if q.y.min(-q.x * m2 - q.y * 0.5) > 0.0 {
        0.0
    } else {
        a.min(b)
    };
    let lateral = ((d2 + q.z * q.z) / m2).sqrt();
    if q.z.max(-y) < 0.0 {
        return -lateral.min(y);
    }
    let e = DVec2::new(p.x.abs() - 0.5, p.z.abs() - 0.5).max(DVec2::ZERO);
    lateral.min((e.dot(e) + y * y).sqrt())
}

fn sd_rect(p: DVec2, h: DVec2) -> f64 {
    let q = p.abs() - h;
    q.max(DVec2::ZERO).length() + q.x.max(q.y).min(0.0)
}

fn unplace(p: DVec2, pos: DVec2, cs: DVec2) -> DVec2 {
    let d = p - pos;
    DVec2::new(cs.x * d.x + cs.y * d.y, -cs.y * d.x + cs.x * d.y)
}

fn sd_polygon(v: &[DVec2], p: DVec2) -> f64 {
    let mut d = (p - v[0]).dot(p - v[0]);
    let mut s = 1.0;
    let mut j = v.len() - 1;
    for i in 0..v.len() {
        let e = v[j] - v[i];
        let w = p - v[i];
        let b = w - e * (w.dot(e) / e.dot(e)).clamp(0.0, 1.0);
        d = d.min(b.dot(b));
        let c = [p.y >= v[i].y, p.y < v[j].y, e.x * w.y > e.y * w.x];
        if c.iter().all(|&x| x) || c.iter().all(|&x| !x) {
            s = -s;
        }
        j = i;
    }
    s * d.sqrt()
}

fn extrusion(d2: f64, z: f64, hh: f64) -> f64 {
    let w = DVec2::new(d2, z.abs() - hh);
    w.x.max(w.y).min(0.0) + w.max(DVec2::ZERO).length()
}

fn warped_slice(p: DVec3, hh: f64, twist: f64, scale_top: DVec2) -> DVec3 {
    let t = ((p.z + hh) / (2.0 * hh)).clamp(0.0, 1.0);
    let s = DVec2::ONE.lerp(scale_top, t).max(DVec2::splat(1e-12));
    let a = -(twist * t).to_radians();
    let cs = DVec2::new(a.cos(), a.sin());
    let q = DVec2::new(cs.x * p.x - cs.y * p.y, cs.y * p.x + cs.x * p.y) / s;
    DVec3::new(q.x, q.y, s.x.min(s.y))
}

#[allow(clippy::too_many_arguments)]
fn warped_bound(
    g: f64,
    p: DVec3,
    hh: f64,
    reach: f64,
    slope: DVec3,
    bmin: DVec3,
    bmax: DVec3,
) -> f64 {
    let cap = p.z.abs() - hh;
    let rho = DVec2::new(p.x, p.y).length().max(reach);
    let lz = (slope.x + slope.z) * rho + slope.y;
    let d = (g / (1.0 + lz * lz).sqrt()).max(cap);
    let outside = max0((bmin - p).max(p - bmax)).length();
    if outside > 0.0 { d.max(outside) } else { d }
}

fn revolution(d: f64, p: DVec3, angle: f64) -> f64 {
    if angle >= 360.0 {
        return d;
    }
    let a = angle.to_radians();
    let end = -a.sin() * p.x - a.cos() * p.z;
    let wedge = if angle <= 180.0 {
        p.z.max(end)
    } else {
        p.z.min(end)
    };
    d.max(wedge)
}

fn smin_exp(a: f64, b: f64, k: f64) -> f64 {
    let diff = (a - b).abs();
    a.min(b) - (1.0 + (-k * diff).exp()).ln() / k
}

fn smin_poly(a: f64, b: f64, k: f64) -> f64 {
    if (b - a).abs() >= k {
        return a.min(b);
    }
    let h = (0.5 + 0.5 * (b - a) / k).clamp(0.0, 1.0);
    b + (a - b) * h - k * h * (1.0 - h)
}

fn smin(a: f64, b: f64, k: f64, poly: bool) -> f64 {
    if poly {
        smin_poly(a, b, k)
    } else {
        smin_exp(a, b, k)
    }
}

fn smax(a: f64, b: f64, k: f64, poly: bool) -> f64 {
    -smin(-a, -b, k, poly)
}

fn combine(c: &Combine, a: f64, b: f64) -> f64 {
    match (c.smooth, c.op) {
        (None, BoolOp::Union) => a.min(b),
        (None, BoolOp::Intersection) => a.max(b),
        (None, BoolOp::Difference) => a.max(-b),
        (Some((poly, k)), BoolOp::Union) => smin(a, b, k, poly),
        (Some((poly, k)), BoolOp::Intersection) => smax(a, b, k, poly),
        (Some((poly, k)), BoolOp::Difference) => smax(a, -b, k, poly),
    }
}

/// `pickUnion` / `pickIntersect` / `pickSubtract`.
fn pick(op: BoolOp, a: (f64, f64), b: (f64, f64), d: f64) -> (f64, f64) {
    let first = match op {
        BoolOp::Union => a.0 <= b.0,
        BoolOp::Intersection => a.0 >= b.0,
        BoolOp::Difference => a.0 >= -b.0,
    };
    (d, if first { a.1 } else { b.1 })
}

fn shape2d(code: &Code, n: u32, p: DVec2) -> f64 {
    let stmts = &code.shapes[n as usize];
    let mut e = vec![0.0; stmts.len()];
    let mut last = EMPTY;
    for s in stmts {
        match s {
            Stmt2::Leaf { dst, prim, place } => {
                let q = if place.pos == DVec2::ZERO && place.rot == 0.0 {
                    p
                } else {
                    let r = place.rot.to_radians();
                    unplace(p, place.pos, DVec2::new(r.cos(), r.sin()))
                };
                e[*dst as usize] = match prim {
                    Call2::Rect { half } => sd_rect(q, *half),
                    Call2::Circle { radius } => q.length() - radius,
                    Call2::RoundedRect { half, radius } => sd_rect(q, *half - *radius) - radius,
                    Call2::Polygon { points, .. } => sd_polygon(points, q),
                };
                last = e[*dst as usize];
            }
            Stmt2::Combine { dst, op, a, b } => {
                let (a, b) = (e[*a as usize], e[*b as usize]);
                e[*dst as usize] = match op {
                    BoolOp::Union => a.min(b),
                    BoolOp::Intersection => a.max(b),
                    BoolOp::Difference => a.max(-b),
                };
                last = e[*dst as usize];
            }
        }
    }
    last
}

fn call(code: &Code, c: &Call, q: DVec3) -> f64 {
    match c {
        Call::Box { half } => sd_box(q, *half),
        Call::Sphere { radius } => q.length() - radius,
        Call::Cylinder {
            radius,
            half_height,
        } => sd_cylinder(q, *radius, *half_height),
        Call::Cone {
            half_height,
            r_bottom,
            r_top,
        } => sd_cone(q, *half_height, *r_bottom, *r_top),
        Call::Pyramid { base, height } => {
            sd_pyramid_unit(
                (q + DVec3::new(0.0, 0.5 * height, 0.0)) / base,
                height / base,
            ) * base
        }
        Call::Plane { normal, offset } => normal.dot(q) + offset,
        Call::Torus { major, minor } => DVec2::new(xz(q).length() - major, q.y).length() - minor,
        Call::Extrude { shape, half_depth } => extrusion(
            shape2d(code, *shape, DVec2::new(q.x, q.y)),
            q.z,
            *half_depth,
        ),
        Call::Warped {
            shape,
            half_depth,
            twist,
            scale_top,
            reach,
            slope,
            bmin,
            bmax,
        } => {
            let s = warped_slice(q, *half_depth, *twist, *scale_top);
            let g = shape2d(code, *shape, DVec2::new(s.x, s.y)) * s.z;
            warped_bound(g, q, *half_depth, *reach, *slope, *bmin, *bmax)
        }
        Call::Revolve { shape, angle } => revolution(
            shape2d(code, *shape, DVec2::new(xz(q).length(), q.y)),
            q,
            *angle,
        ),
    }
}

/// `sceneLeaf(p)`: the distance, the deciding leaf (−1: none), and how many primitives were
/// skipped by their bounding sphere.
pub(crate) fn scene_leaf(code: &Code, p: DVec3) -> (f64, f64, usize) {
    let mut culled = 0;
    let n = code.stmts.len();
    let mut qs = vec![DVec3::ZERO; n + 1];
    let mut ds = vec![(0.0, 0.0); n + 1];
    for s in &code.stmts {
        match s {
            Stmt::Point { dst, m, t } => qs[*dst as usize] = *m * p + *t,
            Stmt::Dist {
                dst,
                q,
                call: c,
                factor,
                leaf,
                cull,
            } => {
                let q = q.map_or(p, |v| qs[v as usize]);
                let bound = cull.and_then(|k| {
                    let b = k.ratio * (p - k.center).length() - k.radius;
                    let a = ds[k.against as usize].0;
                    let t = if k.negate { -a } else { a };
                    (b > t + k.margin).then_some(b)
                });
                culled += usize::from(bound.is_some());
                let d = bound.unwrap_or_else(|| {
                    let d = call(code, c, q);
                    if *factor != 1.0 { d * factor } else { d }
                });
                ds[*dst as usize] = (d, *leaf as f64);
            }
            Stmt::Empty { dst } => ds[*dst as usize] = (EMPTY, -1.0),
            Stmt::Combine { dst, op, a, b } => {
                let (a, b) = (ds[*a as usize], ds[*b as usize]);
                ds[*dst as usize] = pick(op.op, a, b, combine(op, a.0, b.0));
            }
        }
    }
    let (d, leaf) = code.result.map_or((EMPTY, -1.0), |v| ds[v as usize]);
    (d, leaf, culled)
}
