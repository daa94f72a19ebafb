//! Stretching the short edge of a spike no flip or collapse can take.

use super::geometry::{area, plane_distance, twice_normal};
use super::work::Work;
use super::{Op, Plan};
use crate::geom::is_zero_area;

impl Work {
    /// Moving `from`, an end of needle `t`'s short edge, away from its other end `to` along
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
        let (mut dev, mut swept) = (0.0f64, 0.0);
        for &u in &self.around[from as usize] {
            let old = self.tris[u as usize];
            let before = self.corners(old);
            let after = old.map(|w| {
                if w == from {
                    at
                } else {
                    self.positions[w as usize]
                }
            });
            let was_needle = area(before) < self.threshold(old);
            if is_zero_area(after)
                || twice_normal(after).dot(twice_normal(before)) <= 0.0
                || (!was_needle && area(after) < self.threshold(old))
            {
                return None;
            }
            swept += (twice_normal(before).dot(at - source) / 6.0).abs();
            if !was_needle {
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
