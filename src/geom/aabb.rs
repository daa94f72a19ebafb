use glam::DVec3;

/// An axis-aligned bounding box. The empty box has `min = +∞`, `max = −∞`, so growing it by a
/// point gives that point's box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    /// The smallest coordinate on each axis.
    pub min: DVec3,
    /// The largest coordinate on each axis.
    pub max: DVec3,
}

impl Default for Aabb {
    fn default() -> Self {
        Aabb::EMPTY
    }
}

impl Aabb {
    /// The box that contains nothing.
    pub const EMPTY: Aabb = Aabb {
        min: DVec3::splat(f64::INFINITY),
        max: DVec3::splat(f64::NEG_INFINITY),
    };

    /// The box spanned by two corners.
    #[must_use]
    pub fn new(min: DVec3, max: DVec3) -> Self {
        Aabb { min, max }
    }

    /// The smallest box holding every point (empty for no points).
    pub fn from_points<'a>(points: impl IntoIterator<Item = &'a DVec3>) -> Self {
        let mut b = Aabb::EMPTY;
        for p in points {
            b.grow(*p);
        }
        b
    }

    /// True when the box holds no point.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        !(self.min.x <= self.max.x && self.min.y <= self.max.y && self.min.z <= self.max.z)
    }

    /// The slab test: the span `[near, far]` of `t ∈ [0, t_max]` over which the ray
    /// `origin + t·dir` lies in the box (faces included), given `inv = 1 / dir`, or `None` where
    /// it misses. An empty box is the caller's to rule out. A ray with a zero component of `dir`
    /// that starts exactly in one of the box's faces across that axis runs in that face: 0 · ∞
    /// is NaN there, and that axis then bounds nothing (an axis-aligned camera ray along a face,
    /// a segment between two points of a face, were rejected before).
    pub(crate) fn ray_span(&self, origin: DVec3, inv: DVec3, t_max: f64) -> Option<(f64, f64)> {
        let t0 = (self.min - origin) * inv;
        let t1 = (self.max - origin) * inv;
        let in_face = t0.is_nan_mask() | t1.is_nan_mask();
        let near = DVec3::select(in_face, DVec3::NEG_INFINITY, t0.min(t1));
        let far = DVec3::select(in_face, DVec3::INFINITY, t0.max(t1));
        let near = near.max_element().max(0.0);
        let far = far.min_element().min(t_max);
        (near <= far).then_some((near, far))
    }

    /// Extends the box to hold `p`.
    #[inline]
    pub fn grow(&mut self, p: DVec3) {
        self.min = self.min.min(p);
        self.max = self.max.max(p);
    }

    /// The smallest box holding both.
    #[must_use]
    pub fn union(&self, other: &Aabb) -> Aabb {
        Aabb {
            min: self.min.min(other.min),
            max: self.max.max(other.max),
        }
    }

    /// The common part of both boxes (possibly empty).
    #[must_use]
    pub fn intersection(&self, other: &Aabb) -> Aabb {
        Aabb {
            min: self.min.max(other.min),
            max: self.max.min(other.max),
        }
    }

    /// True when the boxes, each grown by `margin` on every side, share a point.
    #[inline]
    #[must_use]
    pub fn overlaps(&self, other: &Aabb, margin: f64) -> bool {
        self.min.x <= other.max.x + margin
            && other.min.x <= self.max.x + margin
            && self.min.y <= other.max.y + margin
            && other.min.y <= self.max.y + margin
            && self.min.z <= other.max.z + margin
            && other.min.z <= self.max.z + margin
    }

    /// True when `p` lies in the box grown by `margin`.
    #[must_use]
    pub fn contains_point(&self, p: DVec3, margin: f64) -> bool {
        p.cmpge(self.min - margin).all() && p.cmple(self.max + margin).all()
    }

    /// Edge lengths (zero for an empty box).
    #[must_use]
    pub fn size(&self) -> DVec3 {
        if self.is_empty() {
            DVec3::ZERO
        } else {
            self.max - self.min
        }
    }

    /// The centre (meaningless for an empty box).
    #[must_use]
    pub fn center(&self) -> DVec3 {
        (self.min + self.max) * 0.5
    }

    /// Length of the diagonal (zero for an empty box).
    #[must_use]
    pub fn diagonal(&self) -> f64 {
        self.size().length()
    }

    /// The largest absolute coordinate of any point in the box (zero for an empty box).
    #[must_use]
    pub fn max_abs(&self) -> f64 {
        if self.is_empty() {
            0.0
        } else {
            self.min.abs().max(self.max.abs()).max_element()
        }
    }

    /// The box grown by `margin` on every side.
    #[must_use]
    pub fn expanded(&self, margin: f64) -> Aabb {
        Aabb {
            min: self.min - DVec3::splat(margin),
            max: self.max + DVec3::splat(margin),
        }
    }

    /// Index (0, 1, 2) of the longest axis.
    #[must_use]
    pub fn longest_axis(&self) -> usize {
        let s = self.size();
        if s.x >= s.y && s.x >= s.z {
            0
        } else if s.y >= s.z {
            1
        } else {
            2
        }
    }
}
