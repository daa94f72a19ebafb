use glam::DVec3;

/// An oriented plane: the points `x` with `normal · (x − anchor) = 0`; `normal` has unit length
/// and points to the front (outside) half-space. The fields are private so that the normal stays
/// a unit vector and `offset` agrees with `anchor`; make planes with [`Plane::from_points`] or
/// [`Plane::from_point_normal`].
///
/// Distances are measured from `anchor`, a point on the plane near the polygon it came from,
/// not from the origin: far from the origin `normal · x − offset` loses the low digits of both
/// terms (about 3·10⁻¹² at 13 000), while `x − anchor` is exact for nearby points. That matters
/// where two faces meet at a tiny angle, as an edge's cut point then moves by the distance
/// error divided by the angle. `offset = normal · anchor` is kept for comparisons.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plane {
    /// Unit normal, pointing to the front side.
    pub(crate) normal: DVec3,
    /// Signed distance of the plane from the origin along `normal` (`normal · anchor`).
    pub(crate) offset: f64,
    /// A point on the plane that distances are measured from.
    pub(crate) anchor: DVec3,
}

/// Where a point or polygon lies relative to a plane, within a tolerance.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Side {
    /// Entirely on the side the normal points to.
    Front,
    /// Entirely on the other side.
    Back,
    /// Within the tolerance of the plane.
    Coplanar,
    /// Parts on both sides (polygons only).
    Spanning,
}

impl Plane {
    /// The unit normal, pointing to the front (outside) half-space.
    #[must_use]
    #[inline]
    pub fn normal(&self) -> DVec3 {
        self.normal
    }

    /// The signed distance of the plane from the origin along the normal.
    #[must_use]
    #[inline]
    pub fn offset(&self) -> f64 {
        self.offset
    }

    /// The point on the plane that distances are measured from.
    #[must_use]
    #[inline]
    pub fn anchor(&self) -> DVec3 {
        self.anchor
    }

    /// The plane of a polygon by Newell's method, which averages over all vertices and so stays
    /// well defined where three chosen points would be collinear. Vertices wind counter-clockwise
    /// seen from the front. `None` when the points span no area or are not finite.
    #[must_use]
    pub fn from_points(points: &[DVec3]) -> Option<Plane> {
        if points.len() < 3 {
            return None;
        }
        // Work relative to the centroid and scaled to unit size: far from the origin this keeps
        // the products precise, and for huge coordinates it keeps them from overflowing.
        let centroid = points.iter().copied().sum::<DVec3>() / points.len() as f64;
        let reach = points
            .iter()
            .map(|&p| (p - centroid).abs().max_element())
            .fold(0.0, f64::max);
        if !(reach.is_finite() && reach > 0.0) {
            return None;
        }
        let scale = 1.0 / reach;
        let mut n = DVec3::ZERO;
        let mut prev = (*points.last().unwrap() - centroid) * scale;
        for &p in points {
            let cur = (p - centroid) * scale;
            n.x += (prev.y - cur.y) * (prev.z + cur.z);
            n.y += (prev.z - cur.z) * (prev.x + cur.x);
            n.z += (prev.x - cur.x) * (prev.y + cur.y);
            prev = cur;
        }
        let normal = n.try_normalize()?;
        Some(Plane::through(centroid, normal))
    }

    /// The plane through `point` with `normal` (normalised here); `None` for a zero or
    /// non-finite normal.
    #[must_use]
    pub fn from_point_normal(point: DVec3, normal: DVec3) -> Option<Plane> {
        Some(Plane::through(point, normal.try_normalize()?))
    }

    /// The plane through `anchor` with a unit `normal`.
    pub(crate) fn through(anchor: DVec3, normal: DVec3) -> Plane {
        Plane {
            normal,
            offset: normal.dot(anchor),
            anchor,
        }
    }

    /// Signed distance of `p`: positive in front.
    #[inline]
    #[must_use]
    pub fn distance(&self, p: DVec3) -> f64 {
        self.normal.dot(p - self.anchor)
    }

    /// Which side `p` lies on, `Coplanar` within `eps`.
    #[inline]
    #[must_use]
    pub fn side_of(&self, p: DVec3, eps: f64) -> Side {
        let d = self.distance(p);
        if d > eps {
            Side::Front
        } else if d < -eps {
            Side::Back
        } else {
            Side::Coplanar
        }
    }

    /// The same plane facing the other way.
    #[must_use]
    pub fn flipped(&self) -> Plane {
        Plane {
            normal: -self.normal,
            offset: -self.offset,
            anchor: self.anchor,
        }
    }

    /// True when `other` is this very plane, facing either way: the same bits, as every
    /// fragment of a polygon keeps its parent's plane. A polygon lies in its own plane by
    /// definition, however far its vertices reach; testing its vertices instead could find a
    /// huge polygon "spanning" its own plane by rounding and split it forever.
    #[inline]
    #[must_use]
    pub fn is_same_or_flipped(&self, other: &Plane) -> bool {
        self.anchor == other.anchor
            && ((self.normal == other.normal && self.offset == other.offset)
                || (self.normal == -other.normal && self.offset == -other.offset))
    }
}
