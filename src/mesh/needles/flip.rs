//! Flipping a needle's longest edge (a cap's apex onto the neighbour across it).

use super::geometry::{area, plane_distance, twice_normal};
use super::work::Work;
use super::{Op, Plan};

impl Work {
    /// Flipping edge `k` of triangle `t` (from corner `k` to `k + 1`): the move (the apex's
    /// distance from the neighbour's plane) and the operation, if the flip is valid and helps.
    ///
    /// For a spike (`spike`), the flip must take the needle out: the smaller new triangle no
    /// needle, or at least twice the smaller old one.
    pub(super) fn plan_flip(&self, t: u32, k: usize, spike: bool) -> Option<Plan> {
        let tri = self.tris[t as usize];
        let (a, b, v) = (tri[k], tri[(k + 1) % 3], tri[(k + 2) % 3]);
        let u = self.with_edge(b, a)?;
        let other = self.tris[u as usize];
        let j = (0..3).find(|&j| other[j] == b && other[(j + 1) % 3] == a)?;
        let c = other[(j + 2) % 3];
        if c == v || self.with_edge(v, c).is_some() || self.with_edge(c, v).is_some() {
            return None;
        }
        let normal = twice_normal(self.corners(tri)) + twice_normal(self.corners(other));
        let (new_t, new_u) = ([a, c, v], [c, b, v]);
        if !self.acceptable(new_t, normal) || !self.acceptable(new_u, normal) {
            return None;
        }
        // Only a change that helps: the smaller of the two areas grows; a spike's, out of the
        // needles or to at least twice what it was. Flipping a spike's long edge keeps its
        // short edge, in the new triangle whose third corner is the neighbour's apex: where
        // that apex lies on the spike's line too, the needle only moves there, of the same area
        // (round 18's b447eea7, the full input: 1.9709e-13 → 1.9710e-13, until a stretch took it).
        let before = area(self.corners(tri)).min(area(self.corners(other)));
        let after = area(self.corners(new_t)).min(area(self.corners(new_u)));
        if after <= before || (spike && after < self.threshold(tri) && after < 2.0 * before) {
            return None;
        }
        let apex = self.positions[v as usize];
        let [pa, pb, pc] = self.corners(other);
        Some(Plan {
            dev: plane_distance(self.corners(other), apex),
            swept: ((pb - pa).cross(pc - pa).dot(apex - pa) / 6.0).abs(),
            op: Op::Flip { t, u, new_t, new_u },
        })
    }

    pub(super) fn apply_flip(
        &mut self,
        t: u32,
        u: u32,
        new_t: [u32; 3],
        new_u: [u32; 3],
    ) -> Vec<u32> {
        self.unlink(t);
        self.unlink(u);
        self.tris[t as usize] = new_t;
        self.tris[u as usize] = new_u;
        // Nearly all of the pair's area was the neighbour's: both keep its source.
        self.sources[t as usize] = self.sources[u as usize];
        self.link(t);
        self.link(u);
        vec![t, u]
    }
}
