//! Basic geometry: boxes, planes and the tolerance that classifies points against planes.

mod aabb;
pub(crate) mod bvh;
mod plane;
mod tolerance;

pub use aabb::Aabb;
pub use plane::{Plane, Side};
pub use tolerance::Tolerance;
