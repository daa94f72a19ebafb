//! Whether a point away from a surface is inside: crossings of rays and segments with its
//! polygons, labels carried along segments, and the generalised winding number where every
//! ray grazes.

use glam::DVec3;

use super::Surface;
use crate::bsp::Label;
use crate::geom::{Aabb, Plane, solid_angle};
use crate::polygon::{Polygon, plane_noise, side_across_line};

/// Ray directions for parity counting, away from any axis or diagonal so that rays rarely
/// graze the edges of axis-aligned or symmetric models; tried in turn when one grazes.
const DIRECTIONS: [[f64; 3]; 6] = [
    [0.5773, 0.6124, 0.5404],
    [-0.7061, 0.3162, 0.6335],
    [0.2673, -0.8018, 0.5345],
    [0.8944, 0.2981, -0.3333],
    [-0.3015, -0.4523, -0.8392],
    [0.1104, 0.9901, 0.0868],
];

enum Crossing {
    Miss,
    /// The ray crosses the polygon's interior this far along (in units of its direction).
    Hit(f64),
    /// The ray passes within tolerance of an edge or runs in the polygon's plane.
    Graze,
}

impl Surface<'_> {
    /// Inside or outside, for a point away from the surface (farther than the tolerance), by
    /// counting crossings of a ray; a ray that grazes an edge is retried in another direction.
    /// The generalised winding number settles the (rare) point whose every ray grazes.
    pub fn label(&self, p: DVec3) -> Label {
        'directions: for d in DIRECTIONS {
            let dir = DVec3::from(d).normalize();
            let mut crossings = 0u32;
            let mut grazed = false;
            self.bvh.ray(p, dir, |i| {
                match crossing(&self.polygons[i as usize], p, dir, self.eps) {
                    Crossing::Miss => {}
                    Crossing::Hit(_) => crossings += 1,
                    Crossing::Graze => grazed = true,
                }
                grazed
            });
            if grazed {
                continue 'directions;
            }
            return if crossings % 2 == 1 {
                Label::Inside
            } else {
                Label::Outside
            };
        }
        self.winding_label(p)
    }

    /// The label of `p` from a point `q` whose label is known, by the parity of crossings along
    /// the segment between them: a short segment meets a few polygons where a ray from `p` meets
    /// every box on its way out of the model. `None` when the segment grazes an edge, runs in a
    /// polygon's plane or crosses a plane within the tolerance of either end (the caller casts
    /// a ray instead).
    pub fn label_from(&self, p: DVec3, known: (DVec3, Label)) -> Option<Label> {
        self.segment_label(p, known, None)
    }

    /// [`Surface::label_from`] where only the polygons `among` (indices into this surface) can
    /// meet the segment: each is tested in turn, without walking the hierarchy.
    pub fn label_from_among(
        &self,
        p: DVec3,
        known: (DVec3, Label),
        among: &[u32],
    ) -> Option<Label> {
        self.segment_label(p, known, Some(among))
    }

    fn segment_label(
        &self,
        p: DVec3,
        (q, q_label): (DVec3, Label),
        among: Option<&[u32]>,
    ) -> Option<Label> {
        let crossings = self.crossings(p, q, among)?;
        Some(if crossings % 2 == 1 {
            match q_label {
                Label::Inside => Label::Outside,
                Label::Outside => Label::Inside,
            }
        } else {
            q_label
        })
    }

    /// How many polygons the segment from `p` to `q` crosses (of `among`, or of all), or `None`
    /// when it grazes an edge, runs in a polygon's plane or crosses a plane within the tolerance
    /// of either end.
    fn crossings(&self, p: DVec3, q: DVec3, among: Option<&[u32]>) -> Option<u32> {
        let len = (q - p).length();
        if len <= self.eps {
            return None;
        }
        let dir = (q - p) / len;
        // A segment between points of one face has zero components (see `Aabb::ray_span`).
        let inv = dir.recip();
        let eps = self.eps;
        // Boxes grown by the tolerance: a polygon the segment passes within it is a graze.
        // The segment's own box first, grown by twice that (room for the slab test's
        // rounding): a box the slab test passes overlaps it, so this cheaper test drops only
        // boxes the slab test would, and a short segment's walk drops most boxes by it.
        let reach = Aabb::new(p.min(q), p.max(q));
        let meets = |b: &Aabb| {
            b.overlaps(&reach, 2.0 * eps) && b.expanded(eps).ray_span(p, inv, len).is_some()
        };
        let mut crossings = 0u32;
        let mut grazed = false;
        let mut test = |i: u32| {
            match crossing(&self.polygons[i as usize], p, dir, self.eps) {
                Crossing::Miss => {}
                Crossing::Hit(t) => {
                    // Either end within the tolerance of the plane it crosses: as unsure as
                    // a graze.
                    let across = self.polygons[i as usize].plane().normal.dot(dir).abs();
                    if t * across <= self.eps || (len - t).abs() * across <= self.eps {
                        grazed = true;
                    } else if t < len {
                        crossings += 1;
                    }
                }
                Crossing::Graze => grazed = true,
            }
            grazed
        };
        match among {
            None => self.bvh.visit(meets, test),
            Some(among) => {
                for &i in among {
                    // The same polygons the hierarchy's walk would test: those whose box the
                    // segment meets.
                    if meets(&self.boxes[i as usize]) && test(i) {
                        break;
                    }
                }
            }
        }
        (!grazed).then_some(crossings)
    }

    /// How many polygons the short segment from `c`, a point of a fragment lying in a face of
    /// the tree whose normal is `normal`, to `p`, the point off that face a ray labels it from,
    /// crosses clear of their edges where `c` lies off their plane beyond its rounding
    /// ([`plane_noise`]), or, on it within that rounding, beyond it across their crossing
    /// line (below): the faces not parallel to that face (crossing it at a sine of at
    /// least [`Polygon::parallel_to`]'s bound) that lie between the two points, nearer than
    /// the tolerance. `None` when it grazes one.
    ///
    /// Such a face, nearly parallel to the one the fragment lies in, is judged as the tree's
    /// split judges it, by the narrow band of nearly parallel planes: the fragment was cut on
    /// their crossing line and routed to its side by that band. The point off the face, two
    /// tolerances away, may lie beyond it. An exact 0.125 cube's face y = −0.5625 inside a
    /// slab's turned 1e-9° (2.7e-13 beyond it there, the slab's face also holding a piece of
    /// the cube's face) was labelled outside the slab from that point, and the intersection
    /// dropped it while the slab's face, outside the cube by the band, was dropped too: a hole
    /// (the solid 2e-5 below its mesh). Faces parallel to the fragment's (within the tolerance
    /// alone, as `split` takes them) are coplanar with it and not counted: the point off them
    /// is what the coplanar rule asks.
    ///
    /// A face whose plane `c` lies on within its rounding, crossing `own` (the fragment's
    /// plane) in the band of nearly parallel planes, is judged by `c`'s distance across their
    /// crossing line instead ([`side_across_line`]), as `split` judged the fragment: where that
    /// puts `c` on the side away from `p`, the segment crosses the face's plane at `c`, and it
    /// counts if the line through `c` along the segment meets the face clear of its edges.
    /// Near the crossing line a fragment's centroid lies within the rounding of both planes: a
    /// 0.125 cube's top y = −0.4375 (exact), inside a cuboid whose bottom is turned 10⁻¹⁰°
    /// (1.4·10⁻¹² rad, crossing it on the diagonal x = z), by 2.5·10⁻¹⁵ at the centroid of a
    /// strip 0.01 wide beside that line; the strip, routed as coplanar along an exact face
    /// y = −0.4375 and to its back under the second coplanar rule, was labelled outside from
    /// two tolerances below, and the difference dropped it while the cuboid's bottom there,
    /// inside the cube by the band, was dropped too (round 20's fork input e3c98fcd: a hole of
    /// 4.9·10⁻⁵, the solid 6.8·10⁻⁶ below its mesh).
    pub fn crossings_off(&self, c: DVec3, p: DVec3, normal: DVec3, own: &Plane) -> Option<u32> {
        let len = (p - c).length();
        if len == 0.0 {
            return Some(0);
        }
        let dir = (p - c) / len;
        let inv = dir.recip();
        let mut crossings = 0u32;
        let mut grazed = false;
        self.bvh.visit(
            |b: &Aabb| b.ray_span(c, inv, len).is_some(),
            |i| {
                let poly = &self.polygons[i as usize];
                let plane = poly.plane();
                let dc = plane.distance(c);
                if poly.parallel_to(normal) {
                    return false;
                }
                // From `c` mirrored through itself: a hit at `len` is the crossing at `c`.
                let (from, reach) = if dc.abs() > plane_noise(plane, c) {
                    (c, len)
                } else {
                    match side_across_line(own, plane, c) {
                        Some(s) if (s > 0.0) != (plane.distance(p) > 0.0) => {
                            (c - (p - c), 2.0 * len)
                        }
                        _ => return false,
                    }
                };
                match crossing(poly, from, dir, self.eps) {
                    Crossing::Miss => {}
                    Crossing::Hit(t) => {
                        if t < reach {
                            crossings += 1;
                        }
                    }
                    Crossing::Graze => grazed = true,
                }
                grazed
            },
        );
        (!grazed).then_some(crossings)
    }

    /// Of the points `off` in front of and behind `at`, a point of polygon `g`, along its
    /// normal, the one on `toward`'s side of `g`'s plane with its label, when the segment
    /// between them crosses `g` clear of its edges and no other polygon of `among`. If every
    /// polygon that can come near that segment is in `among`, the front point is outside and
    /// the back one inside: crossing a face of a closed surface from front to back is what
    /// enters the solid. `None` otherwise.
    pub fn across(
        &self,
        g: u32,
        at: DVec3,
        toward: DVec3,
        off: f64,
        among: &[u32],
    ) -> Option<(DVec3, Label)> {
        let poly = &self.polygons[g as usize];
        let plane = poly.plane();
        let (front, back) = (at + plane.normal * off, at - plane.normal * off);
        if self.crossings(front, back, Some(among))? != 1 {
            return None;
        }
        // The one crossing must be `g`'s own: `at` lies in `g` only where `g` is convex, and
        // another polygon facing the other way would swap the labels.
        if !matches!(
            crossing(poly, front, -plane.normal, self.eps),
            Crossing::Hit(_)
        ) {
            return None;
        }
        Some(if plane.distance(toward) >= 0.0 {
            (front, Label::Outside)
        } else {
            (back, Label::Inside)
        })
    }

    /// Inside when the generalised winding number is above one half.
    fn winding_label(&self, p: DVec3) -> Label {
        let mut total = 0.0;
        for poly in self.polygons {
            for [a, b, c] in poly.fan() {
                total += solid_angle(a - p, b - p, c - p);
            }
        }
        if total / (4.0 * std::f64::consts::PI) > 0.5 {
            Label::Inside
        } else {
            Label::Outside
        }
    }
}

/// Whether the ray from `origin` along `dir` crosses the polygon's interior.
fn crossing(poly: &Polygon, origin: DVec3, dir: DVec3, eps: f64) -> Crossing {
    let plane = poly.plane();
    let denom = plane.normal.dot(dir);
    let d0 = plane.distance(origin);
    // Nearly parallel to the plane: a graze where the origin lies within the tolerance of it.
    // Farther, it still crosses it, at t = d0 / denom: a segment 3.3e-11 from a face and
    // running along it at 8.6e-10 rad crosses it 0.04 away (taken for a miss, the label of a
    // point by a segment from a neighbour came out inside: a nicked box less a slab turned
    // 1e-6°, 1/96 of its volume lost); a ray's far crossing falls outside the polygon.
    if d0.abs() <= eps && denom.abs() < 1e-9 {
        return Crossing::Graze;
    }
    if denom == 0.0 {
        return Crossing::Miss;
    }
    let t = -d0 / denom;
    if t < 0.0 {
        return Crossing::Miss;
    }
    let hit = origin + dir * t;
    let v = poly.vertices();
    let mut inner = f64::INFINITY;
    for i in 0..v.len() {
        let (a, b) = (v[i], v[(i + 1) % v.len()]);
        let edge = b - a;
        let len = edge.length();
        // An edge within the tolerance long has no direction to judge by: one 5.5e-17 long
        // (corners -0.4375 and -0.4375 + 1 ulp, the ring turning back along its neighbour) put
        // every hit on its outer side, and a ray out of a bar crossing its face read zero
        // crossings (a cube's face inside the bar labelled outside and kept: a flat shell).
        // Skipped, the polygon grows at most to the neighbours' lines, within the edge's length
        // of one of them: a hit there is within the tolerance, a graze as before.
        if len <= eps {
            continue;
        }
        let side = edge.cross(hit - a).dot(plane.normal) / len;
        // An edge up to a weld long running back along a neighbour (a spike of no area) has
        // its inner side outward too: one 6.2e-12 long (5.5 tolerances, two cut points on one
        // edge) put a box's face beyond the hit, and a ray out of the box read one crossing
        // short (a face of the other operand lying in a gap labelled inside and dropped: the
        // solid's polygons open by 7.8e-3, its volume 1.1e-3 off its mesh's). Skipped as the
        // short edge is, the ring is its neighbour's line there.
        if side < -eps && turns_back(edge, len, v, i, eps) {
            continue;
        }
        inner = inner.min(side);
    }
    if inner > eps {
        Crossing::Hit(t)
    } else if inner < -eps {
        Crossing::Miss
    } else {
        Crossing::Graze
    }
}

/// Spikes up to this many tolerances long are skipped (a weld: corners nearer are one point).
const SPIKE_TOLERANCES: f64 = 8.0;

/// Whether the edge `edge` (of length `len`) from corner `i` of the ring `v` is a spike: at
/// most [`SPIKE_TOLERANCES`] long, running back along the edge before or after it, which is
/// longer than that (so is never skipped itself: a sliver's long sides still bound it), its
/// far end within `eps` of that edge's line.
fn turns_back(edge: DVec3, len: f64, v: &[DVec3], i: usize, eps: f64) -> bool {
    let spike = SPIKE_TOLERANCES * eps;
    if len > spike {
        return false;
    }
    let n = v.len();
    let before = v[i] - v[(i + n - 1) % n];
    let after = v[(i + 2) % n] - v[(i + 1) % n];
    [before, after].into_iter().any(|m| {
        let m_len = m.length();
        m.dot(edge) < 0.0 && m_len > spike && m.cross(edge).length() <= eps * m_len
    })
}

#[cfg(test)]
mod tests;
