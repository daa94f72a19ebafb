//! The validity check of a sketch: counts of each kind of defect, all zero for a valid one.

use glam::DVec2;

use super::fill::box_pairs;
use super::{Sketch, crossing, signed_area2};
use crate::hash::{KeyedHashMap, key};

/// What [`Sketch::report`] finds. A sketch is valid when every count is zero.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SketchReport {
    /// Rings with fewer than three vertices.
    pub short_rings: usize,
    /// Edges of zero length (a vertex repeated in a row).
    pub zero_length_edges: usize,
    /// Outer rings wound clockwise or holes wound counter-clockwise.
    pub misoriented_rings: usize,
    /// Pairs of edges that cross, or where a vertex lies on another edge without being one of
    /// its ends (within the sketch's tolerance). Rings may share a vertex.
    pub crossings: usize,
    /// Holes not inside their region's outer ring.
    pub stray_holes: usize,
    /// Vertices (not shared with another ring) within the tolerance of the line through
    /// their neighbours: runs that should have been merged.
    pub collinear_vertices: usize,
}

impl SketchReport {
    /// True when nothing is wrong.
    #[must_use]
    pub fn is_valid(&self) -> bool {
        *self == SketchReport::default()
    }
}

pub(super) fn report(s: &Sketch) -> SketchReport {
    let eps = s.tolerance().eps();
    let mut r = SketchReport::default();
    let mut uses: KeyedHashMap<[u64; 3], u32> = KeyedHashMap::default();
    for ring in s.rings() {
        for p in ring {
            *uses.entry(key(p.extend(0.0))).or_default() += 1;
        }
    }
    let mut segs: Vec<[DVec2; 2]> = Vec::new();
    for g in s.regions() {
        for (k, ring) in g.rings().enumerate() {
            let n = ring.len();
            if n < 3 {
                r.short_rings += 1;
                continue;
            }
            let area = signed_area2(ring);
            if (k == 0) != (area > 0.0) {
                r.misoriented_rings += 1;
            }
            for i in 0..n {
                let (p, v, q) = (ring[(i + n - 1) % n], ring[i], ring[(i + 1) % n]);
                if v == q {
                    r.zero_length_edges += 1;
                } else {
                    segs.push([v, q]);
                }
                let base = q - p;
                let shared = uses[&key(v.extend(0.0))] > 1;
                if !shared
                    && base.length() > 0.0
                    && (base.perp_dot(v - p) / base.length()).abs() <= eps
                {
                    r.collinear_vertices += 1;
                }
            }
        }
        for hole in &g.holes {
            let Some(&p) = hole.first() else { continue };
            // A hole vertex may touch the outer ring; test the middle of its first edge.
            let probe = if hole.len() > 1 {
                0.5 * (p + hole[1])
            } else {
                p
            };
            let w: i64 = (0..g.outer.len())
                .map(|i| crossing(probe, g.outer[i], g.outer[(i + 1) % g.outer.len()]))
                .sum();
            if w == 0 {
                r.stray_holes += 1;
            }
        }
    }
    box_pairs(&segs, eps, |i, j| {
        if segments_conflict(segs[i], segs[j], eps) {
            r.crossings += 1;
        }
    });
    r
}

/// True when two edges meet anywhere but at a shared end: a proper crossing, or an end of one
/// within `eps` of the other without being that edge's end.
fn segments_conflict(p: [DVec2; 2], q: [DVec2; 2], eps: f64) -> bool {
    let near = |s: [DVec2; 2], x: DVec2| {
        if x == s[0] || x == s[1] {
            return false;
        }
        super::point_segment_distance(x, s[0], s[1]) <= eps
    };
    if q.iter().any(|&x| near(p, x)) || p.iter().any(|&x| near(q, x)) {
        return true;
    }
    let side = |s: [DVec2; 2], x: DVec2| (s[1] - s[0]).perp_dot(x - s[0]);
    let apart = |a: f64, b: f64| (a > 0.0 && b < 0.0) || (a < 0.0 && b > 0.0);
    apart(side(q, p[0]), side(q, p[1])) && apart(side(p, q[0]), side(p, q[1]))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sketch::Region;

    /// A ring vertex written `-0.0` and one written `0.0` are one point: the notch vertex
    /// (0, 0) lies on the straight left side of the square, which counts as collinear only
    /// if no other ring uses it, and the triangle touching it from the left writes it `-0.0`.
    #[test]
    fn negative_zero_vertex_is_shared() {
        let d = DVec2::new;
        let square = Region {
            outer: vec![
                d(0.0, -1.0),
                d(1.0, -1.0),
                d(1.0, 1.0),
                d(0.0, 1.0),
                d(0.0, 0.0),
            ],
            holes: Vec::new(),
        };
        let mut triangle = Region {
            outer: vec![d(-1.0, -0.5), d(-0.0, 0.0), d(-1.0, 0.5)],
            holes: Vec::new(),
        };
        let sketch = |regions: Vec<Region>| Sketch { regions, eps: 0.0 };
        assert_eq!(
            report(&sketch(vec![square.clone(), triangle.clone()])),
            SketchReport::default()
        );
        // The check itself: with the triangle moved off the vertex, it is collinear.
        triangle.outer[1] = d(-0.5, 0.0);
        let alone = report(&sketch(vec![square, triangle]));
        assert_eq!(alone.collinear_vertices, 1, "{alone:?}");
    }
}
