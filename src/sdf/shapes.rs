//! Distance functions of the primitives, in their local frames (Inigo Quilez's formulas).
//!
//! Every function here is exact — the true signed Euclidean distance, negative inside — so it
//! is 1-Lipschitz, which is what culling and sphere tracing rely on.

use glam::{DVec2, DVec3};

pub(crate) use super::extrusion::Extrusion;
use super::shapes2d::Shape2;
use crate::geom::Aabb;

/// A 3D primitive, centred at the origin, round ones about Y.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Shape {
    Box {
        half: DVec3,
    },
    Sphere {
        radius: f64,
    },
    /// Capped cylinder along Y.
    Cylinder {
        radius: f64,
        half_height: f64,
    },
    /// Capped cone along Y: `r_bottom` at `-half_height`, `r_top` at `+half_height`.
    Cone {
        r_bottom: f64,
        r_top: f64,
        half_height: f64,
    },
    /// Square pyramid: base of side `base` at `y = -height/2`, apex at `y = +height/2`.
    Pyramid {
        base: f64,
        height: f64,
    },
    /// Half-space `normal·p + offset ≤ 0`, `normal` of unit length.
    Plane {
        normal: DVec3,
        offset: f64,
    },
    /// Torus about Y.
    Torus {
        major: f64,
        minor: f64,
    },
    /// A 2D shape extruded along Z over `[-half_depth, half_depth]`, optionally twisted and
    /// scaled towards the top.
    Extrude(Extrusion),
    /// A 2D shape's half-plane x ≥ 0 turned about Y by `angle` degrees (360: a full turn).
    Revolve {
        shape: Shape2,
        angle: f64,
    },
}

impl Shape {
    /// The signed distance at a local point.
    #[inline]
    pub(crate) fn distance(&self, p: DVec3) -> f64 {
        match self {
            Shape::Box { half } => cuboid(p, *half),
            Shape::Sphere { radius } => p.length() - radius,
            Shape::Cylinder {
                radius,
                half_height,
            } => cylinder(p, *radius, *half_height),
            Shape::Cone {
                r_bottom,
                r_top,
                half_height,
            } => capped_cone(p, *half_height, *r_bottom, *r_top),
            Shape::Pyramid { base, height } => {
                // IQ's pyramid has a unit base at y = 0; scale it (uniformly, so exactly).
                let q = (p + DVec3::new(0.0, 0.5 * height, 0.0)) / base;
                pyramid(q, height / base) * base
            }
            Shape::Plane { normal, offset } => normal.dot(p) + offset,
            Shape::Torus { major, minor } => {
                DVec2::new(DVec2::new(p.x, p.z).length() - major, p.y).length() - minor
            }
            Shape::Extrude(e) => e.distance(p),
            Shape::Revolve { shape, angle } => revolution(shape, *angle, p),
        }
    }

    /// Distances at many local points: the match is hoisted out of the loop so each arm is a
    /// tight loop the compiler can vectorise.
    pub(crate) fn distances(&self, points: &[DVec3], out: &mut [f64]) {
        macro_rules! each {
            (|$p:ident| $e:expr) => {
                for (o, &$p) in out.iter_mut().zip(points) {
                    *o = $e;
                }
            };
        }
        match self {
            Shape::Box { half } => each!(|p| cuboid(p, *half)),
            Shape::Sphere { radius } => each!(|p| p.length() - radius),
            Shape::Cylinder {
                radius,
                half_height,
            } => each!(|p| cylinder(p, *radius, *half_height)),
            Shape::Torus { major, minor } => {
                each!(|p| DVec2::new(DVec2::new(p.x, p.z).length() - major, p.y).length() - minor)
            }
            Shape::Cone {
                r_bottom,
                r_top,
                half_height,
            } => each!(|p| capped_cone(p, *half_height, *r_bottom, *r_top)),
            Shape::Plane { normal, offset } => each!(|p| normal.dot(p) + offset),
            // Each of these arms names its own shape's function: calling `self.distance` here
            // would match again per point, and whether that match is inlined depends on how the
            // crate happens to be split into codegen units (measured: the mechanical bake ran
            // 30 % slower when it was not).
            Shape::Pyramid { base, height } => each!(|p| {
                let q = (p + DVec3::new(0.0, 0.5 * height, 0.0)) / base;
                pyramid(q, height / base) * base
            }),
            Shape::Extrude(e) => each!(|p| e.distance(p)),
            Shape::Revolve { shape, angle } => each!(|p| revolution(shape, *angle, p)),
        }
    }

    /// A box holding the solid in the local frame; unbounded for the half-space.
    pub(crate) fn local_bounds(&self) -> Aabb {
        let b = |h: DVec3| Aabb::new(-h, h);
        match self {
            Shape::Box { half } => b(*half),
            Shape::Sphere { radius } => b(DVec3::splat(*radius)),
            Shape::Cylinder {
                radius,
                half_height,
            } => b(DVec3::new(*radius, *half_height, *radius)),
            Shape::Cone {
                r_bottom,
                r_top,
                half_height,
            } => {
                let r = r_bottom.max(*r_top);
                b(DVec3::new(r, *half_height, r))
            }
            Shape::Pyramid { base, height } => b(DVec3::new(0.5 * base, 0.5 * height, 0.5 * base)),
            Shape::Plane { .. } => Aabb::new(DVec3::NEG_INFINITY, DVec3::INFINITY),
            Shape::Torus { major, minor } => b(DVec3::new(major + minor, *minor, major + minor)),
            Shape::Extrude(e) => e.local_bounds(),
            Shape::Revolve { shape, .. } => {
                let (lo, hi) = shape.bounds();
                let r = hi.x.max(0.0);
                if lo.cmpgt(hi).any() || r == 0.0 {
                    return Aabb::EMPTY;
                }
                Aabb::new(DVec3::new(-r, lo.y, -r), DVec3::new(r, hi.y, r))
            }
        }
    }
}

#[inline]
fn cuboid(p: DVec3, half: DVec3) -> f64 {
    let q = p.abs() - half;
    q.max(DVec3::ZERO).length() + q.max_element().min(0.0)
}

#[inline]
pub(super) fn rect(p: DVec2, half: DVec2) -> f64 {
    let q = p.abs() - half;
    q.max(DVec2::ZERO).length() + q.max_element().min(0.0)
}

#[inline]
fn cylinder(p: DVec3, radius: f64, half_height: f64) -> f64 {
    let d = DVec2::new(
        DVec2::new(p.x, p.z).length() - radius,
        p.y.abs() - half_height,
    );
    d.max_element().min(0.0) + d.max(DVec2::ZERO).length()
}

/// The distance to a 2D shape extruded over `|z| ≤ half_depth`, exact when `d2` is.
#[inline]
pub(crate) fn extrusion(d2: f64, z: f64, half_depth: f64) -> f64 {
    let w = DVec2::new(d2, z.abs() - half_depth);
    w.max_element().min(0.0) + w.max(DVec2::ZERO).length()
}

/// IQ's exact capped cone: radius `r1` at `y = -h`, `r2` at `y = +h`.
fn capped_cone(p: DVec3, h: f64, r1: f64, r2: f64) -> f64 {
    let q = DVec2::new(DVec2::new(p.x, p.z).length(), p.y);
    let k1 = DVec2::new(r2, h);
    let k2 = DVec2::new(r2 - r1, 2.0 * h);
    let ca = DVec2::new(
        q.x - q.x.min(if q.y < 0.0 { r1 } else { r2 }),
        q.y.abs() - h,
    );
    let cb = q - k1 + k2 * ((k1 - q).dot(k2) / k2.length_squared()).clamp(0.0, 1.0);
    let s = if cb.x < 0.0 && ca.y < 0.0 { -1.0 } else { 1.0 };
    s * ca.length_squared().min(cb.length_squared()).sqrt()
}

/// IQ's pyramid, made exact at the base: unit square base centred at the origin in y = 0, apex at (0, h, 0).
fn pyramid(p: DVec3, h: f64) -> f64 {
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
    // IQ's expression is the distance to the four lateral faces only; the base square is a
    // face too, nearer below the base and near it from inside.
    let lateral = ((d2 + q.z * q.z) / m2).sqrt();
    if q.z.max(-y) < 0.0 {
        -lateral.min(y)
    } else {
        let b = DVec2::new(p.x.abs() - 0.5, p.z.abs() - 0.5).max(DVec2::ZERO);
        lateral.min((b.length_squared() + y * y).sqrt())
    }
}

/// IQ's exact polygon distance: nearest edge, sign by the crossing-number rule.
pub(super) fn polygon(v: &[DVec2], p: DVec2) -> f64 {
    let n = v.len();
    let mut d = (p - v[0]).length_squared();
    let mut s = 1.0;
    let mut j = n - 1;
    for i in 0..n {
        let e = v[j] - v[i];
        let w = p - v[i];
        let b = w - e * (w.dot(e) / e.length_squared()).clamp(0.0, 1.0);
        d = d.min(b.length_squared());
        let c = [p.y >= v[i].y, p.y < v[j].y, e.x * w.y > e.y * w.x];
        if c.iter().all(|&x| x) || c.iter().all(|&x| !x) {
            s = -s;
        }
        j = i;
    }
    s * d.sqrt()
}

/// The distance to a 2D shape's half-plane x ≥ 0 turned about Y by `angle` degrees: the 2D
/// distance within the meridian half-plane, exact for a full turn of a profile clear of the
/// axis and a bound otherwise (an edge on the axis, or a part beyond it, is nearer than the
/// real boundary, never farther); a partial turn also lies within a wedge of angles, so the
/// larger of the two distances is a bound.
fn revolution(shape: &Shape2, angle: f64, p: DVec3) -> f64 {
    let d = shape.distance(DVec2::new(DVec2::new(p.x, p.z).length(), p.y));
    if angle >= 360.0 {
        return d;
    }
    // The turn starts in the xy plane and carries +x towards −z; the end face's outward normal
    // is the direction of the turn there.
    let a = angle.to_radians();
    let end = -a.sin() * p.x - a.cos() * p.z;
    let wedge = if angle <= 180.0 {
        p.z.max(end)
    } else {
        p.z.min(end)
    };
    d.max(wedge)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Arc;

    #[test]
    fn polygon_square_matches_rect() {
        let sq: Arc<[DVec2]> = vec![
            DVec2::new(-1.0, -1.0),
            DVec2::new(1.0, -1.0),
            DVec2::new(1.0, 1.0),
            DVec2::new(-1.0, 1.0),
        ]
        .into();
        for &(x, y) in &[
            (0.0, 0.0),
            (2.0, 0.5),
            (3.0, 3.0),
            (0.5, -0.25),
            (-1.5, 0.2),
        ] {
            let p = DVec2::new(x, y);
            let a = polygon(&sq, p);
            let b = rect(p, DVec2::ONE);
            assert!((a - b).abs() < 1e-12, "{p}: {a} vs {b}");
        }
    }
}
