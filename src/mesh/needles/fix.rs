//! Choosing, for one needle, the operation that removes it and moves the surface least.

use super::geometry::area;
use super::work::Work;
use super::{Op, Plan};

impl Work {
    /// One operation on needle `t`, of those that apply the one that moves the surface least;
    /// the triangles it changed, or `None` when none applies.
    pub(super) fn fix(&mut self, t: u32) -> Option<Vec<u32>> {
        let tri = self.tris[t as usize];
        let c = self.corners(tri);
        let len = [0, 1, 2].map(|k| c[k].distance(c[(k + 1) % 3]));
        let longest = (0..3).max_by(|&i, &j| len[i].total_cmp(&len[j]))?;
        // Never move the surface more than twice the needle's own thickness (its height over
        // its longest edge), nor beyond the shell's bound.
        let height = 2.0 * area(c) / len[longest].max(f64::MIN_POSITIVE);
        let shell = self.shell[tri[0] as usize] as usize;
        let limit = self.max_move[shell].min((2.0 * height).max(self.tolerance[shell]));
        // A needle with a short edge (a spike, or a speck) keeps that edge through any flip,
        // and a short edge is what rounding to f32 on export collapses: it is collapsed if it
        // can be. A cap (apex near the middle of the longest edge) is flipped if it can be.
        let shortest = (0..3).min_by(|&i, &j| len[i].total_cmp(&len[j]))?;
        let short_edge = len[shortest] <= 4.0 * height;
        // Of the operations that move the surface no farther than `limit`, the one that sweeps
        // the least volume: moving a corner of a large triangle off its plane sweeps much even
        // when the distance is small.
        let mut flips: Option<(f64, Op)> = None;
        let mut collapses: Option<(f64, Op)> = None;
        let consider = |best: &mut Option<(f64, Op)>, candidate: Option<Plan>| {
            if let Some(Plan { dev, swept, op }) = candidate
                && dev <= limit
                && best.as_ref().is_none_or(|(v, _)| swept < *v)
            {
                *best = Some((swept, op));
            }
        };
        consider(&mut flips, self.plan_flip(t, longest));
        for k in 0..3 {
            let (p, q) = (tri[k], tri[(k + 1) % 3]);
            consider(&mut collapses, self.plan_collapse(t, p, q));
            consider(&mut collapses, self.plan_collapse(t, q, p));
        }
        let best = if short_edge {
            let mut stretches: Option<(f64, Op)> = None;
            if collapses.is_none() && flips.is_none() {
                let (p, q) = (tri[shortest], tri[(shortest + 1) % 3]);
                consider(&mut stretches, self.plan_stretch(t, p, q));
                consider(&mut stretches, self.plan_stretch(t, q, p));
            }
            collapses.or(flips).or(stretches)
        } else {
            flips.or(collapses)
        };
        match best?.1 {
            Op::Move { v, at } => {
                self.positions[v as usize] = at;
                Some(self.around[v as usize].to_vec())
            }
            Op::Flip { t, u, new_t, new_u } => Some(self.apply_flip(t, u, new_t, new_u)),
            Op::Collapse {
                from,
                to,
                at,
                t1,
                t2,
            } => Some(self.apply_collapse(from, to, at, t1, t2)),
        }
    }
}
