//! Moving one corner of a needle no flip or collapse can take: stretching a spike's short
//! edge, or widening a flat sliver away from its long edge.

use glam::DVec3;

use super::geometry::{area, plane_distance, twice_normal};
use super::work::Work;
use super::{Op, Plan};
use crate::geom::is_zero_area;

impl Work {
    /// Moving `from`, an end of an edge of needle `t` (its short edge where [`Work::choose`]
    /// asks; any edge where [`Work::stretch_any`] does), away from its other end `to` along
    /// that edge, until the needle's area is half again the threshold. Where a thin wedge ends
    /// in a face narrower than the bound (a prism's cap turned 0.001° passing 3.9e-10 from a
    /// cube's corner: an end face 3.9e-10 × 4.4e-5), no flip applies and every collapse folds
    /// the wedge's tip into a sheet of no thickness, whose removal would cut 4.4e-5 off the
    /// wedge; this moves one vertex by about the needle's height and keeps the wedge. Checked
    /// as a collapse is: every triangle around `from` keeps its orientation and area.
    pub(super) fn plan_stretch(&self, t: u32, from: u32, to: u32) -> Option<Plan> {
        let tri = self.tris[t as usize];
        let (source, target) = (self.positions[from as usize], self.positions[to as usize]);
        let grow = 1.5 * self.threshold(tri) / area(self.corners(tri));
        let at = target + (source - target) * grow;
        // A needle of no area at all has no direction to grow in.
        if !at.is_finite() {
            return None;
        }
        let (mut dev, mut swept) = (0.0f64, 0.0);
        for &u in self.around(from) {
            let old = self.tris[u as usize];
            let before = self.corners(old);
            let after = self.corners_moved(old, from, at);
            let was_needle = area(before) < self.threshold(old);
            if is_zero_area(after)
                || twice_normal(after).dot(twice_normal(before)) <= 0.0
                || (!was_needle && area(after) < self.threshold(old))
            {
                return None;
            }
            swept += (twice_normal(before).dot(at - source) / 6.0).abs();
            if area(before) >= self.noise_area(old) {
                dev = dev.max(plane_distance(before, at));
            }
        }
        Some(Plan {
            dev,
            swept,
            op: Op::Move { v: from, at },
        })
    }
}

impl Work {
    /// Moving the apex of needle `t` opposite its edge `k` (from corner `k` to `k + 1`) away
    /// from that edge, in the plane of the apex's other triangles, until the needle's area is
    /// half again the threshold. The last resort for a flat sliver no flip, collapse or merge
    /// can take: where near-coplanar faces meet, a sliver 0.06 long and 5·10⁻¹³ thick sits
    /// among edges that already exist both ways round it (both diagonals of the quad a vertex
    /// removal leaves, or the edge a flip would make), so only widening it keeps the topology.
    /// The move is about `3 · threshold / |edge|`, far inside the bound for a needle whose
    /// edge is longer than a speck's; on a flat fan it moves the surface by nothing.
    pub(super) fn plan_widen(&self, t: u32, k: usize) -> Option<Plan> {
        let tri = self.tris[t as usize];
        // A tetrahedron's faces all meet at each corner: no plane of the fan to widen in.
        if self.shell_tris[self.shell[tri[0] as usize] as usize] <= 4 {
            return None;
        }
        let (a, b, v) = (tri[k], tri[(k + 1) % 3], tri[(k + 2) % 3]);
        let [pa, pb, pv] = [a, b, v].map(|w| self.positions[w as usize]);
        let mut normal = DVec3::ZERO;
        for &u in self.around(v) {
            if u != t {
                normal += twice_normal(self.corners(self.tris[u as usize]));
            }
        }
        let along = (pb - pa).try_normalize()?;
        // (b − a) × (n × e) runs along n: the needle keeps the fan's orientation.
        let away = normal.cross(along).try_normalize()?;
        let height = 3.0 * self.threshold(tri) / pa.distance(pb);
        let at = pa + along * (pv - pa).dot(along) + away * height;
        let (mut dev, mut swept) = (0.0f64, 0.0);
        for &u in self.around(v) {
            let old = self.tris[u as usize];
            let before = self.corners(old);
            let after = self.corners_moved(old, v, at);
            let was_needle = area(before) < self.threshold(old);
            let noise = area(before) < self.noise_area(old);
            let reference = if noise { normal } else { twice_normal(before) };
            if is_zero_area(after)
                || twice_normal(after).dot(reference) <= 0.0
                || ((!was_needle || u == t) && area(after) < self.threshold(old))
            {
                return None;
            }
            swept += (twice_normal(before).dot(at - pv) / 6.0).abs();
            if !noise {
                dev = dev.max(plane_distance(before, at));
            }
        }
        Some(Plan {
            dev,
            swept,
            op: Op::Move { v, at },
        })
    }
}
