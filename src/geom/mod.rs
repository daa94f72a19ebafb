//! Basic geometry: boxes, planes and the tolerance that classifies points against planes.

mod aabb;
pub(crate) mod bvh;
mod plane;
mod tolerance;

pub use aabb::Aabb;
pub use plane::{Plane, Side};
pub use tolerance::Tolerance;

/// The largest coordinate magnitude the kernel accepts. Volumes multiply three coordinates,
/// so beyond about 10¹⁰² they overflow f64; inputs past this bound are refused where they enter
/// (primitive sizes, transforms, meshes) rather than giving infinite or empty results.
pub const MAX_COORDINATE: f64 = 1e100;

/// The power of two that brings a magnitude of `reach` (finite, > 0) to at most 1. Scaling by
/// it is exact, so exact predicates can work on the scaled values without overflow.
pub(crate) fn unit_scale(reach: f64) -> f64 {
    2f64.powi(-reach.log2().ceil() as i32)
}

/// The signed solid angle of triangle `abc` seen from the origin (Van Oosterom–Strackee), for
/// generalised winding numbers: the angles of a closed surface sum to 4π at a point inside.
pub(crate) fn solid_angle(a: glam::DVec3, b: glam::DVec3, c: glam::DVec3) -> f64 {
    let (la, lb, lc) = (a.length(), b.length(), c.length());
    let num = a.dot(b.cross(c));
    let den = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
    2.0 * num.atan2(den)
}
