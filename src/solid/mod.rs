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
mod convert;
mod measure;
mod ops;
mod primitives;
mod transform;

pub use boolean::{BoolOp, ParseBoolOpError, boolean, boolean_with};
pub use measure::{Containment, PointClassifier};
pub use ops::boolean_all;

use crate::geom::Tolerance;
use crate::polygon::Polygon;

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
        Solid { polygons, eps: 0.0 }
    }

    pub(crate) fn with_eps(polygons: Vec<Polygon>, eps: f64) -> Self {
        Solid { polygons, eps }
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
