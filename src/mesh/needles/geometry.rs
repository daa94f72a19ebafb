//! Triangle measures the needle pass uses.

use glam::DVec3;

/// The distance of `p` from the plane of triangle `c` (its distance from `c[0]` if `c` is flat).
pub(super) fn plane_distance(c: [DVec3; 3], p: DVec3) -> f64 {
    match twice_normal(c).try_normalize() {
        Some(n) => n.dot(p - c[0]).abs(),
        None => p.distance(c[0]),
    }
}

pub(super) fn twice_normal([a, b, c]: [DVec3; 3]) -> DVec3 {
    (b - a).cross(c - a)
}

pub(super) fn area(c: [DVec3; 3]) -> f64 {
    0.5 * twice_normal(c).length()
}
