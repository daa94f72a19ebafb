//! The primitive solids, centred at the origin with Y up. The faces are built in
//! [`crate::primitives`]; here they become solids.

use glam::DVec3;

use super::Solid;
use crate::error::{Error, MeshDefect, Result};
use crate::primitives;

impl Solid {
    /// An axis-aligned box of the given edge lengths, centred at the origin.
    ///
    /// ```
    /// let b = bspcsg::Solid::cuboid(bspcsg::glam::DVec3::new(1.0, 2.0, 3.0)).unwrap();
    /// assert!((b.volume() - 6.0).abs() < 1e-12);
    /// ```
    ///
    /// # Errors
    ///
    /// [`Error::InvalidParameter`] when a size is not finite and positive or beyond
    /// [`MAX_COORDINATE`](crate::MAX_COORDINATE).
    pub fn cuboid(size: DVec3) -> Result<Solid> {
        primitives::cuboid(size).map(Solid::from_polygons)
    }

    /// A cube of edge `size`, centred at the origin.
    ///
    /// # Errors
    ///
    /// As [`Solid::cuboid`].
    pub fn cube(size: f64) -> Result<Solid> {
        Solid::cuboid(DVec3::splat(size))
    }

    /// A UV sphere: `segments` around the Y axis (≥ 3), `rings` from pole to pole (≥ 2).
    /// Quads between rings, triangles at the poles.
    ///
    /// ```
    /// let s = bspcsg::Solid::sphere(1.0, 64, 32).unwrap();
    /// assert!((s.volume() - 4.0 / 3.0 * std::f64::consts::PI).abs() < 0.02);
    /// ```
    ///
    /// # Errors
    ///
    /// [`Error::InvalidParameter`] for a radius that is not finite and positive, or segment and
    /// ring counts out of range or over the polygon budget
    /// ([`MAX_SEGMENTS`](crate::MAX_SEGMENTS), [`MAX_POLYGONS`](crate::MAX_POLYGONS)).
    pub fn sphere(radius: f64, segments: u32, rings: u32) -> Result<Solid> {
        primitives::sphere(radius, segments, rings).map(Solid::from_polygons)
    }

    /// A cylinder of `radius` along Y from `-height/2` to `height/2`, `segments` ≥ 3 around.
    ///
    /// # Errors
    ///
    /// As [`Solid::frustum`].
    pub fn cylinder(radius: f64, height: f64, segments: u32) -> Result<Solid> {
        Solid::frustum(radius, radius, height, segments)
    }

    /// A cone along Y: base of `radius` at `-height/2`, apex at `height/2`.
    ///
    /// # Errors
    ///
    /// As [`Solid::frustum`].
    pub fn cone(radius: f64, height: f64, segments: u32) -> Result<Solid> {
        Solid::frustum(radius, 0.0, height, segments)
    }

    /// A frustum along Y: radius `r_bottom` at `-height/2`, `r_top` at `height/2`. One radius
    /// may be zero (a cone); caps are single polygons.
    ///
    /// # Errors
    ///
    /// [`Error::InvalidParameter`] for a negative or non-finite radius, both radii zero, a
    /// height that is not finite and positive, or a segment count out of range.
    pub fn frustum(r_bottom: f64, r_top: f64, height: f64, segments: u32) -> Result<Solid> {
        primitives::frustum(r_bottom, r_top, height, segments).map(Solid::from_polygons)
    }

    /// A torus about the Y axis: tube centre at distance `major` from the axis, tube radius
    /// `minor < major`; `segments` ≥ 3 around the axis, `rings` ≥ 3 around the tube.
    ///
    /// # Errors
    ///
    /// [`Error::InvalidParameter`] for radii that are not finite and positive, `minor ≥ major`,
    /// or counts out of range or over the polygon budget.
    pub fn torus(major: f64, minor: f64, segments: u32, rings: u32) -> Result<Solid> {
        primitives::torus(major, minor, segments, rings).map(Solid::from_polygons)
    }

    /// A solid from vertices and faces (each a list of vertex indices, counter-clockwise seen
    /// from outside). Faces that are planar and convex become one polygon each; others are
    /// triangulated.
    ///
    /// The input is checked and refused with [`Error::InvalidMesh`] (with counts) unless every
    /// coordinate is finite, every face has at least three distinct in-range indices and spans
    /// an area, and the faces close up: every edge is used once in each direction.
    ///
    /// ```
    /// use bspcsg::glam::DVec3;
    /// let v = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z];
    /// let tetra = bspcsg::Solid::polyhedron(&v, &[[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]]).unwrap();
    /// assert!((tetra.volume() - 1.0 / 6.0).abs() < 1e-12);
    /// ```
    ///
    /// # Errors
    ///
    /// [`Error::InvalidMesh`] with the [`MeshDefect`](crate::MeshDefect) when the input fails
    /// the checks above.
    pub fn polyhedron<F: AsRef<[u32]>>(vertices: &[DVec3], faces: &[F]) -> Result<Solid> {
        let solid = Solid::from_polygons(primitives::polyhedron(vertices, faces)?);
        if solid.volume() <= 0.0 {
            return Err(Error::mesh(MeshDefect::InsideOut {
                inverted_shells: 1,
                shells: 1,
            }));
        }
        Ok(solid)
    }
}
