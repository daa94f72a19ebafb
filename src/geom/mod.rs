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
