//! `Solid`: the polygon soup booleans work on. Every `impl Solid` lives in this folder, one file
//! per concern:
//!
//! - `mod.rs` (here): the type, its polygons and the tolerance it carries;
//! - [`primitives`]: boxes, spheres, cylinders, cones, tori, polyhedra;
//! - [`transform`]: moving, rotating, scaling, mirroring, turning inside out;
//! - [`measure`]: bounding box, volume, area, point containment;
//! - [`convert`]: to and from indexed meshes;
//! - [`boolean`]: the one boolean operation, and [`ops`]: its named wrappers and operators.

mod boolean;
mod checked;
mod convert;
mod far;
mod flat;
mod measure;
mod ops;
mod overlapping;
mod primitives;
mod transform;
mod vertex_ids;

pub use boolean::{
    BoolOp, MAX_BOOLEAN_WORK, ParseBoolOpError, WORK_PER_POLYGON, boolean, boolean_with,
};
pub use checked::{MESH_VOLUME_RELATIVE, MESH_VOLUME_TOLERANCES};
pub use measure::{Containment, PointClassifier};
pub use ops::boolean_all;
pub(crate) use ops::boolean_all_metered;

use std::sync::Arc;

use crate::error::{Error, Result};
use crate::geom::{Aabb, Tolerance};
use crate::mesh::import::MeshPolygons;
use crate::mesh::repair::Indexed;
use crate::polygon::Polygon;

use vertex_ids::VertexIds;

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
    /// The first boolean on the way to this solid that could not resolve the region its
    /// operands met in (see [`Solid::check_precision`]).
    lost: Option<PrecisionLoss>,
    /// The boolean on the way to this solid that its work meter stopped (see
    /// [`Solid::check_budget`]); the solid is then empty.
    overrun: Option<Overrun>,
    /// The polygons a boolean passed through whole, with vertex ids (see [`Indexed`]): kept
    /// only while the polygons are the boolean's own, so any change to them drops it.
    index: Option<Indexed>,
    /// The vertex ids of the polygons' corners, for a solid made from a mesh, with its
    /// polygons' boxes and hierarchy, merge floors and fan checks (see [`VertexIds`]): kept
    /// only while the polygons are the mesh's own.
    vertex_ids: Option<Arc<VertexIds>>,
}

/// A boolean whose operands met in a region too small for the tolerance it had to use: the
/// floor that the coordinates' magnitude sets, or one carried from an earlier, larger boolean,
/// is more than [`Tolerance::PRECISION_LIMIT`] of the region's diagonal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct PrecisionLoss {
    /// The diagonal of the region where the operands met.
    pub(crate) region: f64,
    /// The largest coordinate magnitude in it.
    pub(crate) magnitude: f64,
    /// The tolerance the boolean had to use.
    pub(crate) eps: f64,
}

/// A boolean stopped by its work meter: the corners of the pieces its tree builds and clipping
/// had cut (with those of the other booleans sharing the meter) when it stopped, and the limit.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Overrun {
    pub(crate) work: u64,
    pub(crate) limit: u64,
}

impl PrecisionLoss {
    /// The loss, if a tolerance `tol` does not resolve `region`.
    pub(crate) fn check(region: &Aabb, tol: Tolerance) -> Option<PrecisionLoss> {
        let d = region.diagonal();
        (!tol.resolves(d)).then(|| PrecisionLoss {
            region: d,
            magnitude: region.max_abs(),
            eps: tol.eps(),
        })
    }
}

impl Solid {
    /// The empty solid.
    #[must_use]
    pub fn empty() -> Self {
        Solid::default()
    }

    /// A solid from polygons that bound it, outward-facing. The polygons are trusted: use
    /// [`Solid::from_mesh`] for input that needs checking.
    #[must_use]
    pub fn from_polygons(polygons: Vec<Polygon>) -> Self {
        Solid {
            polygons,
            eps: 0.0,
            lost: None,
            overrun: None,
            index: None,
            vertex_ids: None,
        }
    }

    /// [`Solid::from_polygons`] for the polygons of a mesh, with their vertex ids (and whether
    /// they are discs by position: see [`MeshPolygons::discs_if_apart`]; and whether their fans
    /// span area and how small they get: see [`vertex_ids::check_fans`]).
    pub(crate) fn from_mesh_polygons(mesh: MeshPolygons) -> Self {
        let MeshPolygons {
            polygons,
            discs_if_apart,
        } = mesh;
        let mut ids = VertexIds::new(&polygons);
        ids.set_discs(discs_if_apart == Some(ids.vertex_count()));
        ids.set_fans(vertex_ids::check_fans(&polygons));
        ids.set_merge_floors(&polygons);
        ids.set_surface_index(&polygons);
        Solid {
            vertex_ids: Some(Arc::new(ids)),
            ..Solid::from_polygons(polygons)
        }
    }

    pub(crate) fn with_eps(polygons: Vec<Polygon>, eps: f64, lost: Option<PrecisionLoss>) -> Self {
        Solid {
            polygons,
            eps,
            lost,
            overrun: None,
            index: None,
            vertex_ids: None,
        }
    }

    /// The empty solid a boolean stopped by its work meter leaves (see [`Solid::check_budget`]).
    pub(crate) fn overran(overrun: Overrun) -> Self {
        Solid {
            overrun: Some(overrun),
            ..Solid::default()
        }
    }

    /// The mark of a boolean stopped on the way to this solid, if any.
    pub(crate) fn overrun(&self) -> Option<Overrun> {
        self.overrun
    }

    /// The solid with what its boolean knew of its topology (see [`Indexed`]).
    pub(crate) fn with_index(mut self, index: Option<Indexed>) -> Self {
        self.index = index;
        self
    }

    /// Takes the polygons and their vertex ids, if the solid has them.
    pub(crate) fn into_parts(self) -> (Vec<Polygon>, Option<Arc<VertexIds>>) {
        (self.polygons, self.vertex_ids)
    }

    /// The index of the polygons passed through whole, for `to_mesh`.
    pub(crate) fn index(&self) -> Option<&Indexed> {
        self.index.as_ref()
    }

    /// Whether this solid was made within the precision contract (the crate docs,
    /// `# Precision`): every boolean on the way to it resolved the region where its operands
    /// met to one part in 10⁵ ([`Tolerance::PRECISION_LIMIT`]), and a solid no boolean made is
    /// resolved so at its own size and place.
    ///
    /// Booleans never fail, so a result past the limit is marked instead, and the mark passes to
    /// every solid made from it; this is where it turns into an error. The command line and
    /// [`crate::Scene::to_solid`] call it before writing anything.
    ///
    /// ```
    /// use bspcsg::{Error, Solid};
    /// use bspcsg::glam::DVec3;
    ///
    /// // Two unit cubes overlapping by half: exact at 10⁸ from the origin…
    /// let at = |x: f64| Solid::cube(1.0)?.translate(DVec3::new(x, 0.0, 0.0));
    /// let near = &at(1e8)? | &at(1e8 + 0.5)?;
    /// assert!(near.check_precision().is_ok());
    /// assert!((near.volume() - 1.5).abs() < 1e-6);
    /// // …but at 10¹¹ a coordinate is only known to 1.5·10⁻⁵: refused, not silently wrong.
    /// let far = &at(1e11)? | &at(1e11 + 0.5)?;
    /// assert!(matches!(far.check_precision(), Err(Error::BeyondPrecision { .. })));
    /// # Ok::<(), bspcsg::Error>(())
    /// ```
    ///
    /// # Errors
    ///
    /// [`Error::BeyondPrecision`] with the region, its distance from the origin and the
    /// tolerance it needed.
    pub fn check_precision(&self) -> Result<()> {
        let lost = self.lost.or_else(|| {
            if self.eps > 0.0 || self.is_empty() {
                return None;
            }
            let b = self.bbox();
            PrecisionLoss::check(&b, Tolerance::for_region(&b))
        });
        match lost {
            None => Ok(()),
            Some(l) => Err(Error::BeyondPrecision {
                region: l.region,
                magnitude: l.magnitude,
                eps: l.eps,
            }),
        }
    }

    /// Whether every boolean on the way to this solid finished within its work budget: the
    /// corners of the pieces its tree builds and clipping cut, at most [`MAX_BOOLEAN_WORK`] or
    /// [`WORK_PER_POLYGON`] per polygon of its operands, whichever is more (for the n-ary
    /// reductions, [`boolean_all`], all their booleans together). Ordinary booleans cut a few
    /// corners per polygon near the other operand; faces of different operands that nearly
    /// coincide over a wide area (copies of one detailed outline a little apart) are cut at
    /// every plane of the other's faces they cross, and the pieces grow faster than any
    /// estimate from the operands' size can tell.
    ///
    /// Booleans never fail, so one past its budget stops, leaves the empty solid, and marks it;
    /// the mark passes to every solid made from it (the booleans after it do no work), and this
    /// is where it turns into an error. The command line, [`Solid::to_checked_mesh`] and
    /// [`crate::Scene::to_solid`] call it before anything is written.
    ///
    /// # Errors
    ///
    /// [`Error::BeyondBudget`] with the work done when the boolean stopped and the limit.
    pub fn check_budget(&self) -> Result<()> {
        match self.overrun {
            None => Ok(()),
            Some(o) => Err(Error::BeyondBudget {
                work: o.work,
                limit: o.limit,
            }),
        }
    }

    /// The precision loss this solid carries, if any.
    pub(crate) fn precision_loss(&self) -> Option<PrecisionLoss> {
        self.lost
    }

    /// The bounding polygons.
    #[must_use]
    pub fn polygons(&self) -> &[Polygon] {
        &self.polygons
    }

    /// Takes the bounding polygons.
    #[must_use]
    pub fn into_polygons(self) -> Vec<Polygon> {
        self.polygons
    }

    /// True when the solid has no polygons.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.polygons.is_empty()
    }

    /// Number of polygons.
    #[must_use]
    pub fn polygon_count(&self) -> usize {
        self.polygons.len()
    }

    /// Number of polygon corners (a vertex shared by several polygons counts in each).
    #[must_use]
    pub fn corner_count(&self) -> usize {
        self.polygons.iter().map(|p| p.vertices().len()).sum()
    }

    /// The tolerance carried from the boolean that made this solid (zero for exact input).
    #[must_use]
    pub fn carried_eps(&self) -> f64 {
        self.eps
    }

    /// The tolerance this solid's own queries (point containment, `to_mesh`) use: the one
    /// carried from the boolean that made it, which was relative to where its operands met; for
    /// a solid no boolean made, one relative to its box. Never relative to the box of a boolean's
    /// result: a huge operand would make it swallow the small one's detail.
    #[must_use]
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
}
