//! The axis-aligned box.

use glam::DVec3;

use super::{face, positive};
use crate::error::Result;
use crate::polygon::Polygon;

/// A box's six faces as corner indices whose bits say which end of each axis the corner takes
/// (1 = +x, 2 = +y, 4 = +z), each face counter-clockwise from outside.
pub(crate) const BOX_FACES: [[usize; 4]; 6] = [
    [0, 4, 6, 2], // -x
    [1, 3, 7, 5], // +x
    [0, 1, 5, 4], // -y
    [2, 6, 7, 3], // +y
    [0, 2, 3, 1], // -z
    [4, 5, 7, 6], // +z
];

/// The six faces of an axis-aligned box of the given edge lengths, centred at the origin.
pub(crate) fn cuboid(size: DVec3) -> Result<Vec<Polygon>> {
    positive("size.x", size.x)?;
    positive("size.y", size.y)?;
    positive("size.z", size.z)?;
    let h = size * 0.5;
    cuboid_between(-h, h)
}

/// The six faces of the axis-aligned box from `lo` to `hi`, each corner taking its coordinates
/// from `lo` and `hi` bit for bit (a box sized and then moved can shift a face by a rounding).
pub(crate) fn cuboid_between(lo: DVec3, hi: DVec3) -> Result<Vec<Polygon>> {
    positive("size.x", hi.x - lo.x)?;
    positive("size.y", hi.y - lo.y)?;
    positive("size.z", hi.z - lo.z)?;
    let corner = |i: usize| {
        DVec3::new(
            if i & 1 != 0 { hi.x } else { lo.x },
            if i & 2 != 0 { hi.y } else { lo.y },
            if i & 4 != 0 { hi.z } else { lo.z },
        )
    };
    BOX_FACES
        .iter()
        .map(|f| face(f.map(corner).as_slice()))
        .collect()
}
