//! Rotations from the angles users and scene documents give.

use glam::{DQuat, DVec3, EulerRot};

/// The rotation of Euler angles in degrees, X first, then Y, then Z, about fixed axes.
pub(crate) fn euler_degrees(degrees: DVec3) -> DQuat {
    let r = degrees * (std::f64::consts::PI / 180.0);
    DQuat::from_euler(EulerRot::ZYX, r.z, r.y, r.x)
}
