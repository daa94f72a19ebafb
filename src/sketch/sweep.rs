//! Sketches swept into solids: extrusion along +z (with optional twist and top scale) and
//! revolution about the y axis. Side walls are quads where they are planar and triangle pairs
//! where they are not (twist, per-axis scale); caps are the sketch's regions triangulated by the
//! crate's constrained Delaunay triangulation, holes kept.

use std::f64::consts::TAU;

use glam::{DMat2, DVec2, DVec3};

use super::{Region, Sketch, lift};
use crate::error::{Error, Result};
use crate::geom::triangulate::triangulate_boundary;
use crate::hash::{KeyedHashMap, key};
use crate::polygon::Polygon;
use crate::primitives::{MAX_SEGMENTS, positive};
use crate::solid::Solid;

/// The twist per slice that [`ExtrudeOptions::slices`] of `None` aims for, in degrees.
pub const TWIST_DEGREES_PER_SLICE: f64 = 2.0;

/// How [`Sketch::extrude_with`] shapes the prism.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ExtrudeOptions {
    /// Rotation of the top relative to the bottom about +z, in degrees (counter-clockwise seen
    /// from above); any finite value. Each slice turns by `twist / slices`.
    pub twist: f64,
    /// Slices along the height. `None`: one without twist, else one per
    /// [`TWIST_DEGREES_PER_SLICE`] of twist. The walls between slices are ruled surfaces cut
    /// into triangles, so the volume converges to area × height as slices grow.
    pub slices: Option<u32>,
    /// Scale of the top relative to the bottom, about the sketch's origin, per axis. Each
    /// factor is ≥ 0; `[0, 0]` brings the top to a point (a cone or pyramid). One factor of 0
    /// alone (a wedge) is refused.
    pub scale_top: DVec2,
    /// Centre the prism on z = 0 (`z ∈ [−h/2, h/2]`) instead of standing it on it (`[0, h]`).
    pub center: bool,
}

impl Default for ExtrudeOptions {
    fn default() -> Self {
        ExtrudeOptions {
            twist: 0.0,
            slices: None,
            scale_top: DVec2::ONE,
            center: false,
        }
    }
}

impl Sketch {
    /// The prism over the sketch from z = 0 to z = `height`.
    ///
    /// # Errors
    ///
    /// As [`Sketch::extrude_with`].
    pub fn extrude(&self, height: f64) -> Result<Solid> {
        self.extrude_with(height, &ExtrudeOptions::default())
    }

    /// The extrusion with twist, top scale, slices and centring from `options`.
    ///
    /// ```
    /// use bspcsg::{ExtrudeOptions, Sketch};
    /// use bspcsg::glam::DVec2;
    /// let square = Sketch::rectangle(1.0, 1.0)?;
    /// let pyramid = square.extrude_with(
    ///     3.0,
    ///     &ExtrudeOptions { scale_top: DVec2::ZERO, ..Default::default() },
    /// )?;
    /// assert!((pyramid.volume() - 1.0).abs() < 1e-12);
    /// # Ok::<(), bspcsg::Error>(())
    /// ```
    ///
    /// # Errors
    ///
    /// [`Error::InvalidParameter`](crate::Error::InvalidParameter) for a height or option out
    /// of range.
    pub fn extrude_with(&self, height: f64, options: &ExtrudeOptions) -> Result<Solid> {
        positive("height", height)?;
        let ExtrudeOptions {
            twist,
            slices,
            scale_top,
            center,
        } = *options;
        if !twist.is_finite() {
            return Err(Error::param("twist", twist, "must be finite"));
        }
        for s in scale_top.to_array() {
            if !(s.is_finite() && s >= 0.0) {
                return Err(Error::param("scale_top", s, "must be finite and ≥ 0"));
            }
        }
        let apex = scale_top == DVec2::ZERO;
        if !apex && scale_top.min_element() == 0.0 {
            return Err(Error::param(
                "scale_top",
                0.0,
                "may be 0 on both axes (a point) but not on one alone",
            ));
        }
        let n = match slices {
            Some(0) => return Err(Error::param("slices", 0.0, "must be at least 1")),
            Some(n) if n > MAX_SEGMENTS => {
                return Err(Error::param("slices", n as f64, "must be at most 16384"));
            }
            Some(n) => n,
            None => ((twist.abs() / TWIST_DEGREES_PER_SLICE).ceil() as u32).clamp(1, MAX_SEGMENTS),
        } as usize;
        if self.is_empty() {
            return Ok(Solid::empty());
        }
        let z0 = if center { -0.5 * height } else { 0.0 };
        let at = |k: usize| -> (DMat2, f64) {
            let t = k as f64 / n as f64;
            let s = DVec2::ONE.lerp(scale_top, t);
            let m = DMat2::from_angle((twist * t).to_radians()) * DMat2::from_diagonal(s);
            (m, if k == n { z0 + height } else { z0 + height * t })
        };
        // Walls are planar when every slice is a uniform scale of the bottom.
        let planar = twist == 0.0 && scale_top.x == scale_top.y;
        let mut polygons = Vec::new();
        for region in &self.regions {
            // Positions per slice, per ring vertex.
            let slices: Vec<Vec<Vec<DVec3>>> = (0..=n)
                .map(|k| {
                    let (m, z) = at(k);
                    region
                        .rings()
                        .map(|r| r.iter().map(|&p| lift(m * p, z)).collect())
                        .collect()
                })
                .collect();
            for (ri, ring) in region.rings().enumerate() {
                let len = ring.len();
                for i in 0..len {
                    let j = (i + 1) % len;
                    for k in 0..n {
                        let (a0, b0) = (slices[k][ri][i], slices[k][ri][j]);
                        let (a1, b1) = (slices[k + 1][ri][i], slices[k + 1][ri][j]);
                        if apex && k + 1 == n {
                            polygons.push(face(&[a0, b0, b1])?);
                        } else if planar {
                            polygons.push(face(&[a0, b0, b1, a1])?);
                        } else {
                            // The wall is the bilinear (ruled) patch between the two edges:
                            // four triangles about its centre follow it to second order, where
                            // either diagonal alone folds it in or out by a first-order amount.
                            let c = 0.25 * (a0 + b0 + b1 + a1);
                            for (p, q) in [(a0, b0), (b0, b1), (b1, a1), (a1, a0)] {
                                polygons.push(face(&[p, q, c])?);
                            }
                        }
                    }
                }
            }
            let bottom = cap(region, |p| lift(p, 0.0))?;
            let (m0, zb) = at(0);
            for t in &bottom {
                polygons.push(face(&[
                    lift(m0 * t[2], zb),
                    lift(m0 * t[1], zb),
                    lift(m0 * t[0], zb),
                ])?);
            }
            if !apex {
                let (mn, zt) = at(n);
                for t in &bottom {
                    polygons.push(face(&t.map(|p| lift(mn * p, zt)))?);
                }
            }
        }
        Ok(Solid::from_polygons(polygons))
    }

    /// The solid swept by turning the sketch about the y axis by `angle_deg` (in (0, 360];
    /// right-handed, so +x turns towards −z), with `segments` steps per full turn (a partial
    /// turn takes its share, at least one). The sketch's x is the distance from the axis and
    /// must be ≥ 0 (within the tolerance, which snaps to the axis); edges on the axis bound
    /// nothing and are left out, so a profile touching the axis closes without slivers. A full
    /// turn closes on itself; a partial one is capped by the sketch at both ends.
    ///
    /// ```
    /// use bspcsg::Sketch;
    /// use bspcsg::glam::DVec2;
    /// // A 1 × 2 rectangle from x = 1 to 2: a tube of volume 2π·1.5·2 = 6π.
    /// let ring = Sketch::rectangle(1.0, 2.0)?.translate(DVec2::new(1.5, 0.0))?;
    /// let tube = ring.revolve(360.0, 256)?;
    /// assert!((tube.volume() - 6.0 * std::f64::consts::PI).abs() < 2e-3);
    /// # Ok::<(), bspcsg::Error>(())
    /// ```
    ///
    /// # Errors
    ///
    /// [`Error::InvalidParameter`](crate::Error::InvalidParameter) for an angle or segment
    /// count out of range, or a sketch that crosses the axis.
    pub fn revolve(&self, angle_deg: f64, segments: u32) -> Result<Solid> {
        if !(angle_deg.is_finite() && angle_deg > 0.0 && angle_deg <= 360.0) {
            return Err(Error::param(
                "angle",
                angle_deg,
                "must be in (0, 360] degrees",
            ));
        }
        if !(3..=MAX_SEGMENTS).contains(&segments) {
            return Err(Error::param(
                "segments",
                segments as f64,
                "must be between 3 and 16384",
            ));
        }
        if self.is_empty() {
            return Ok(Solid::empty());
        }
        let eps = self.tolerance().eps();
        let min_x = self.aabb().min.x;
        if min_x < -eps {
            return Err(Error::param(
                "sketch",
                min_x,
                "reaches x < 0: a revolved profile must lie in x ≥ 0 (intersect it with a \
                 half-plane first)",
            ));
        }
        let full = angle_deg == 360.0;
        let steps = if full {
            segments as usize
        } else {
            ((segments as f64 * angle_deg / 360.0).ceil() as usize).max(1)
        };
        let angle = if full { TAU } else { angle_deg.to_radians() };
        let turn: Vec<(f64, f64)> = (0..=steps)
            .map(|j| {
                if full && j == steps {
                    (1.0, 0.0)
                } else {
                    let a = angle * j as f64 / steps as f64;
                    (a.cos(), a.sin())
                }
            })
            .collect();
        let on_axis = |p: DVec2| p.x <= eps;
        let place = |p: DVec2, j: usize| {
            if on_axis(p) {
                DVec3::new(0.0, p.y, 0.0)
            } else {
                let (c, s) = turn[j];
                DVec3::new(p.x * c, p.y, -p.x * s)
            }
        };
        let mut polygons = Vec::new();
        for region in &self.regions {
            for ring in region.rings() {
                let len = ring.len();
                for i in 0..len {
                    let (a, b) = (ring[i], ring[(i + 1) % len]);
                    if on_axis(a) && on_axis(b) {
                        continue;
                    }
                    for j in 0..steps {
                        let quad = if on_axis(a) {
                            vec![place(a, j), place(b, j + 1), place(b, j)]
                        } else if on_axis(b) {
                            vec![place(a, j), place(a, j + 1), place(b, j)]
                        } else {
                            vec![place(a, j), place(a, j + 1), place(b, j + 1), place(b, j)]
                        };
                        polygons.push(face(&quad)?);
                    }
                }
            }
            if !full {
                let tris = cap(region, |p| lift(p, 0.0))?;
                for t in &tris {
                    polygons.push(face(&t.map(|p| place(p, 0)))?);
                    polygons.push(face(&[
                        place(t[2], steps),
                        place(t[1], steps),
                        place(t[0], steps),
                    ])?);
                }
            }
        }
        Ok(Solid::from_polygons(polygons))
    }
}

/// The triangles of a region (counter-clockwise in the xy plane), by constrained Delaunay
/// triangulation of its rings; vertices shared by two rings are one vertex.
fn cap(region: &Region, to3: impl Fn(DVec2) -> DVec3) -> Result<Vec<[DVec2; 3]>> {
    let mut index: KeyedHashMap<[u64; 3], u32> = KeyedHashMap::default();
    let mut points: Vec<DVec2> = Vec::new();
    let mut edges: Vec<(u32, u32)> = Vec::new();
    for ring in region.rings() {
        let ids: Vec<u32> = ring
            .iter()
            .map(|&p| {
                *index.entry(key(p.extend(0.0))).or_insert_with(|| {
                    points.push(p);
                    points.len() as u32 - 1
                })
            })
            .collect();
        for i in 0..ids.len() {
            edges.push((ids[i], ids[(i + 1) % ids.len()]));
        }
    }
    let positions: Vec<DVec3> = points.iter().map(|&p| to3(p)).collect();
    let tris = triangulate_boundary(&positions, DVec3::Z, &edges).ok_or(Error::param(
        "sketch",
        region.area(),
        "has a region whose cap could not be triangulated (edges crossing within rounding)",
    ))?;
    Ok(tris
        .into_iter()
        .map(|t| t.map(|i| points[i as usize]))
        .collect())
}

/// A wall or cap face, or an error where rounding left it without a plane.
fn face(vertices: &[DVec3]) -> Result<Polygon> {
    Polygon::new(vertices, 0).ok_or(Error::param(
        "sketch",
        vertices[0].length(),
        "gives a face with no computable plane (a feature below the tolerance)",
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A hole touching the outer ring at a vertex the outer ring writes `0.0` and the hole
    /// `-0.0`: one CDT vertex, so the cap is the ring's seven points and covers the region.
    #[test]
    fn negative_zero_vertex_is_one_cap_vertex() {
        let d = DVec2::new;
        let region = Region {
            outer: vec![
                d(-2.0, -2.0),
                d(0.0, -2.0),
                d(2.0, -2.0),
                d(2.0, 2.0),
                d(-2.0, 2.0),
            ],
            holes: vec![vec![d(-0.0, -2.0), d(-1.0, 0.0), d(1.0, 0.0)]],
        };
        assert_eq!(region.area(), 14.0);
        let tris = cap(&region, |p| p.extend(0.0)).unwrap();
        let corners: std::collections::BTreeSet<[u64; 2]> = tris
            .iter()
            .flatten()
            .map(|p| [p.x.to_bits(), p.y.to_bits()])
            .collect();
        assert_eq!(corners.len(), 7, "{corners:?}");
        assert!(!corners.contains(&[(-0.0f64).to_bits(), (-2.0f64).to_bits()]));
        let area: f64 = tris
            .iter()
            .map(|[a, b, c]| 0.5 * (*b - *a).perp_dot(*c - *a))
            .sum();
        assert!((area - 14.0).abs() < 1e-12, "{area}");
        // The boundary walked once is a simple polygon of eight corners (the pinch twice).
        assert_eq!(tris.len(), 6, "{tris:?}");
    }
}
