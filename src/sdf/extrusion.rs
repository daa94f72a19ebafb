//! The extrusion of a 2D shape along z, optionally twisted about z and scaled towards the top,
//! as a distance bound for the SDF route.
//!
//! Without twist or scale the distance is exact. Otherwise each slice at height z is the shape
//! turned by θ(z) and scaled by s(z), and the slice's own 2D distance `g` (1-Lipschitz across the
//! slice) changes along z at most `L_z` per unit: `k·ρ` from the turn (k radians per unit, ρ the
//! distance from the axis) plus `|s'|·R` from the scale (R the shape's reach). On the segment
//! from a point to its nearest surface point ρ never exceeds `ρ_m = max(ρ, reach)` (the reach
//! of every slice), so `g / √(1 + L_z(ρ_m)²)` never overestimates, and it is zero only on the
//! surface — a bounding cylinder's distance would be zero on the cylinder too, where sphere
//! tracing would stall. The larger of it and the distance to the local box keeps far points'
//! steps long.

use glam::{DVec2, DVec3};

use super::shapes::extrusion;
use super::shapes2d::Shape2;
use crate::geom::Aabb;

#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Extrusion {
    pub shape: Shape2,
    pub half_depth: f64,
    /// Turn of the top relative to the bottom, degrees counter-clockwise about +z.
    pub twist: f64,
    /// Scale of the top relative to the bottom, per axis (≥ 0; both 0 or neither).
    pub scale_top: DVec2,
    /// The radius of a cylinder about z holding every slice.
    reach: f64,
    /// How fast the slice field can change along z: `turn · ρ + scale_rate + scale_per_rho · ρ`.
    turn: f64,
    scale_rate: f64,
    scale_per_rho: f64,
}

impl Extrusion {
    pub(crate) fn new(shape: Shape2, half_depth: f64, twist: f64, scale_top: DVec2) -> Self {
        let r = shape.reach();
        let reach = r * scale_top.max_element().max(1.0);
        let height = 2.0 * half_depth;
        let turn = twist.to_radians().abs() / height;
        let ds = (scale_top - DVec2::ONE).abs() / height;
        let (scale_rate, scale_per_rho) = if scale_top.x == scale_top.y {
            (ds.x * r, 0.0)
        } else {
            // Per-axis: the slice field is m(z)·d(D(z)⁻¹ p) with m the smaller factor.
            let smin = scale_top.min_element().min(1.0);
            (ds.max_element() * r, ds.max_element() * 2.0 / smin)
        };
        Extrusion {
            shape,
            half_depth,
            twist,
            scale_top,
            reach,
            turn,
            scale_rate,
            scale_per_rho,
        }
    }

    /// The constants of the twisted / tapered bound: `(reach, turn, scale_rate,
    /// scale_per_rho)`, as [`Extrusion::distance`] uses them.
    pub(crate) fn slope(&self) -> (f64, f64, f64, f64) {
        (self.reach, self.turn, self.scale_rate, self.scale_per_rho)
    }

    pub(crate) fn is_plain(&self) -> bool {
        self.twist == 0.0 && self.scale_top == DVec2::ONE
    }

    pub(crate) fn distance(&self, p: DVec3) -> f64 {
        let h = self.half_depth;
        let xy = DVec2::new(p.x, p.y);
        if self.is_plain() {
            return extrusion(self.shape.distance(xy), p.z, h);
        }
        let cap = p.z.abs() - h;
        let rho = xy.length().max(self.reach);
        let lz = (self.turn + self.scale_per_rho) * rho + self.scale_rate;
        let t = ((p.z + h) / (2.0 * h)).clamp(0.0, 1.0);
        let s = DVec2::ONE.lerp(self.scale_top, t).max(DVec2::splat(1e-12));
        let turn = DVec2::from_angle(-(self.twist * t).to_radians());
        let q = turn.rotate(xy) / s;
        let g = self.shape.distance(q) * s.min_element();
        let d = (g / (1.0 + lz * lz).sqrt()).max(cap);
        // Outside the local box its distance is a bound too, and long for far points.
        let b = self.local_bounds();
        let outside = (b.min - p).max(p - b.max).max(DVec3::ZERO).length();
        if outside > 0.0 { d.max(outside) } else { d }
    }

    pub(crate) fn local_bounds(&self) -> Aabb {
        let h = self.half_depth;
        if self.is_plain() {
            let (lo, hi) = self.shape.bounds();
            if lo.cmpgt(hi).any() {
                return Aabb::EMPTY;
            }
            return Aabb::new(lo.extend(-h), hi.extend(h));
        }
        let r = self.reach;
        Aabb::new(DVec3::new(-r, -r, -h), DVec3::new(r, r, h))
    }
}
