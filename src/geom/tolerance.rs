use super::Aabb;

/// The one distance within which a point counts as lying on a plane.
///
/// It is relative to the size of the region where two operands meet (the intersection of their
/// bounding boxes), so a model and its copy scaled by 10⁻⁶ or 10⁶ give the same answer, scaled,
/// and a huge operand (a box out to 10³⁸) does not blur a small one. A floor keeps it above the
/// rounding error of coordinates far from the origin. See the crate docs, `# Tolerance` and
/// `# Precision`.
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
    /// The floor as a fraction of the largest coordinate magnitude in the region: 2⁻⁴³, between
    /// 512 and 1024 units in the last place of that magnitude. A split point, a moved vertex or
    /// a Newell plane is off by a few units in the last place of the coordinates it is computed
    /// from, and faces crossing at small angles multiply that, so a tolerance below this would
    /// call rounding noise a real offset.
    pub const FLOOR_RELATIVE: f64 = 1.0 / (1u64 << 43) as f64;
    /// The coarsest tolerance, as a fraction of the region's diagonal, that a boolean accepts:
    /// one part in 10⁵ (the weld then moves the surface by less than 10⁻⁴ of the region). Past it (the floor of coordinates far from the origin, or a
    /// tolerance carried from a much larger boolean, dwarfs the region) the result is marked as
    /// beyond precision (see [`crate::Solid::check_precision`]).
    pub const PRECISION_LIMIT: f64 = 1e-5;

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
        let eps = (Self::RELATIVE * region.diagonal()).max(Self::floor(region.max_abs()));
        Tolerance::new(eps)
    }

    /// The least tolerance coordinates of magnitude `magnitude` allow:
    /// `FLOOR_RELATIVE · magnitude`.
    #[must_use]
    pub fn floor(magnitude: f64) -> f64 {
        Self::FLOOR_RELATIVE * magnitude
    }

    /// The region two operands interact in: where their boxes meet, or the smaller operand
    /// where they meet only in a point (or not at all).
    #[must_use]
    pub fn region(a: &Aabb, b: &Aabb) -> Aabb {
        let meet = a.intersection(b);
        if !meet.is_empty() && meet.diagonal() > 0.0 {
            meet
        } else if a.diagonal() <= b.diagonal() {
            *a
        } else {
            *b
        }
    }

    /// The tolerance for combining two operands: relative to where their boxes meet, or to the
    /// smaller operand where they meet only in a point.
    #[must_use]
    pub fn for_operands(a: &Aabb, b: &Aabb) -> Self {
        Self::for_region(&Self::region(a, b))
    }

    /// The plane-side epsilon.
    #[inline]
    #[must_use]
    pub fn eps(&self) -> f64 {
        self.eps
    }

    /// True when this tolerance resolves a region of diagonal `diagonal` to one part in
    /// `1 / PRECISION_LIMIT` or better.
    #[must_use]
    pub fn resolves(&self, diagonal: f64) -> bool {
        self.eps <= Self::PRECISION_LIMIT * diagonal
    }

    /// The larger of two tolerances.
    #[must_use]
    pub fn max(self, other: Tolerance) -> Tolerance {
        Tolerance {
            eps: self.eps.max(other.eps),
        }
    }
}
