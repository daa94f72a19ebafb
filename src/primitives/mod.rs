//! The faces of primitive solids, centred at the origin with Y up, and segment counts from a
//! chordal tolerance. The solids themselves are made in `solid/primitives.rs`. Invalid
//! parameters return [`Error::InvalidParameter`]; nothing here panics.

mod cuboid;
mod polyhedron;
mod revolved;

/// The box's face table, for tests that bend a box's corners.
#[cfg(test)]
pub(crate) use cuboid::BOX_FACES;
pub(crate) use cuboid::{cuboid, cuboid_between};
pub(crate) use polyhedron::polyhedron;
pub(crate) use revolved::{frustum, frustum_between, sphere, torus};

use crate::error::{Error, Result};
use crate::polygon::Polygon;

/// The fewest segments a round primitive accepts around its axis.
pub const MIN_SEGMENTS: u32 = 3;
/// The most segments (or rings) a round primitive accepts: beyond this, polygons are smaller
/// than any tolerance worth asking for and memory runs out first.
pub const MAX_SEGMENTS: u32 = 1 << 14;
/// The most polygons one primitive may have (segments × rings for spheres and tori), about
/// 800 MB of polygons: a finer request is refused rather than exhausting memory.
pub const MAX_POLYGONS: u64 = 1 << 22;

/// How many segments a circle of `radius` needs so that no chord strays more than `tolerance`
/// from the true circle: `⌈π / acos(1 − tolerance / radius)⌉`, at least [`MIN_SEGMENTS`].
///
/// ```
/// let n = bspcsg::segments_for_tolerance(1.0, 1e-3).unwrap();
/// assert_eq!(n, 71);
/// ```
///
/// # Errors
///
/// [`Error::InvalidParameter`] when `radius` or `tolerance` is not finite and positive, or the
/// tolerance would need more than [`MAX_SEGMENTS`] segments.
pub fn segments_for_tolerance(radius: f64, tolerance: f64) -> Result<u32> {
    positive("radius", radius)?;
    positive("tolerance", tolerance)?;
    if tolerance >= radius {
        return Ok(MIN_SEGMENTS);
    }
    let n = (std::f64::consts::PI / (1.0 - tolerance / radius).acos()).ceil();
    if n > MAX_SEGMENTS as f64 {
        return Err(Error::param(
            "tolerance",
            tolerance,
            format!("is too fine for this radius (more than {MAX_SEGMENTS} segments)"),
        ));
    }
    Ok((n as u32).max(MIN_SEGMENTS))
}

/// A primitive's face, or an error where the parameters make it degenerate (sizes so extreme
/// that the face has no computable plane).
pub(crate) fn face(vertices: &[glam::DVec3]) -> Result<Polygon> {
    Polygon::new(vertices, 0).ok_or(Error::param(
        "size",
        vertices[0].length(),
        "gives a face with no computable plane (out of the supported range)",
    ))
}

/// Refuses a round primitive with more than [`MAX_POLYGONS`] polygons.
pub(crate) fn budget(segments: u32, rings: u32) -> Result<()> {
    if segments as u64 * rings as u64 > MAX_POLYGONS {
        Err(Error::param(
            "rings",
            rings as f64,
            format!("times segments exceeds the {MAX_POLYGONS}-polygon budget of one primitive"),
        ))
    } else {
        Ok(())
    }
}

pub(crate) fn positive(name: &'static str, value: f64) -> Result<()> {
    if !(value.is_finite() && value > 0.0) {
        Err(Error::param(name, value, "must be finite and > 0"))
    } else if value > crate::geom::MAX_COORDINATE {
        Err(Error::param(
            name,
            value,
            format!(
                "is beyond the supported range (at most {:e})",
                crate::geom::MAX_COORDINATE
            ),
        ))
    } else {
        Ok(())
    }
}

pub(crate) fn count(name: &'static str, value: u32, min: u32) -> Result<()> {
    if value < min {
        Err(Error::param(name, value as f64, "is too small"))
    } else if value > MAX_SEGMENTS {
        Err(Error::param(
            name,
            value as f64,
            format!("must be at most {MAX_SEGMENTS}"),
        ))
    } else {
        Ok(())
    }
}
