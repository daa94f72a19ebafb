//! 2D regions ("sketches") and their booleans by a BSP of edges used as knives, and the
//! extrusions and revolutions that turn them into solids.
//!
//! A [`Sketch`] is a set of [`Region`]s: polygons with holes in the xy plane, in `f64`, outer
//! rings counter-clockwise and holes clockwise, so the region always lies to the left of every
//! directed edge. Each edge is a *knife*: the half-plane to its left is inside, to its right
//! outside, and its line cuts any other edge into an in, an on and an out part.
//!
//! # Booleans
//!
//! [`Sketch::boolean`] builds a 2D BSP tree of each operand's edges (`knife`), pushes the other
//! operand's edges through it to classify every piece as inside, outside, or on the boundary
//! facing the same or the opposite way (`classify`), keeps the pieces the operation needs
//! (`boolean`), and stitches them into rings (`assemble`). Trees live in arenas and every walk
//! uses an explicit stack.
//!
//! # Tolerance
//!
//! The same model as the 3D kernel ([`crate::Tolerance`]): `eps = max(1e-12 × d, 2⁻⁴⁰ × m)` for
//! the region where the operands' boxes meet, carried by the result so later booleans never
//! use a smaller one. Points within `eps` of a knife's line lie on it; output vertices within
//! `eps` of each other are one vertex.
//!
//! # Valid output
//!
//! Every sketch a constructor or boolean returns has rings of at least three vertices, no
//! zero-length edges, no two consecutive edges collinear, no edge crossing or touching another
//! except at a shared vertex, and every hole inside its region's outer ring.
//! [`Sketch::report`] checks these.

mod assemble;
mod boolean;
mod classify;
mod fill;
mod knife;
mod report;
mod shapes;
mod sweep;

use glam::{DAffine2, DVec2, DVec3};

use crate::error::{Error, Result};
use crate::geom::{Aabb, Tolerance};
use crate::solid::Containment;

pub use report::SketchReport;
pub use sweep::{ExtrudeOptions, TWIST_DEGREES_PER_SLICE};

/// One connected piece of a sketch: a counter-clockwise outer ring and clockwise holes inside
/// it. Rings are closed implicitly (the last vertex joins the first).
#[derive(Clone, Debug, PartialEq)]
pub struct Region {
    outer: Vec<DVec2>,
    holes: Vec<Vec<DVec2>>,
}

impl Region {
    /// The outer ring, counter-clockwise.
    #[must_use]
    pub fn outer(&self) -> &[DVec2] {
        &self.outer
    }

    /// The holes, each clockwise.
    #[must_use]
    pub fn holes(&self) -> &[Vec<DVec2>] {
        &self.holes
    }

    /// The outer ring followed by the holes.
    pub fn rings(&self) -> impl Iterator<Item = &[DVec2]> {
        std::iter::once(self.outer.as_slice()).chain(self.holes.iter().map(Vec::as_slice))
    }

    /// The area: the outer ring's less the holes'.
    pub fn area(&self) -> f64 {
        self.rings().map(signed_area).sum()
    }
}

/// How a self-intersecting or overlapping set of rings fills the plane: by the winding number
/// `w` of a point (how many times the rings wind around it counter-clockwise).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum FillRule {
    /// Inside where `w` is odd: overlaps of two rings are holes, whatever their windings.
    EvenOdd,
    /// Inside where `w ≠ 0`: rings wound the same way add up, a ring wound against its
    /// surroundings cuts a hole. SVG's and the scene format's default.
    #[default]
    NonZero,
}

/// A 2D region in the xy plane: polygons with holes, valid by construction (see the module
/// docs), with the tolerance of the boolean that made it.
///
/// ```
/// use bspcsg::Sketch;
/// let plate = Sketch::rectangle(2.0, 1.0)?;
/// let hole = Sketch::circle(0.25, 1e-3)?;
/// let part = &plate - &hole;
/// assert!((part.area() - (2.0 - hole.area())).abs() < 1e-12);
/// let solid = part.extrude(0.5)?;
/// assert!((solid.volume() - part.area() * 0.5).abs() < 1e-12);
/// # Ok::<(), bspcsg::Error>(())
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Sketch {
    regions: Vec<Region>,
    /// The knife-side epsilon of the boolean that made this sketch; zero for exact input.
    eps: f64,
}

impl Sketch {
    /// The empty sketch.
    #[must_use]
    pub fn empty() -> Self {
        Sketch::default()
    }

    /// The regions.
    #[must_use]
    pub fn regions(&self) -> &[Region] {
        &self.regions
    }

    /// True when the sketch covers nothing.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.regions.is_empty()
    }

    /// Every ring of every region: outer rings counter-clockwise, holes clockwise.
    pub fn rings(&self) -> impl Iterator<Item = &[DVec2]> {
        self.regions.iter().flat_map(Region::rings)
    }

    /// Number of vertices over all rings.
    pub fn vertex_count(&self) -> usize {
        self.rings().map(<[DVec2]>::len).sum()
    }

    /// The area covered (holes excluded).
    pub fn area(&self) -> f64 {
        self.regions.iter().map(Region::area).sum()
    }

    /// The total length of all rings, holes included.
    #[must_use]
    pub fn perimeter(&self) -> f64 {
        self.rings()
            .map(|r| {
                (0..r.len())
                    .map(|i| r[i].distance(r[(i + 1) % r.len()]))
                    .sum::<f64>()
            })
            .sum()
    }

    /// The bounding box as `[min, max]`, or `None` for the empty sketch.
    #[must_use]
    pub fn bounds(&self) -> Option<[DVec2; 2]> {
        let b = self.aabb();
        (!b.is_empty()).then(|| [b.min.truncate(), b.max.truncate()])
    }

    /// The tolerance carried from the boolean that made this sketch (zero for exact input).
    #[must_use]
    pub fn carried_eps(&self) -> f64 {
        self.eps
    }

    /// The tolerance this sketch's own queries use: the carried one, or one relative to its box.
    #[must_use]
    pub fn tolerance(&self) -> Tolerance {
        if self.eps > 0.0 {
            Tolerance::new(self.eps)
        } else {
            Tolerance::for_region(&self.aabb())
        }
    }

    /// Where `p` lies: inside, outside, or within the sketch's tolerance of an edge.
    #[must_use]
    pub fn contains(&self, p: DVec2) -> Containment {
        let eps = self.tolerance().eps();
        let mut winding = 0i64;
        for ring in self.rings() {
            for i in 0..ring.len() {
                let (a, b) = (ring[i], ring[(i + 1) % ring.len()]);
                if point_segment_distance(p, a, b) <= eps {
                    return Containment::OnBoundary;
                }
                winding += crossing(p, a, b);
            }
        }
        if winding != 0 {
            Containment::Inside
        } else {
            Containment::Outside
        }
    }

    /// Checks the validity invariants (see the module docs).
    #[must_use]
    pub fn report(&self) -> SketchReport {
        report::report(self)
    }

    /// Moves the sketch by `offset`.
    ///
    /// # Errors
    ///
    /// [`Error::InvalidParameter`](crate::Error::InvalidParameter) for a non-finite offset or a
    /// result out of range.
    pub fn translate(&self, offset: DVec2) -> Result<Sketch> {
        self.transform(DAffine2::from_translation(offset))
    }

    /// Rotates about the origin by `degrees`, counter-clockwise.
    ///
    /// # Errors
    ///
    /// [`Error::InvalidParameter`](crate::Error::InvalidParameter) for non-finite degrees or a
    /// result out of range.
    pub fn rotate(&self, degrees: f64) -> Result<Sketch> {
        if !degrees.is_finite() {
            return Err(Error::param("degrees", degrees, "must be finite"));
        }
        self.transform(DAffine2::from_angle(degrees.to_radians()))
    }

    /// Scales uniformly about the origin; a negative factor mirrors through the origin.
    ///
    /// # Errors
    ///
    /// As [`Sketch::transform`].
    pub fn scale(&self, factor: f64) -> Result<Sketch> {
        self.scale_xy(DVec2::splat(factor))
    }

    /// Scales per axis about the origin; one negative factor mirrors (rings are re-wound so the
    /// sketch stays valid).
    ///
    /// # Errors
    ///
    /// As [`Sketch::transform`].
    pub fn scale_xy(&self, factors: DVec2) -> Result<Sketch> {
        self.transform(DAffine2::from_scale(factors))
    }

    /// Mirrors across the line through the origin along `axis`.
    ///
    /// # Errors
    ///
    /// [`Error::InvalidParameter`](crate::Error::InvalidParameter) for a zero or non-finite
    /// axis.
    pub fn mirror(&self, axis: DVec2) -> Result<Sketch> {
        let d = axis.try_normalize().ok_or(Error::param(
            "axis",
            axis.length(),
            "must be a finite, non-zero vector",
        ))?;
        // Reflection across a line along d: 2 d dᵀ − I.
        let m = glam::DMat2::from_cols(
            DVec2::new(2.0 * d.x * d.x - 1.0, 2.0 * d.x * d.y),
            DVec2::new(2.0 * d.x * d.y, 2.0 * d.y * d.y - 1.0),
        );
        self.transform(DAffine2::from_mat2(m))
    }

    /// Applies an invertible affine map. A map with negative determinant re-winds every ring,
    /// so outer rings stay counter-clockwise.
    ///
    /// # Errors
    ///
    /// [`Error::InvalidParameter`](crate::Error::InvalidParameter) for a non-finite or singular
    /// map, or a result out of range.
    pub fn transform(&self, map: DAffine2) -> Result<Sketch> {
        let det = map.matrix2.determinant();
        if !(det.is_finite() && map.translation.is_finite()) {
            return Err(Error::param("transform", det, "must be finite"));
        }
        if det == 0.0 || !map.matrix2.inverse().is_finite() {
            return Err(Error::param(
                "transform",
                det,
                "must be invertible (determinant ≠ 0)",
            ));
        }
        let ring = |r: &Vec<DVec2>| {
            let mut out: Vec<DVec2> = r.iter().map(|&p| map.transform_point2(p)).collect();
            if det < 0.0 {
                out.reverse();
            }
            out
        };
        let regions = self
            .regions
            .iter()
            .map(|g| Region {
                outer: ring(&g.outer),
                holes: g.holes.iter().map(ring).collect(),
            })
            .collect();
        let out = Sketch {
            regions,
            eps: self.eps * det.abs().sqrt(),
        };
        let reach = out.aabb().max_abs();
        if !reach.is_finite() || reach > crate::geom::MAX_COORDINATE {
            return Err(Error::param(
                "transform",
                reach,
                "moves the sketch beyond the supported range of ±1e100",
            ));
        }
        // Rounding can fold a vertex onto its neighbours' line under extreme anisotropic
        // scaling; rebuild then, so the result keeps the validity invariants.
        if out.report().is_valid() {
            Ok(out)
        } else {
            Ok(Sketch::from_rings_tol(
                out.rings().map(<[DVec2]>::to_vec).collect(),
                FillRule::NonZero,
                out.eps,
            ))
        }
    }

    /// The bounding box, in the xy plane of a 3D box (z = 0).
    pub(crate) fn aabb(&self) -> Aabb {
        let mut b = Aabb::EMPTY;
        for g in &self.regions {
            for &p in &g.outer {
                b.grow(p.extend(0.0));
            }
        }
        b
    }

    fn from_regions(regions: Vec<Region>, eps: f64) -> Sketch {
        Sketch { regions, eps }
    }
}

/// Twice the signed area of a ring (positive counter-clockwise), summed relative to its first
/// vertex so rings far from the origin lose no precision.
pub(crate) fn signed_area2(ring: &[DVec2]) -> f64 {
    let Some(&o) = ring.first() else { return 0.0 };
    (1..ring.len().saturating_sub(1))
        .map(|i| (ring[i] - o).perp_dot(ring[i + 1] - o))
        .sum()
}

/// The signed area of a ring (positive counter-clockwise).
pub(crate) fn signed_area(ring: &[DVec2]) -> f64 {
    0.5 * signed_area2(ring)
}

/// The contribution of edge `a → b` to the winding number of `p` (crossing rule on a
/// horizontal ray to +x).
pub(crate) fn crossing(p: DVec2, a: DVec2, b: DVec2) -> i64 {
    if a.y <= p.y {
        if b.y > p.y && (b - a).perp_dot(p - a) > 0.0 {
            return 1;
        }
    } else if b.y <= p.y && (b - a).perp_dot(p - a) < 0.0 {
        return -1;
    }
    0
}

/// The distance from `p` to the segment `ab`.
pub(crate) fn point_segment_distance(p: DVec2, a: DVec2, b: DVec2) -> f64 {
    let d = b - a;
    let len2 = d.length_squared();
    let t = if len2 > 0.0 {
        ((p - a).dot(d) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    p.distance(a + d * t)
}

/// A point of the xy plane as a 3D point at height `z`.
pub(crate) fn lift(p: DVec2, z: f64) -> DVec3 {
    DVec3::new(p.x, p.y, z)
}
