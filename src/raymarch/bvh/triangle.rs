//! The tests the BVH's queries run at its leaves: the watertight ray–triangle test (Woop,
//! Benthin and Wald 2013), its per-ray part computed once, and the closest point of a triangle.

use glam::DVec3;

use crate::raymarch::camera::Ray;

/// The per-ray part of the watertight test: the axis permutation and shear that map the ray
/// to +z, computed once per ray rather than per triangle.
#[derive(Clone, Copy)]
pub(super) struct Shear {
    origin: DVec3,
    k: [usize; 3],
    s: [f64; 3],
}

impl Shear {
    #[inline]
    pub(super) fn new(ray: &Ray) -> Shear {
        let d = ray.dir;
        let kz = d.abs().max_position();
        let mut kx = (kz + 1) % 3;
        let mut ky = (kx + 1) % 3;
        if d[kz] < 0.0 {
            std::mem::swap(&mut kx, &mut ky);
        }
        let sz = 1.0 / d[kz];
        Shear {
            origin: ray.origin,
            k: [kx, ky, kz],
            s: [d[kx] * sz, d[ky] * sz, sz],
        }
    }

    /// The watertight ray–triangle test of Woop, Benthin and Wald (JCGT 2013): edge functions
    /// in a ray-aligned shear frame, so a ray through a shared edge or vertex hits at least one
    /// of the triangles there (never slips between them). Both sides count. Returns
    /// `(t, u, v)`.
    #[inline]
    pub(super) fn hit(&self, tri: &[DVec3; 3], t_min: f64, t_max: f64) -> Option<(f64, f64, f64)> {
        let [kx, ky, kz] = self.k;
        let [sx, sy, sz] = self.s;
        let a = tri[0] - self.origin;
        let b = tri[1] - self.origin;
        let c = tri[2] - self.origin;
        let ax = a[kx] - sx * a[kz];
        let ay = a[ky] - sy * a[kz];
        let bx = b[kx] - sx * b[kz];
        let by = b[ky] - sy * b[kz];
        let cx = c[kx] - sx * c[kz];
        let cy = c[ky] - sy * c[kz];
        let u = cx * by - cy * bx;
        let v = ax * cy - ay * cx;
        let w = bx * ay - by * ax;
        if (u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0) {
            return None;
        }
        let det = u + v + w;
        if det == 0.0 {
            return None;
        }
        let t = (u * a[kz] + v * b[kz] + w * c[kz]) * sz / det;
        if !(t > t_min && t < t_max) {
            return None;
        }
        Some((t, v / det, w / det))
    }
}

/// [`Shear::hit`] for one ray and one triangle.
#[cfg(test)]
pub(super) fn watertight(
    ray: &Ray,
    tri: &[DVec3; 3],
    t_min: f64,
    t_max: f64,
) -> Option<(f64, f64, f64)> {
    Shear::new(ray).hit(tri, t_min, t_max)
}

/// The point of triangle `t` nearest to `p` (Ericson, Real-Time Collision Detection 5.1.5).
pub(super) fn closest_on_triangle(p: DVec3, t: &[DVec3; 3]) -> DVec3 {
    let [a, b, c] = *t;
    let ab = b - a;
    let ac = c - a;
    let ap = p - a;
    let d1 = ab.dot(ap);
    let d2 = ac.dot(ap);
    if d1 <= 0.0 && d2 <= 0.0 {
        return a;
    }
    let bp = p - b;
    let d3 = ab.dot(bp);
    let d4 = ac.dot(bp);
    if d3 >= 0.0 && d4 <= d3 {
        return b;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return a + ab * (d1 / (d1 - d3));
    }
    let cp = p - c;
    let d5 = ab.dot(cp);
    let d6 = ac.dot(cp);
    if d6 >= 0.0 && d5 <= d6 {
        return c;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return a + ac * (d2 / (d2 - d6));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    }
    let denom = va + vb + vc;
    if denom == 0.0 || !denom.is_finite() {
        // Degenerate triangle: the nearest of its edges' endpoints will do.
        return [a, b, c]
            .into_iter()
            .min_by(|x, y| {
                (*x - p)
                    .length_squared()
                    .total_cmp(&(*y - p).length_squared())
            })
            .unwrap_or(a);
    }
    let v = vb / denom;
    let w = vc / denom;
    a + ab * v + ac * w
}
