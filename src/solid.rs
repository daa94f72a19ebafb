//! `Solid`: the polygon soup booleans work on, with its transforms and measurements.

use glam::{DAffine3, DMat3, DQuat, DVec3, EulerRot};

use crate::bsp::{Label, Tree};
use crate::error::{Error, Result};
use crate::geom::{Aabb, Plane, Tolerance};
use crate::mesh::Mesh;
use crate::polygon::{Polygon, Vertices};

/// A solid bounded by convex planar polygons whose normals point outward.
///
/// Primitives, meshes and booleans make solids; [`Solid::to_mesh`] turns one into an indexed
/// triangle mesh. A solid made by a boolean remembers the tolerance that made it, so later
/// operations never use a smaller one (see the crate docs, `# Tolerance`).
#[derive(Clone, Debug, Default)]
pub struct Solid {
    polygons: Vec<Polygon>,
    /// The plane-side epsilon of the boolean that made this solid; zero for an exact input.
    eps: f64,
}

/// Where a point lies relative to a solid.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Containment {
    /// Strictly inside.
    Inside,
    /// Strictly outside.
    Outside,
    /// On the boundary, within the solid's tolerance.
    OnBoundary,
}

impl Solid {
    /// The empty solid.
    pub fn empty() -> Self {
        Solid::default()
    }

    /// A solid from polygons that bound it, outward-facing. The polygons are trusted: use
    /// [`Solid::from_mesh`] for input that needs checking.
    pub fn from_polygons(polygons: Vec<Polygon>) -> Self {
        Solid { polygons, eps: 0.0 }
    }

    pub(crate) fn with_eps(polygons: Vec<Polygon>, eps: f64) -> Self {
        Solid { polygons, eps }
    }

    /// The bounding polygons.
    pub fn polygons(&self) -> &[Polygon] {
        &self.polygons
    }

    /// Takes the bounding polygons.
    pub fn into_polygons(self) -> Vec<Polygon> {
        self.polygons
    }

    /// True when the solid has no polygons.
    pub fn is_empty(&self) -> bool {
        self.polygons.is_empty()
    }

    /// Number of polygons.
    pub fn polygon_count(&self) -> usize {
        self.polygons.len()
    }

    /// Number of polygon corners (a vertex shared by several polygons counts in each).
    pub fn corner_count(&self) -> usize {
        self.polygons.iter().map(|p| p.vertices().len()).sum()
    }

    /// The tolerance carried from the boolean that made this solid (zero for exact input).
    pub fn carried_eps(&self) -> f64 {
        self.eps
    }

    /// The tolerance this solid's own queries (point containment, `to_mesh`) use: the one
    /// carried from the boolean that made it, which was relative to where its operands met; for
    /// a solid no boolean made, one relative to its box. Never relative to the box of a boolean's
    /// result: a huge operand would make it swallow the small one's detail.
    pub fn tolerance(&self) -> Tolerance {
        if self.eps > 0.0 {
            Tolerance::new(self.eps)
        } else {
            Tolerance::for_region(&self.bbox())
        }
    }

    /// Sets the source id of every polygon (materials ride on it through booleans).
    #[must_use]
    pub fn with_source(mut self, source: u32) -> Self {
        for p in &mut self.polygons {
            p.set_source(source);
        }
        self
    }

    /// The bounding box.
    pub fn bbox(&self) -> Aabb {
        let mut b = Aabb::EMPTY;
        for p in &self.polygons {
            for &v in p.vertices() {
                b.grow(v);
            }
        }
        b
    }

    /// Signed volume by the divergence theorem, in f64, summed relative to the box centre.
    pub fn volume(&self) -> f64 {
        let apex = self.bbox().center();
        self.polygons
            .iter()
            .map(|p| p.signed_volume6(apex))
            .sum::<f64>()
            / 6.0
    }

    /// Total surface area.
    pub fn area(&self) -> f64 {
        self.polygons.iter().map(Polygon::area).sum()
    }

    /// The solid turned inside out: every polygon flipped (the complement, for booleans).
    #[must_use]
    pub fn inverse(mut self) -> Self {
        for p in &mut self.polygons {
            p.flip();
        }
        self
    }

    /// Moves the solid by `offset`. Non-finite offsets, and offsets that would move a vertex
    /// beyond [`MAX_COORDINATE`](crate::MAX_COORDINATE), are refused.
    pub fn translate(self, offset: DVec3) -> Result<Self> {
        finite_vec("offset", offset)?;
        in_range(self.map_rigid(DQuat::IDENTITY, offset))
    }

    /// Rotates the solid about the origin by a quaternion (normalised here).
    pub fn rotate(self, rotation: DQuat) -> Result<Self> {
        let q = normalized(rotation).ok_or(Error::param(
            "rotation",
            rotation.length(),
            "must be a finite, non-zero quaternion",
        ))?;
        in_range(self.map_rigid(q, DVec3::ZERO))
    }

    /// Rotates by `degrees` about `axis` (right-handed).
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
    pub fn rotate_euler(self, degrees: DVec3) -> Result<Self> {
        finite_vec("degrees", degrees)?;
        in_range(self.map_rigid(euler_degrees(degrees), DVec3::ZERO))
    }

    /// Scales uniformly about the origin. The factor must be finite and non-zero; a negative one
    /// mirrors the solid and its winding is reversed so it stays outward-facing.
    pub fn scale(self, factor: f64) -> Result<Self> {
        self.scale_xyz(DVec3::splat(factor))
    }

    /// Scales per axis about the origin (see [`Solid::scale`]).
    pub fn scale_xyz(self, factors: DVec3) -> Result<Self> {
        self.transform(DAffine3::from_scale(factors))
    }

    /// Applies any invertible affine map. A map with negative determinant reverses each
    /// polygon's winding so the solid stays outward-facing.
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
        }
    }

    /// Where `p` lies: inside, outside or on the boundary (within the solid's tolerance).
    /// For many points, build a [`PointClassifier`] once.
    pub fn contains(&self, p: DVec3) -> Containment {
        self.classifier().classify(p)
    }

    /// A BSP tree of this solid for classifying many points.
    pub fn classifier(&self) -> PointClassifier {
        PointClassifier {
            tree: Tree::build(self.polygons.clone(), self.tolerance().eps()),
        }
    }
}

/// Classifies points against a solid in `O(log n)` each (see [`Solid::classifier`]).
#[derive(Clone, Debug)]
pub struct PointClassifier {
    tree: Tree,
}

impl PointClassifier {
    /// Where `p` lies relative to the solid.
    pub fn classify(&self, p: DVec3) -> Containment {
        match self.tree.classify_point(p) {
            Some(Label::Inside) => Containment::Inside,
            Some(Label::Outside) => Containment::Outside,
            None => Containment::OnBoundary,
        }
    }
}

/// The rotation of Euler angles in degrees, X first, then Y, then Z, about fixed axes.
pub(crate) fn euler_degrees(degrees: DVec3) -> DQuat {
    let r = degrees * (std::f64::consts::PI / 180.0);
    DQuat::from_euler(EulerRot::ZYX, r.z, r.y, r.x)
}

/// The solid, or an error where a transform moved it beyond the supported range.
fn in_range(solid: Solid) -> Result<Solid> {
    let reach = solid.bbox().max_abs();
    if reach > crate::geom::MAX_COORDINATE || !reach.is_finite() {
        Err(Error::param(
            "transform",
            reach,
            "moves the solid beyond the supported range of ±1e100",
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

impl From<&Solid> for Mesh {
    fn from(solid: &Solid) -> Mesh {
        solid.to_mesh()
    }
}
