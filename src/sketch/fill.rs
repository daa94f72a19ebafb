//! Rings that may cross, overlap or nest, filled by a [`FillRule`]: every edge is cut where
//! another meets it, the pieces form a planar graph whose faces get winding numbers (counted
//! from the unbounded face, one step per edge crossed), and the edges between a filled and an
//! empty face are the boundary.

use glam::DVec2;

use super::assemble::{self, next_around_faces};
use super::{FillRule, Sketch, crossing};
use crate::disjoint_sets::DisjointSets;
use crate::geom::{Aabb, Tolerance};

impl Sketch {
    /// The region that `rings` enclose under `rule`. Rings may wind either way, cross
    /// themselves and each other, overlap and nest; repeated points and zero-length edges are
    /// ignored. The result is valid (see the module docs).
    ///
    /// ```
    /// use bspcsg::{FillRule, Sketch};
    /// use bspcsg::glam::DVec2;
    /// // A pentagram: its centre winds twice.
    /// let star: Vec<DVec2> = (0..5)
    ///     .map(|k| {
    ///         let a = std::f64::consts::TAU * (2 * k) as f64 / 5.0;
    ///         DVec2::new(a.cos(), a.sin())
    ///     })
    ///     .collect();
    /// let nonzero = Sketch::polygon(&star, FillRule::NonZero)?;
    /// let evenodd = Sketch::polygon(&star, FillRule::EvenOdd)?;
    /// assert_eq!(nonzero.regions().len(), 1);
    /// assert!(evenodd.area() < nonzero.area());
    /// # Ok::<(), bspcsg::Error>(())
    /// ```
    ///
    /// # Errors
    ///
    /// [`Error::InvalidParameter`](crate::Error::InvalidParameter) for a ring with fewer than
    /// three points or a coordinate that is not finite or out of range.
    pub fn from_rings(rings: &[Vec<DVec2>], rule: FillRule) -> crate::Result<Sketch> {
        for ring in rings {
            for p in ring {
                if !p.is_finite() || p.abs().max_element() > crate::geom::MAX_COORDINATE {
                    return Err(crate::Error::param(
                        "points",
                        p.abs().max_element(),
                        "must be finite and at most 1e100 in magnitude",
                    ));
                }
            }
        }
        Ok(Sketch::from_rings_tol(rings.to_vec(), rule, 0.0))
    }

    /// One ring filled by `rule` (see [`Sketch::from_rings`]).
    ///
    /// # Errors
    ///
    /// As [`Sketch::from_rings`].
    pub fn polygon(points: &[DVec2], rule: FillRule) -> crate::Result<Sketch> {
        Sketch::from_rings(&[points.to_vec()], rule)
    }

    /// [`Sketch::from_rings`] for checked input, with a tolerance of at least `carried`.
    pub(super) fn from_rings_tol(rings: Vec<Vec<DVec2>>, rule: FillRule, carried: f64) -> Sketch {
        let mut segs: Vec<[DVec2; 2]> = Vec::new();
        let mut bbox = Aabb::EMPTY;
        for ring in &rings {
            for i in 0..ring.len() {
                let (a, b) = (ring[i], ring[(i + 1) % ring.len()]);
                bbox.grow(a.extend(0.0));
                if a != b {
                    segs.push([a, b]);
                }
            }
        }
        if segs.is_empty() {
            return Sketch::empty();
        }
        let eps = Tolerance::for_region(&bbox)
            .max(Tolerance::new(carried))
            .eps();
        let pieces = split_at_meetings(&segs, eps);
        let boundary = filled_boundary(&pieces, rule, eps);
        // The own tolerance of exact input is recomputed from its box; carry only what came in.
        Sketch::from_regions(assemble::regions(&boundary, eps), carried)
    }
}

/// Candidate pairs of segments whose boxes come within `eps`, by sorting on x and sweeping.
pub(super) fn box_pairs(segs: &[[DVec2; 2]], eps: f64, mut visit: impl FnMut(usize, usize)) {
    let lo: Vec<DVec2> = segs.iter().map(|s| s[0].min(s[1])).collect();
    let hi: Vec<DVec2> = segs.iter().map(|s| s[0].max(s[1])).collect();
    let mut order: Vec<u32> = (0..segs.len() as u32).collect();
    order.sort_unstable_by(|&i, &j| lo[i as usize].x.total_cmp(&lo[j as usize].x));
    for (k, &i) in order.iter().enumerate() {
        let i = i as usize;
        for &j in &order[k + 1..] {
            let j = j as usize;
            if lo[j].x > hi[i].x + eps {
                break;
            }
            if lo[j].y <= hi[i].y + eps && lo[i].y <= hi[j].y + eps {
                visit(i, j);
            }
        }
    }
}

/// Every segment cut where another crosses it or ends on it (within `eps`); a crossing point
/// is computed once and shared by both segments.
fn split_at_meetings(segs: &[[DVec2; 2]], eps: f64) -> Vec<[DVec2; 2]> {
    let mut cuts: Vec<Vec<(f64, DVec2)>> = vec![Vec::new(); segs.len()];
    box_pairs(segs, eps, |i, j| {
        let (p, q) = (segs[i], segs[j]);
        for (s, t, ks) in [(p, q, i), (q, p, j)] {
            // Ends of t on s's interior.
            for e in t {
                if let Some(u) = interior_param(s, e, eps) {
                    cuts[ks].push((u, e));
                }
            }
        }
        if let Some(x) = crossing_point(p, q, eps) {
            for (s, ks) in [(p, i), (q, j)] {
                if let Some(u) = interior_param(s, x, eps) {
                    cuts[ks].push((u, x));
                }
            }
        }
    });
    let mut out = Vec::with_capacity(segs.len());
    for (s, mut c) in segs.iter().zip(cuts) {
        c.sort_by(|x, y| x.0.total_cmp(&y.0));
        let mut prev = s[0];
        for (_, p) in c {
            out.push([prev, p]);
            prev = p;
        }
        out.push([prev, s[1]]);
    }
    out
}

/// The parameter of `p` along `s` when `p` lies within `eps` of `s` and farther than `eps`
/// from both its ends.
fn interior_param(s: [DVec2; 2], p: DVec2, eps: f64) -> Option<f64> {
    let d = s[1] - s[0];
    let len2 = d.length_squared();
    if len2 == 0.0 || p.distance(s[0]) <= eps || p.distance(s[1]) <= eps {
        return None;
    }
    let u = (p - s[0]).dot(d) / len2;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    (p.distance(s[0] + d * u) <= eps).then_some(u)
}

/// The point where `p` and `q` cross properly (each one's ends strictly on both sides of the
/// other's line).
fn crossing_point(p: [DVec2; 2], q: [DVec2; 2], eps: f64) -> Option<DVec2> {
    let side = |s: [DVec2; 2], x: DVec2| {
        let d = s[1] - s[0];
        d.perp_dot(x - s[0]) / d.length()
    };
    let (dp0, dp1) = (side(q, p[0]), side(q, p[1]));
    let (dq0, dq1) = (side(p, q[0]), side(p, q[1]));
    let apart = |a: f64, b: f64| (a > eps && b < -eps) || (a < -eps && b > eps);
    if !(apart(dp0, dp1) && apart(dq0, dq1)) {
        return None;
    }
    let t = dp0 / (dp0 - dp1);
    Some(p[0] + (p[1] - p[0]) * t)
}

/// The directed edges between filled and empty faces of the arrangement of `pieces`.
fn filled_boundary(pieces: &[[DVec2; 2]], rule: FillRule, eps: f64) -> Vec<[DVec2; 2]> {
    let graph = assemble::weld(pieces, eps);
    let pts = &graph.points;
    let m = graph.edges.len();
    // Half-edge 2k runs along edge k, 2k + 1 against it.
    let mut half: Vec<(u32, u32)> = Vec::with_capacity(2 * m);
    for &(a, b, _) in &graph.edges {
        half.push((a, b));
        half.push((b, a));
    }
    let (next, _) = next_around_faces(pts, &half);
    let (face, face_area) = label_faces(pts, &half, &next);
    // Connected components, each with its unbounded face (the most negative one).
    let mut sets = DisjointSets::new(pts.len());
    for &(a, b, _) in &graph.edges {
        sets.union(a as usize, b as usize);
    }
    let mut comp_faces: crate::hash::FxHashMap<usize, Vec<u32>> = Default::default();
    let mut face_comp = vec![usize::MAX; face_area.len()];
    for (h, &(a, _)) in half.iter().enumerate() {
        let f = face[h] as usize;
        if face_comp[f] == usize::MAX {
            let c = sets.find(a as usize);
            face_comp[f] = c;
            comp_faces.entry(c).or_default().push(f as u32);
        }
    }
    // Edges and boxes per component, for the windings of one component's outside.
    let mut comp_edges: crate::hash::FxHashMap<usize, Vec<usize>> = Default::default();
    for (k, &(a, _, _)) in graph.edges.iter().enumerate() {
        comp_edges.entry(sets.find(a as usize)).or_default().push(k);
    }
    let comp_box: Vec<(usize, [DVec2; 2])> = comp_edges
        .iter()
        .map(|(&c, ks)| {
            let mut lo = DVec2::splat(f64::INFINITY);
            let mut hi = DVec2::splat(f64::NEG_INFINITY);
            for &k in ks {
                let (a, b, _) = graph.edges[k];
                for p in [pts[a as usize], pts[b as usize]] {
                    lo = lo.min(p);
                    hi = hi.max(p);
                }
            }
            (c, [lo, hi])
        })
        .collect();
    let mut winding: Vec<i64> = vec![i64::MIN; face_area.len()];
    for (&c, faces) in &comp_faces {
        let outer = faces
            .iter()
            .copied()
            .min_by(|&x, &y| face_area[x as usize].total_cmp(&face_area[y as usize]))
            .unwrap_or(faces[0]);
        // The other components' winding around one vertex of this one.
        let probe = pts[graph.edges[comp_edges[&c][0]].0 as usize];
        let mut base = 0i64;
        for (d, [lo, hi]) in &comp_box {
            if *d == c || !(probe.cmpge(*lo).all() && probe.cmple(*hi).all()) {
                continue;
            }
            for &k in &comp_edges[d] {
                let (a, b, n) = graph.edges[k];
                base += crossing(probe, pts[a as usize], pts[b as usize]) * n as i64;
            }
        }
        winding[outer as usize] = base;
    }
    propagate_windings(&face, &graph.edges, &mut winding);
    let filled = |w: i64| match rule {
        FillRule::EvenOdd => w.rem_euclid(2) == 1,
        FillRule::NonZero => w != 0,
    };
    let mut out = Vec::new();
    for (k, &(a, b, _)) in graph.edges.iter().enumerate() {
        let left = filled(winding[face[2 * k] as usize]);
        let right = filled(winding[face[2 * k + 1] as usize]);
        let (pa, pb) = (pts[a as usize], pts[b as usize]);
        match (left, right) {
            (true, false) => out.push([pa, pb]),
            (false, true) => out.push([pb, pa]),
            _ => {}
        }
    }
    out
}

/// The faces of a half-edge graph (`next` walks each face): every half-edge's face, and each
/// face's doubled signed area (negative for the unbounded face of a component).
fn label_faces(pts: &[DVec2], half: &[(u32, u32)], next: &[u32]) -> (Vec<u32>, Vec<f64>) {
    let mut face = vec![u32::MAX; half.len()];
    let mut face_area: Vec<f64> = Vec::new();
    for h in 0..half.len() {
        if face[h] != u32::MAX {
            continue;
        }
        let f = face_area.len() as u32;
        let (mut area, origin) = (0.0, pts[half[h].0 as usize]);
        let mut g = h;
        while face[g] == u32::MAX {
            face[g] = f;
            let (a, b) = half[g];
            area += (pts[a as usize] - origin).perp_dot(pts[b as usize] - origin);
            g = next[g] as usize;
        }
        face_area.push(area);
    }
    (face, face_area)
}

/// Fills in the windings not yet known (`i64::MIN`) from the known ones, across edges:
/// crossing half-edge h (2k along edge k, 2k + 1 against it) from its right face to its left
/// adds the edge's count in h's direction.
fn propagate_windings(face: &[u32], edges: &[(u32, u32, i32)], winding: &mut [i64]) {
    let mut face_halves: Vec<Vec<u32>> = vec![Vec::new(); winding.len()];
    for (h, &f) in face.iter().enumerate() {
        face_halves[f as usize].push(h as u32);
    }
    let mut queue: Vec<u32> = (0..winding.len() as u32)
        .filter(|&f| winding[f as usize] != i64::MIN)
        .collect();
    while let Some(f) = queue.pop() {
        let w = winding[f as usize];
        for &h in &face_halves[f as usize] {
            // h has face f on its left; its twin has the neighbour on its left.
            let twin = h ^ 1;
            let g = face[twin as usize] as usize;
            if winding[g] != i64::MIN {
                continue;
            }
            let count = edges[(h / 2) as usize].2 as i64;
            let along = if h % 2 == 0 { count } else { -count };
            // left(h) = right(h) + along  ⇒  right(h) = left(h) − along.
            winding[g] = w - along;
            queue.push(g as u32);
        }
    }
}
