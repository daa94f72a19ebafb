use glam::DVec3;

/// An oriented plane: the points `x` with `normal · x = offset`; `normal` has unit length and
/// points to the front (outside) half-space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plane {
    /// Unit normal, pointing to the front side.
    pub normal: DVec3,
    /// Signed distance of the plane from the origin along `normal`.
    pub offset: f64,
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
        Some(Plane {
            normal,
            offset: normal.dot(centroid),
        })
    }

    /// The plane through `point` with unit `normal`.
    pub fn from_point_normal(point: DVec3, normal: DVec3) -> Option<Plane> {
        let normal = normal.try_normalize()?;
        Some(Plane {
            normal,
            offset: normal.dot(point),
        })
    }

    /// Signed distance of `p`: positive in front.
    #[inline]
    pub fn distance(&self, p: DVec3) -> f64 {
        self.normal.dot(p) - self.offset
    }

    /// Which side `p` lies on, `Coplanar` within `eps`.
    #[inline]
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
        }
    }

    /// True when both planes are the same oriented plane within `eps` at points within
    /// `radius` of the origin-side foot of the plane.
    pub fn approx_eq(&self, other: &Plane, eps: f64, radius: f64) -> bool {
        (self.offset - other.offset).abs() <= eps
            && (self.normal - other.normal).length() * radius.max(1.0) <= eps
    }
}
