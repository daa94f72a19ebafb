//! What a solid measures: its box, volume and area, and where points lie relative to it.

use glam::DVec3;

use super::Solid;
use crate::bsp::{Label, Tree};
use crate::geom::Aabb;
use crate::polygon::{Polygon, bbox_of, volume_of};

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
    /// The bounding box.
    #[must_use]
    pub fn bbox(&self) -> Aabb {
        bbox_of(&self.polygons)
    }

    /// Signed volume by the divergence theorem, in f64, summed relative to the box centre.
    #[must_use]
    pub fn volume(&self) -> f64 {
        volume_of(&self.polygons)
    }

    /// Total surface area.
    pub fn area(&self) -> f64 {
        self.polygons.iter().map(Polygon::area).sum()
    }

    /// Where `p` lies: inside, outside or on the boundary (within the solid's tolerance).
    /// For many points, build a [`PointClassifier`] once.
    #[must_use]
    pub fn contains(&self, p: DVec3) -> Containment {
        self.classifier().classify(p)
    }

    /// A BSP tree of this solid for classifying many points.
    #[must_use]
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
    #[must_use]
    pub fn classify(&self, p: DVec3) -> Containment {
        match self.tree.classify_point(p) {
            Some(Label::Inside) => Containment::Inside,
            Some(Label::Outside) => Containment::Outside,
            None => Containment::OnBoundary,
        }
    }
}
