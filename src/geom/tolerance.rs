use super::Aabb;

/// The one distance within which a point counts as lying on a plane.
///
/// It is relative to the size of the region where two operands meet (the intersection of their
/// bounding boxes), so a model and its copy scaled by 10⁻⁶ or 10⁶ give the same answer, scaled,
/// and a huge operand (a box out to 10³⁸) does not blur a small one. A floor keeps it above the
/// rounding error of coordinates far from the origin. See the crate docs, `# Tolerance`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tolerance {
    eps: f64,
}

impl Tolerance {
    /// The plane-side epsilon as a fraction of the interaction region's diagonal. Small on
    /// purpose: faces that really are 10⁻⁸ of the model apart must not be called coplanar, or
    /// fragments get routed by a plane far from where its polygon lies; and with planes anchored
    /// near their polygons (see [`crate::Plane`]) rounding stays near 10⁻¹⁶ of the model size.
    pub const RELATIVE: f64 = 1e-12;
    /// The floor as a fraction of the largest coordinate magnitude in the region: about 8000
    /// units in the last place, well above the error of a plane evaluation or an edge split.
    pub const FLOOR_RELATIVE: f64 = 1.0 / (1u64 << 40) as f64;

    /// A tolerance of exactly `eps` (callers that know better).
    #[must_use]
    pub fn new(eps: f64) -> Self {
        Tolerance {
            eps: eps.max(f64::MIN_POSITIVE),
        }
    }

    /// The tolerance for a region: `max(RELATIVE · diagonal, FLOOR_RELATIVE · max |coordinate|)`.
    #[must_use]
    pub fn for_region(region: &Aabb) -> Self {
        let eps = (Self::RELATIVE * region.diagonal()).max(Self::FLOOR_RELATIVE * region.max_abs());
        Tolerance::new(eps)
    }

    /// The tolerance for combining two operands: relative to where their boxes meet, or to the
    /// smaller operand where they meet only in a point.
    #[must_use]
    pub fn for_operands(a: &Aabb, b: &Aabb) -> Self {
        let meet = a.intersection(b);
        let region = if !meet.is_empty() && meet.diagonal() > 0.0 {
            meet
        } else if a.diagonal() <= b.diagonal() {
            *a
        } else {
            *b
        };
        Self::for_region(&region)
    }

    /// The plane-side epsilon.
    #[inline]
    #[must_use]
    pub fn eps(&self) -> f64 {
        self.eps
    }

    /// The larger of two tolerances.
    #[must_use]
    pub fn max(self, other: Tolerance) -> Tolerance {
        Tolerance {
            eps: self.eps.max(other.eps),
        }
    }
}
