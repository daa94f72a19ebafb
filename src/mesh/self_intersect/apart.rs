//! A triangle against a box, for pruning the pairs of thin triangles. A long thin triangle's
//! box is mostly empty: the slivers of a cone's apex fan each span the cone's height, so every
//! one's box overlaps every one of its base's; the triangle itself meets only the boxes near it.

use glam::DVec3;

use crate::geom::Aabb;

/// Below this ratio of a triangle's doubled area to its box's largest face, [`apart`] is tried
/// at every node of the tree a query enters, so not for every triangle: at 1/4 reading a UV
/// sphere of 40,000 triangles took 23 % more instructions than without it, at 1/16 3 %.
const THIN: f64 = 1.0 / 16.0;

/// Whether triangle `t` is thin enough in its box for [`apart`] to be worth its cost: its area
/// under a thirty-second of its box's largest face (a sliver of aspect over about 30; the
/// triangles of a cone of 100 sides are thinner, those near a UV sphere's poles about so).
pub(super) fn thin([a, b, c]: [DVec3; 3]) -> bool {
    let s = Aabb::from_points(&[a, b, c]).size();
    let face = (s.x * s.y).max(s.y * s.z).max(s.z * s.x);
    (b - a).cross(c - a).length() < THIN * face
}

/// True when triangle `t` and box `b` are surely apart: some plane along the triangle or along
/// one of its edges and an axis leaves them on its two sides with room to spare for rounding.
/// False says nothing (they may or may not meet). The box's own three axes are left to the
/// caller's box overlap test.
///
/// The separating-axis test for a triangle and a box (Akenine-Möller): the triangle's normal
/// and each edge crossed with each axis. Any direction may be tried, so computing the axes in
/// floating point costs nothing in rigour; the projections are rounded, and a gap counts only
/// beyond `32 ε` of the magnitudes involved, which bounds the rounding of the differences from
/// the box's centre and of the three-term dot products (each a few `ε` of those magnitudes).
pub(super) fn apart(t: [DVec3; 3], b: &Aabb) -> bool {
    let frame = Frame::new(t, b);
    let edges = [
        frame.v[1] - frame.v[0],
        frame.v[2] - frame.v[1],
        frame.v[0] - frame.v[2],
    ];
    frame.separates(edges[0].cross(edges[1]))
        || edges.iter().any(|e| {
            frame.separates(DVec3::new(0.0, -e.z, e.y))
                || frame.separates(DVec3::new(e.z, 0.0, -e.x))
                || frame.separates(DVec3::new(-e.y, e.x, 0.0))
        })
}

/// A triangle and a box, both taken from the box's centre.
struct Frame {
    v: [DVec3; 3],
    half: DVec3,
    reach: DVec3,
}

impl Frame {
    fn new(t: [DVec3; 3], b: &Aabb) -> Frame {
        let centre = b.center();
        let half = b.size() * 0.5;
        let v = t.map(|p| p - centre);
        let reach = centre.abs() + half + v[0].abs().max(v[1].abs()).max(v[2].abs());
        Frame { v, half, reach }
    }

    /// Whether the projections on `axis` are apart by more than rounding can explain.
    fn separates(&self, axis: DVec3) -> bool {
        let p = self.v.map(|q| q.dot(axis));
        let radius = self.half.dot(axis.abs());
        let room = 32.0 * f64::EPSILON * self.reach.dot(axis.abs());
        p[0].min(p[1]).min(p[2]) > radius + room || p[0].max(p[1]).max(p[2]) < -radius - room
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_sliver_is_apart_from_boxes_its_own_box_overlaps() {
        // A sliver from (0, 0, 1) down to the x axis near (1, 0, 0), and boxes in the plane
        // z = 0 from the origin towards points of the unit circle.
        let sliver = [
            DVec3::new(0.0, 0.0, 1.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(1.0, 0.01, 0.0),
        ];
        assert!(thin(sliver));
        let towards = |deg: f64| {
            let a = deg.to_radians();
            Aabb::from_points(&[DVec3::ZERO, DVec3::new(a.cos(), a.sin(), 0.0)])
        };
        let own = Aabb::from_points(&sliver);
        for deg in [30.0, 60.0, 120.0, 200.0, 300.0] {
            assert!(own.overlaps(&towards(deg), 0.0), "{deg}");
            assert!(apart(sliver, &towards(deg)), "{deg}");
        }
        // Boxes it does meet: flat under its foot, around its middle, and one touching only
        // its corner (1, 0, 0).
        let under = Aabb::from_points(&[DVec3::new(0.5, -0.1, 0.0), DVec3::new(1.5, 0.1, 0.0)]);
        assert!(!apart(sliver, &under));
        let mid = Aabb::from_points(&[DVec3::new(0.4, -0.1, 0.4), DVec3::new(0.6, 0.1, 0.6)]);
        assert!(!apart(sliver, &mid));
        let foot = Aabb::from_points(&[DVec3::new(1.0, 0.0, 0.0), DVec3::new(2.0, 1.0, -1.0)]);
        assert!(!apart(sliver, &foot));
        // A fat triangle is not thin.
        assert!(!thin([DVec3::ZERO, DVec3::X, DVec3::Y]));
    }
}
