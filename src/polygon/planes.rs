//! Planes known beside a polygon's own: the meet of three planes, computed the same by every
//! polygon that needs it, and the planes of the neighbours across a polygon's edges.

use std::sync::Arc;

use glam::DVec3;

use crate::geom::Plane;
use crate::hash::{KeyedHashMap, key};

use super::dd::{self, Dd};
use super::side::NEAR_PARALLEL;
use super::{Polygon, UNKNOWN};

/// The point where three planes meet, the same bits whichever order they come in and whichever
/// way they face: `None` where they do not meet in one point.
///
/// Of the three, the two closest to parallel give a line (the one whose position is least
/// certain: a rounding error over their angle), which the third cuts. Every point on the line
/// where two nearly coincident faces cross is so computed from one and the same line, so all of
/// them, from either operand, lie on it; cut at the third plane, each is as certain as that
/// plane's angle to the line allows. Where the third crosses both of the others below
/// [`NEAR_PARALLEL`] too, that angle is about their sines' product and the cut a rounding error
/// over it along the line: the three are solved in double-double instead (see [`solve`]).
pub(crate) fn meet(p: &Plane, q: &Plane, r: &Plane) -> Option<DVec3> {
    let mut planes = [canonical(p), canonical(q), canonical(r)];
    planes.sort_by_key(plane_bits);
    let pairs = [(0, 1, 2), (0, 2, 1), (1, 2, 0)];
    let (i, j, k) = pairs
        .into_iter()
        .min_by(|&(i, j, _), &(x, y, _)| {
            let s = planes[i].normal.cross(planes[j].normal).length_squared();
            let t = planes[x].normal.cross(planes[y].normal).length_squared();
            s.total_cmp(&t)
        })
        .expect("three pairs");
    let sine = |a: &Plane, b: &Plane| a.normal.cross(b.normal).length();
    let (pi, pj, pk) = (&planes[i], &planes[j], &planes[k]);
    if sine(pi, pk).max(sine(pj, pk)) < NEAR_PARALLEL {
        return solve(pi, pj, pk);
    }
    let (on_line, d) = line_of(pi, pj)?;
    let slope = pk.normal.dot(d);
    if slope == 0.0 {
        return None;
    }
    let t = pk.normal.dot(pk.anchor - on_line) / slope;
    let x = on_line + d * t;
    x.is_finite().then_some(x)
}

/// The point on planes `pi`, `pj` and `pk`, relative to `pi`'s anchor and `pi`'s normal: `y`
/// with `nᵢ · y = 0`, `(nⱼ − nᵢ) · y = hⱼ` and `(nₖ − nᵢ) · y = hₖ`, where `hₓ = nₓ · (aₓ − aᵢ)`
/// (each normal facing the way `nᵢ` does), by Cramer's rule in double-double.
///
/// For nearly parallel planes the differences of the normals are exact and every product is
/// carried to about 106 bits, so the point is the meet of the three planes as stored, rounded
/// once. In doubles it was not: the line of two planes crossing at a sine `s` lies a rounding
/// error over `s` across their faces (ε · 0.3 / 1.5·10⁻¹¹ ≈ 5·10⁻⁶ for a sphere's facets turned
/// 10⁻⁹°), and a third nearly parallel plane cut it a rounding error over *its* sine further
/// along, so the three lines of three such planes, each computed alone, did not pass through
/// one point: where one operand's face was cut along two of them from their meet and the
/// other's along the third, the cuts parted by up to 10⁻⁶ (three copies of a sphere, two turned
/// 10⁻⁹° about different axes, intersected: 606 boundary edges).
fn solve(pi: &Plane, pj: &Plane, pk: &Plane) -> Option<DVec3> {
    let ni = pi.normal;
    let (nj, nk) = (aligned(pj.normal, ni), aligned(pk.normal, ni));
    let h = |n: DVec3, a: DVec3| dd::dot(n, dd::diff(a, pi.anchor));
    let (hj, hk) = (h(nj, pj.anchor), h(nk, pk.anchor));
    let (mj, mk) = (nj - ni, nk - ni);
    let det = dd::dot(ni, dd::cross(mj, mk));
    let (cj, ck) = (dd::cross(mk, ni), dd::cross(ni, mj));
    let mut x = [0.0; 3];
    for (axis, out) in x.iter_mut().enumerate() {
        let y = hj.mul(cj[axis]).add(hk.mul(ck[axis])).div(det)?;
        *out = Dd::from(pi.anchor[axis]).add(y).value();
    }
    let x = DVec3::from_array(x);
    x.is_finite().then_some(x)
}

/// The line where two planes cross, as a point on it and its direction (the cross product of
/// the normals, up to sign, not normalised): `pi` and `pj` canonical (see [`canonical`]) and sorted by
/// [`plane_bits`], so every caller gets the same bits for the same pair. `None` for parallel
/// planes.
///
/// The direction is `nᵢ × (nⱼ − nᵢ)`, the same as `nᵢ × nⱼ` but exact to rounding relative
/// to its length: for nearly parallel planes the difference is exact, while `nᵢ × nⱼ` cancels
/// terms near 1 to leave an error of ε in each component, the direction off by ε over the
/// sine (2e-7 rad at 5.9e-10), so that points on it drifted off the line `Crossing::side`
/// judges by (2e-7 across a unit face).
fn line_of(pi: &Plane, pj: &Plane) -> Option<(DVec3, DVec3)> {
    let nj = aligned(pj.normal, pi.normal);
    let d = pi.normal.cross(nj - pi.normal);
    let dd = d.length_squared();
    if dd == 0.0 || !dd.is_finite() {
        return None;
    }
    // From `pi`'s anchor: the point of the line nearest it.
    let o = pi.anchor;
    let h = nj.dot(pj.anchor - o);
    let on_line = o + d.cross(pi.normal) * (h / dd);
    on_line.is_finite().then_some((on_line, d))
}

/// Where two nearly parallel planes cross, once for both: the point on their crossing line
/// that [`meet`] starts from, and the difference of their canonical normals, from which a point
/// of either plane is judged against the other by its distance across the line within its
/// own plane (see [`Crossing::side`]).
pub(crate) struct Crossing {
    on_line: DVec3,
    /// The difference of the two normals, both facing the way the first of the pair (by
    /// [`plane_bits`] of [`canonical`]) does: exact, their components being close.
    apart: DVec3,
    /// Whether `cut` faces against its normal in `apart`.
    flip: bool,
    /// How far [`Crossing::side`] of a point on the line may read off zero by the rounding of
    /// the line's own position (see [`Crossing::rounding`]).
    rounding: f64,
}

impl Crossing {
    /// The crossing of a polygon's plane `own` and a cutting plane `cut`; `None` if they do not
    /// cross.
    pub(crate) fn new(own: &Plane, cut: &Plane) -> Option<Crossing> {
        let (o, c) = (canonical(own), canonical(cut));
        let (first, second) = if plane_bits(&o) <= plane_bits(&c) {
            (&o, &c)
        } else {
            (&c, &o)
        };
        let (on_line, _) = line_of(first, second)?;
        // Both facing the way the first does, so the two planes' crossings agree to the bit.
        let (own_n, cut_n) = (
            aligned(o.normal, first.normal),
            aligned(c.normal, first.normal),
        );
        let rounding =
            LINE_NOISE_ULPS * f64::EPSILON * (second.anchor - first.anchor).abs().max_element();
        Some(Crossing {
            on_line,
            apart: cut_n - own_n,
            flip: cut_n != cut.normal,
            rounding,
        })
    }

    /// How far from zero [`Crossing::side`] may read for a point on the line, by the rounding
    /// of the line's position alone: its point comes from the second plane's distance from
    /// the first's anchor, rounded by a few ulps of their separation, over the sine across the
    /// line, which `side` multiplies by the sine again.
    pub(crate) fn rounding(&self) -> f64 {
        self.rounding
    }

    /// The signed distance from `cut` of the point of `own` at `v` (a vertex of a polygon in
    /// `own`): `cut.distance(v)` less the part that comes of `v` lying a rounding error off
    /// `own`. That part is about ε |v − anchor|, which across the crossing line is that over
    /// the angle (7e-9 on faces crossing at 1.4e-9 rad), while this is exact to a rounding error
    /// of the angle times |v − line|. The polygons of the other plane, cut by this one, get
    /// exactly the negation for the same point: both operands' faces are cut on one line.
    pub(crate) fn side(&self, v: DVec3) -> f64 {
        let s = self.apart.dot(v - self.on_line);
        if self.flip { -s } else { s }
    }
}

/// Units in the last place of the two planes' anchors' separation that the rounding of their
/// crossing line's position amounts to in [`Crossing::side`].
const LINE_NOISE_ULPS: f64 = 8.0;

/// `n`, or its reverse, whichever faces the way `reference` does: two nearly parallel planes'
/// canonical normals can face opposite ways (a first component of 1e-10 and −1e-10).
#[inline]
fn aligned(n: DVec3, reference: DVec3) -> DVec3 {
    if n.dot(reference) < 0.0 { -n } else { n }
}

/// The plane facing the way whose normal's first non-zero component is positive.
pub(super) fn canonical(p: &Plane) -> Plane {
    let n = p.normal;
    let first = if n.x != 0.0 {
        n.x
    } else if n.y != 0.0 {
        n.y
    } else {
        n.z
    };
    if first < 0.0 { p.flipped() } else { *p }
}

pub(super) fn plane_bits(p: &Plane) -> [u64; 6] {
    [
        p.normal.x.to_bits(),
        p.normal.y.to_bits(),
        p.normal.z.to_bits(),
        p.anchor.x.to_bits(),
        p.anchor.y.to_bits(),
        p.anchor.z.to_bits(),
    ]
}

/// The polygon holding each directed edge of `polygons`, keyed by its ends' positions bit for
/// bit (the last one where several do).
pub(crate) fn edge_owners(polygons: &[Polygon]) -> KeyedHashMap<([u64; 3], [u64; 3]), u32> {
    let corners = polygons.iter().map(|p| p.vertices.len()).sum();
    let mut owner = KeyedHashMap::with_capacity_and_hasher(corners, Default::default());
    for (i, p) in polygons.iter().enumerate() {
        let v = &p.vertices;
        for k in 0..v.len() {
            owner.insert((key(v[k]), key(v[(k + 1) % v.len()])), i as u32);
        }
    }
    owner
}

/// Gives every edge of `polygons` whose plane is not known the plane of the polygon across it
/// (the one holding the same edge the other way, same ends bit for bit). Edges with no such
/// neighbour stay unknown, and are cut by interpolation.
pub(crate) fn attach_edge_planes(polygons: &mut [Polygon]) {
    let known =
        |p: &Polygon| !p.edges().is_empty() && p.edges().iter().all(|e| e.normal != DVec3::ZERO);
    if polygons.iter().all(known) {
        return;
    }
    let owner = edge_owners(polygons);
    let mut found: Vec<(usize, Arc<[Plane]>)> = Vec::new();
    for (i, p) in polygons.iter().enumerate() {
        if known(p) {
            continue;
        }
        let v = &p.vertices;
        let edges = (0..v.len())
            .map(|k| match p.edge_plane(k) {
                Some(e) => *e,
                None => owner
                    .get(&(key(v[(k + 1) % v.len()]), key(v[k])))
                    .map_or(UNKNOWN, |&j| polygons[j as usize].plane),
            })
            .collect();
        found.push((i, edges));
    }
    for (i, edges) in found {
        polygons[i].edges = Some(edges);
    }
}

/// [`attach_edge_planes`], then gives each edge still unknown the plane of a polygon of
/// `others` across it. A boolean clips only the polygons near the other operand; their
/// neighbours away from it are `others`. An edge cut where a nearly parallel face crosses it is
/// cut at the [`meet`] of its planes only if its neighbour's plane is known (else by
/// interpolation, off along the crossing line by a rounding error over the angle: 6e-7 on a box
/// turned 1e-10°), and every other point on that crossing line is a meet on the same line.
pub(crate) fn attach_edge_planes_among<'a>(
    polygons: &mut [Polygon],
    others: impl Iterator<Item = &'a Polygon> + Clone,
) {
    attach_edges_by_ends(polygons, others.clone());
    attach_edges_across_t_junctions(polygons, others);
}

/// [`attach_edge_planes`], then the planes of `others` across edges still unknown, same ends
/// bit for bit.
fn attach_edges_by_ends<'a>(polygons: &mut [Polygon], others: impl Iterator<Item = &'a Polygon>) {
    attach_edge_planes(polygons);
    let mut missing: KeyedHashMap<([u64; 3], [u64; 3]), (u32, u32)> = KeyedHashMap::default();
    for (i, p) in polygons.iter().enumerate() {
        let v = &p.vertices;
        for k in 0..v.len() {
            if p.edge_plane(k).is_none() {
                missing.insert((key(v[(k + 1) % v.len()]), key(v[k])), (i as u32, k as u32));
            }
        }
    }
    if missing.is_empty() {
        return;
    }
    // Most far polygons touch none of these edges: the filter settles them without hashing
    // their edges (which was 6 % of a boolean of two 256 × 128 spheres).
    let filter = PositionFilter::new(missing.keys().map(|&(start, _)| start));
    let mut found: Vec<(u32, u32, Plane)> = Vec::new();
    for q in others {
        let v = &q.vertices;
        if !v.iter().any(|&p| filter.may_hold(p)) {
            continue;
        }
        for k in 0..v.len() {
            if let Some(&(i, e)) = missing.get(&(key(v[k]), key(v[(k + 1) % v.len()]))) {
                found.push((i, e, q.plane));
            }
        }
    }
    found.sort_unstable_by_key(|&(i, e, _)| (i, e));
    let mut at = 0;
    while at < found.len() {
        let i = found[at].0 as usize;
        let mut edges: Vec<Plane> = polygons[i].edges().to_vec();
        while at < found.len() && found[at].0 as usize == i {
            edges[found[at].1 as usize] = found[at].2;
            at += 1;
        }
        polygons[i].edges = Some(edges.into());
    }
}

/// Gives each edge still unknown the plane of a polygon, of `polygons` or `others`, whose edge
/// runs back along it from one of its ends to a point inside it: a neighbour across the edge
/// that was cut there, by an earlier boolean, where this polygon was not (a T-junction).
///
/// Without it the edge's plane is unknown, and [`Polygon::split`] takes its ends as possibly
/// made on any plane (`made_on`): a corner of an operand turned a hair, 6.4e-15 off the other's
/// nearly parallel face, counted as on it by the plane's rounding (2e-14 there, against the
/// 1.1e-15 a corner merely given is allowed), and the face was cut through that corner while
/// the other operand's face was cut on the planes' crossing line; a later cut along that edge
/// ended 6.3e-8 from the other's (a 0.625 cube turned 1e-5° about its diagonal, united with a
/// bar that cut its bottom face, then intersected with the cube unturned: 4 boundary edges).
fn attach_edges_across_t_junctions<'a>(
    polygons: &mut [Polygon],
    others: impl Iterator<Item = &'a Polygon>,
) {
    // Per end of an edge still unknown: the edges (polygon, index) it ends.
    let mut ends: KeyedHashMap<[u64; 3], smallvec::SmallVec<[(u32, u32); 2]>> =
        KeyedHashMap::default();
    for (i, p) in polygons.iter().enumerate() {
        let v = &p.vertices;
        for k in 0..v.len() {
            if p.edge_plane(k).is_none() {
                for end in [v[k], v[(k + 1) % v.len()]] {
                    ends.entry(key(end)).or_default().push((i as u32, k as u32));
                }
            }
        }
    }
    if ends.is_empty() {
        return;
    }
    // A polygon of a chain's earlier result rarely has an end among these; the filter settles
    // it without hashing both ends of each of its edges (a third operand's far polygons:
    // 24 M on a chain of three rocker-arms).
    let filter = PositionFilter::new(ends.keys().copied());
    let mut found: Vec<(u32, u32, Plane)> = Vec::new();
    {
        let polygons: &[Polygon] = polygons;
        let own = polygons.iter().enumerate().map(|(j, q)| (Some(j), q));
        for (j, q) in own.chain(others.map(|q| (None, q))) {
            let w = &q.vertices;
            if !w.iter().any(|&p| filter.may_hold(p)) {
                continue;
            }
            for m in 0..w.len() {
                let (c, d) = (w[m], w[(m + 1) % w.len()]);
                for (at, other, from_end) in [(c, d, true), (d, c, false)] {
                    let Some(list) = ends.get(&key(at)) else {
                        continue;
                    };
                    for &(i, k) in list {
                        if j == Some(i as usize) {
                            continue;
                        }
                        let v = &polygons[i as usize].vertices;
                        let (a, b) = (v[k as usize], v[(k as usize + 1) % v.len()]);
                        // The neighbour runs the edge from `b` towards `a`: its edge leaves `b`
                        // (`from_end`) or reaches `a`, the other end inside the edge.
                        let (shared, far) = if from_end { (b, a) } else { (a, b) };
                        if at == shared && strictly_inside(other, shared, far) {
                            found.push((i, k, q.plane));
                        }
                    }
                }
            }
        }
    }
    found.sort_unstable_by_key(|&(i, e, _)| (i, e));
    found.dedup_by_key(|&mut (i, e, _)| (i, e));
    let mut at = 0;
    while at < found.len() {
        let i = found[at].0 as usize;
        let mut edges: Vec<Plane> = if polygons[i].edges().len() == polygons[i].vertices.len() {
            polygons[i].edges().to_vec()
        } else {
            vec![UNKNOWN; polygons[i].vertices.len()]
        };
        while at < found.len() && found[at].0 as usize == i {
            edges[found[at].1 as usize] = found[at].2;
            at += 1;
        }
        polygons[i].edges = Some(edges.into());
    }
}

/// A bit per hashed position: settles at once most points that are not among a set of keyed
/// positions (a point it holds may still be absent; one it does not hold is).
struct PositionFilter {
    bits: Vec<u64>,
    shift: u32,
}

impl PositionFilter {
    fn new(keys: impl ExactSizeIterator<Item = [u64; 3]>) -> PositionFilter {
        let bits = (keys.len() * 16).next_power_of_two().max(1024);
        let mut filter = PositionFilter {
            bits: vec![0; bits / 64],
            shift: 64 - bits.trailing_zeros(),
        };
        for k in keys {
            let s = filter.slot(k);
            filter.bits[s / 64] |= 1 << (s % 64);
        }
        filter
    }

    fn slot(&self, [x, y, z]: [u64; 3]) -> usize {
        ((x ^ y.rotate_left(21) ^ z.rotate_left(42)).wrapping_mul(0x9E37_79B9_7F4A_7C15)
            >> self.shift) as usize
    }

    fn may_hold(&self, p: DVec3) -> bool {
        let s = self.slot(key(p));
        self.bits[s / 64] & (1 << (s % 64)) != 0
    }
}

/// Whether `p` lies on the segment from `from` to `to`, strictly between its ends, within the
/// rounding of a point interpolated along it.
fn strictly_inside(p: DVec3, from: DVec3, to: DVec3) -> bool {
    let e = to - from;
    let len2 = e.length_squared();
    let t = (p - from).dot(e);
    if !(t > 0.0 && t < len2) {
        return false;
    }
    let off = (p - from - e * (t / len2)).abs().max_element();
    let scale = from.abs().max_element().max(to.abs().max_element());
    off <= 16.0 * f64::EPSILON * scale
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An edge whose neighbour was cut inside it (a T-junction) takes that neighbour's plane;
    /// one whose only candidate edge runs beside it, not along it, stays unknown.
    #[test]
    fn an_edge_takes_the_plane_of_a_neighbour_across_a_t_junction() {
        let p = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
        // The top z = 0 of a unit square prism; its edge from (1, 0) to (1, 1) lies on x = 1.
        let top = Polygon::new(
            &[p(0., 0., 0.), p(1., 0., 0.), p(1., 1., 0.), p(0., 1., 0.)],
            0,
        );
        // The side x = 1, cut at y = 0.3 by an earlier boolean: its piece runs back from
        // (1, 1) to (1, 0.3) along the top's edge.
        let side = Polygon::new(
            &[
                p(1., 1., 0.),
                p(1., 0.3, 0.),
                p(1., 0.3, -1.),
                p(1., 1., -1.),
            ],
            0,
        );
        // The side y = 0, which shares the corner (1, 0) but runs along the top's other edge.
        let front = Polygon::new(
            &[p(0., 0., 0.), p(0., 0., -1.), p(1., 0., -1.), p(1., 0., 0.)],
            0,
        );
        // A stray edge reaching (0, 1) from 1e-9 beside the top's edge from (0, 1) to (0, 0).
        let stray = Polygon::new(&[p(1e-9, 0.5, 0.), p(0., 1., 0.), p(0., 0.5, -1.)], 0);
        let mut polygons = vec![top.unwrap()];
        let others = [side.unwrap(), front.unwrap(), stray.unwrap()];
        attach_edge_planes_among(&mut polygons, others.iter());
        let edges = polygons[0].edges();
        assert_eq!(edges.len(), 4);
        assert!(
            edges[1].is_same_or_flipped(others[0].plane()),
            "{:?}",
            edges[1]
        );
        assert!(
            edges[0].is_same_or_flipped(others[1].plane()),
            "{:?}",
            edges[0]
        );
        assert_eq!(edges[3].normal, DVec3::ZERO, "{:?}", edges[3]);
        assert_eq!(edges[2].normal, DVec3::ZERO, "{:?}", edges[2]);
    }

    /// The filter holds every position it was made from, and settles most others at once
    /// (a point it holds may be absent; one it does not hold never is).
    #[test]
    fn the_position_filter_holds_its_keys_and_few_others() {
        let points: Vec<DVec3> = (0..500)
            .map(|i| DVec3::new(i as f64 * 0.37, (i % 7) as f64, -0.5))
            .collect();
        let filter = PositionFilter::new(
            points
                .iter()
                .map(|&p| key(p))
                .collect::<Vec<_>>()
                .into_iter(),
        );
        assert!(points.iter().all(|&p| filter.may_hold(p)));
        let others =
            (0..10_000).filter(|&i| filter.may_hold(DVec3::new(i as f64 * 0.011, 3.5, 2.0)));
        assert!(others.count() < 1_000);
    }

    /// Two planes crossing at 2e-10 rad whose canonical normals face opposite ways (first
    /// components ±1e-10): each judges the other's points by one line, exactly opposite ways,
    /// within rounding of the plane distance where that is exact enough to tell, and the `meet`s
    /// on their crossing lie on that line. Before the normals were aligned, the difference of
    /// the canonical normals was near 2 and the judgement meaningless.
    #[test]
    fn both_planes_judge_by_one_crossing_line() {
        let p = Plane::from_point_normal(DVec3::new(0.3, 1.0, 0.2), DVec3::new(1e-10, 1.0, 0.0))
            .unwrap();
        let q = Plane::from_point_normal(DVec3::new(0.7, 1.0, 0.9), DVec3::new(-1e-10, 1.0, 0.0))
            .unwrap();
        assert!(canonical(&p).normal.dot(canonical(&q).normal) < 0.0);
        let (on_p, on_q) = (
            Crossing::new(&p, &q).unwrap(),
            Crossing::new(&q, &p).unwrap(),
        );
        // They cross on x = 0.5; points of `p` on either side of it.
        for x in [-0.5, 0.25, 0.49, 0.51, 0.75, 1.5] {
            for z in [0.0, 0.4, 1.0] {
                let v = DVec3::new(x, 1.0 - 1e-10 * (x - 0.3), z);
                let (s, t) = (on_p.side(v), on_q.side(v));
                assert_eq!(s, -t, "{v}");
                // −2e-10 (x − 0.5): the distance from `q` of the point of `p` at `v`.
                let want = -2e-10 * (x - 0.5);
                assert!((s - want).abs() <= 1e-6 * want.abs(), "{s} vs {want}");
                assert!((s - q.distance(v)).abs() <= 1e-3 * want.abs());
            }
        }
        let r = Plane::from_point_normal(DVec3::new(0.0, 0.0, 0.6), DVec3::Z).unwrap();
        let m = meet(&p, &q, &r).unwrap();
        assert!(
            on_p.side(m).abs() <= 1e-25 && on_q.side(m).abs() <= 1e-25,
            "{m}"
        );
    }
}
