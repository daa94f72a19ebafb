//! Rigid motions, scaling, general affine maps and inversion of a solid. Every map is checked:
//! non-finite or singular maps, and results beyond the supported range, are refused.

use glam::{DAffine3, DMat3, DQuat, DVec3};

use super::Solid;
use crate::error::{Error, Result};
use crate::geom::{MAX_COORDINATE, Plane, Tolerance, euler_degrees};
use crate::polygon::{Polygon, Vertices};

impl Solid {
    /// The solid turned inside out: every polygon flipped, so each faces the other way and
    /// [`volume`](Solid::volume) is negated. It is not a complement as a boolean operand: the
    /// booleans do not read it as the unbounded outside (the flipped unit cube ∩ a 3-cube
    /// around it does not give 26); for a complement within a bound, take a difference.
    #[must_use]
    pub fn flipped(mut self) -> Self {
        self.index = None;
        self.vertex_ids = None;
        for p in &mut self.polygons {
            p.flip();
        }
        self
    }

    /// Moves the solid by `offset`. Non-finite offsets, and offsets that would move a vertex
    /// beyond [`MAX_COORDINATE`](crate::MAX_COORDINATE), are refused.
    ///
    /// # Errors
    ///
    /// [`Error::InvalidParameter`] for a non-finite offset or a result beyond
    /// [`MAX_COORDINATE`].
    pub fn translate(self, offset: DVec3) -> Result<Self> {
        finite_vec("offset", offset)?;
        in_range(self.map_rigid(DQuat::IDENTITY, offset))
    }

    /// Rotates the solid about the origin by a quaternion (normalised here).
    ///
    /// # Errors
    ///
    /// [`Error::InvalidParameter`] for a zero or non-finite quaternion or a result beyond
    /// [`MAX_COORDINATE`].
    pub fn rotate(self, rotation: DQuat) -> Result<Self> {
        let q = normalized(rotation).ok_or(Error::param(
            "rotation",
            rotation.length(),
            "must be a finite, non-zero quaternion",
        ))?;
        in_range(self.map_rigid(q, DVec3::ZERO))
    }

    /// Rotates by `degrees` about `axis` (right-handed).
    ///
    /// # Errors
    ///
    /// [`Error::InvalidParameter`] for a zero or non-finite axis, non-finite degrees, or a
    /// result beyond [`MAX_COORDINATE`].
    pub fn rotate_axis_angle(self, axis: DVec3, degrees: f64) -> Result<Self> {
        finite("degrees", degrees)?;
        let axis = axis.try_normalize().ok_or(Error::param(
            "axis",
            axis.length(),
            "must be a finite, non-zero vector",
        ))?;
        in_range(self.map_rigid(
            DQuat::from_axis_angle(axis, degrees.to_radians()),
            DVec3::ZERO,
        ))
    }

    /// Rotates by Euler angles in degrees: first about X, then Y, then Z, all about the fixed
    /// world axes (`R = Rz · Ry · Rx`), the order scene documents use.
    ///
    /// # Errors
    ///
    /// [`Error::InvalidParameter`] for non-finite angles or a result beyond [`MAX_COORDINATE`].
    pub fn rotate_euler(self, degrees: DVec3) -> Result<Self> {
        finite_vec("degrees", degrees)?;
        in_range(self.map_rigid(euler_degrees(degrees), DVec3::ZERO))
    }

    /// Scales uniformly about the origin. The factor must be finite and non-zero; a negative one
    /// mirrors the solid and its winding is reversed so it stays outward-facing.
    ///
    /// # Errors
    ///
    /// As [`Solid::transform`].
    pub fn scale(self, factor: f64) -> Result<Self> {
        self.scale_xyz(DVec3::splat(factor))
    }

    /// Scales per axis about the origin (see [`Solid::scale`]).
    ///
    /// # Errors
    ///
    /// As [`Solid::transform`].
    pub fn scale_xyz(self, factors: DVec3) -> Result<Self> {
        self.transform(DAffine3::from_scale(factors))
    }

    /// Applies any invertible affine map. A map with negative determinant reverses each
    /// polygon's winding so the solid stays outward-facing.
    ///
    /// # Errors
    ///
    /// [`Error::InvalidParameter`] for a non-finite or singular map, or a result beyond
    /// [`MAX_COORDINATE`].
    pub fn transform(self, map: DAffine3) -> Result<Self> {
        let m = map.matrix3;
        let det = m.determinant();
        if !(det.is_finite() && map.translation.is_finite()) {
            return Err(Error::param("transform", det, "must be finite"));
        }
        if det == 0.0 || !m.inverse().is_finite() {
            return Err(Error::param(
                "transform",
                det,
                "must be invertible (determinant ≠ 0)",
            ));
        }
        let normal_map: DMat3 = m.inverse().transpose();
        let polygons = self
            .polygons
            .into_iter()
            .filter_map(|p| {
                let mut vs: Vertices = p
                    .vertices()
                    .iter()
                    .map(|&v| map.transform_point3(v))
                    .collect();
                if det < 0.0 {
                    vs.reverse();
                }
                // The plane maps exactly by the inverse transpose; Newell would only re-derive it.
                let plane = Plane::from_point_normal(
                    map.transform_point3(p.plane().anchor),
                    normal_map * p.plane().normal,
                )?;
                Some(Polygon::with_plane(vs, plane, p.source()))
            })
            .collect();
        in_range(Solid {
            polygons,
            eps: self.eps * det.abs().cbrt(),
            lost: self.lost,
            overrun: self.overrun,
            index: None,
            vertex_ids: None,
        })
    }

    fn map_rigid(self, q: DQuat, t: DVec3) -> Self {
        let polygons = self
            .polygons
            .into_iter()
            .map(|p| {
                let vs: Vertices = p.vertices().iter().map(|&v| q * v + t).collect();
                let plane = Plane::through(q * p.plane().anchor + t, q * p.plane().normal);
                Polygon::with_plane(vs, plane, p.source())
            })
            .collect();
        Solid {
            polygons,
            eps: self.eps,
            lost: self.lost,
            overrun: self.overrun,
            index: None,
            vertex_ids: None,
        }
    }
}

/// The solid, or an error where a transform moved it beyond the supported range.
///
/// A carried tolerance grows to the floor of the new place: vertices moved far from the origin
/// are rounded to the precision of their new coordinates, which a tolerance made near the
/// origin would not allow for.
fn in_range(mut solid: Solid) -> Result<Solid> {
    let reach = solid.bbox().max_abs();
    if solid.eps > 0.0 {
        solid.eps = solid.eps.max(Tolerance::floor(reach));
    }
    if reach > MAX_COORDINATE || !reach.is_finite() {
        Err(Error::param(
            "transform",
            reach,
            format!("moves the solid beyond the supported range of ±{MAX_COORDINATE:e}"),
        ))
    } else {
        Ok(solid)
    }
}

fn finite(name: &'static str, value: f64) -> Result<()> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(Error::param(name, value, "must be finite"))
    }
}

fn finite_vec(name: &'static str, v: DVec3) -> Result<()> {
    for c in v.to_array() {
        finite(name, c)?;
    }
    Ok(())
}

/// The unit quaternion along `q`, if `q` is finite and not zero.
fn normalized(q: DQuat) -> Option<DQuat> {
    let len = q.length();
    (len.is_finite() && len > 0.0).then(|| q / len)
}

#[cfg(test)]
mod tests {
    use crate::Solid;

    /// What [`Solid::flipped`] documents: the same polygons facing the other way, the volume
    /// negated, and flipping twice gives the solid back.
    #[test]
    fn flipped_turns_every_polygon_and_negates_the_volume() {
        let cube = Solid::cube(1.0).unwrap();
        let flipped = cube.clone().flipped();
        assert_eq!(flipped.polygon_count(), cube.polygon_count());
        assert!(
            (flipped.volume() + 1.0).abs() < 1e-12,
            "{}",
            flipped.volume()
        );
        for (p, q) in cube.polygons().iter().zip(flipped.polygons()) {
            assert!((p.plane().normal + q.plane().normal).length() < 1e-12);
        }
        assert!((flipped.flipped().volume() - 1.0).abs() < 1e-12);
    }
}
