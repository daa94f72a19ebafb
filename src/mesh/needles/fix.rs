//! Choosing, for one needle, the operation that removes it and moves the surface least.

use super::geometry::area;
use super::work::Work;
use super::{Op, Plan};
use crate::geom::NEEDLE_THIN;

impl Work {
    /// The operation on needle `t` that, of those that apply, moves the surface least, or
    /// `None` when none applies.
    ///
    /// First within twice the needle's own thickness (or the boolean's tolerance); where
    /// nothing applies that close, within the shell's bound ([`super::SPECK_MOVE`] × d). A
    /// needle where near-coplanar faces meet is often a spike whose short edge is far longer
    /// than its thickness (6·10⁻⁹ beside a height of 10⁻¹²): collapsing that edge keeps the
    /// volume and moves the surface by about its length, far inside the bound.
    pub(super) fn plan(&self, t: u32) -> Option<Op> {
        let tri = self.tris[t as usize];
        let shell = self.shell[tri[0] as usize] as usize;
        let bound = self.max_move[shell];
        let limit = bound.min((2.0 * self.height(t)).max(self.tolerance[shell]));
        match self.choose(t, limit) {
            None if limit < bound => self.choose(t, bound),
            best => best,
        }
        .or_else(|| self.widen(t, bound))
        .or_else(|| self.stretch_any(t, bound))
    }

    /// Stretching any edge of needle `t`, either way, within `bound`, the one that sweeps the
    /// least: the very last resort, where nothing else applies (see [`Work::plan_stretch`]).
    /// [`Work::choose`] stretches only a spike's shortest edge. On a handle (every edge of the
    /// needle fails the link condition, no flip keeps its orientation; the round-20 fork input
    /// 79dd0a25, step 1) a flat sliver with sides 0.25, 0.25 and 7.6·10⁻⁷, its far corner
    /// 6.7·10⁻⁸ off the line of the short edge, is no spike by its height over the longest
    /// edge (2·10⁻¹³), and was left; beside it, a speck whose shortest edge's stretch moves a
    /// corner out of a large triangle's plane by 5.7·10⁻⁶ (the bound 1.8·10⁻⁶) stretches
    /// another edge instead, along that plane (1.5·10⁻⁶).
    fn stretch_any(&self, t: u32, bound: f64) -> Option<Op> {
        let tri = self.tris[t as usize];
        (0..3)
            .flat_map(|k| {
                let (p, q) = (tri[k], tri[(k + 1) % 3]);
                [self.plan_stretch(t, p, q), self.plan_stretch(t, q, p)]
            })
            .flatten()
            .filter(|plan| plan.dev <= bound)
            .min_by(|a, b| a.swept.total_cmp(&b.swept))
            .map(|plan| plan.op)
    }

    /// Applies `op` (planned by [`Work::plan`]); the triangles it changed.
    pub(super) fn apply(&mut self, op: Op) -> Vec<u32> {
        match op {
            Op::Move { v, at } => {
                self.positions[v as usize] = at;
                self.around(v).to_vec()
            }
            Op::Flip { t, u, new_t, new_u } => self.apply_flip(t, u, new_t, new_u),
            Op::Collapse {
                from,
                to,
                at,
                t1,
                t2,
                cap,
            } => self.apply_collapse(from, to, at, [t1, t2], cap),
            Op::Merge { vertices, at, cut } => self.apply_merge(&vertices, at, cut),
        }
    }

    /// Widening needle `t` away from whichever of its edges moves the surface least, within
    /// `bound` (see [`Work::plan_widen`]): where nothing else applies. Edges are tried longest
    /// first, so on a flat fan (every edge moves the surface by 0) the apex moves off the long
    /// edge, by the least distance, not along the plane off a short one.
    fn widen(&self, t: u32, bound: f64) -> Option<Op> {
        let c = self.corners(self.tris[t as usize]);
        let mut edges = [0, 1, 2];
        edges.sort_by(|&j, &k| {
            let len = |k: usize| c[k].distance_squared(c[(k + 1) % 3]);
            len(k).total_cmp(&len(j))
        });
        edges
            .into_iter()
            .filter_map(|k| self.plan_widen(t, k))
            .filter(|plan| plan.dev <= bound)
            .min_by(|p, q| p.dev.total_cmp(&q.dev))
            .map(|plan| plan.op)
    }

    /// Needle `t`'s thickness: its height over its longest edge.
    fn height(&self, t: u32) -> f64 {
        let c = self.corners(self.tris[t as usize]);
        let longest = (0..3)
            .map(|k| c[k].distance(c[(k + 1) % 3]))
            .fold(0.0, f64::max);
        2.0 * area(c) / longest.max(f64::MIN_POSITIVE)
    }

    /// The operation on needle `t` that moves the surface no farther than `limit`, of those
    /// that apply (see [`Work::fix`]).
    fn choose(&self, t: u32, limit: f64) -> Option<Op> {
        let tri = self.tris[t as usize];
        let c = self.corners(tri);
        let len = [0, 1, 2].map(|k| c[k].distance(c[(k + 1) % 3]));
        let longest = (0..3).max_by(|&i, &j| len[i].total_cmp(&len[j]))?;
        let height = self.height(t);
        // A needle with a short edge (a spike, or a speck) keeps that edge through any flip,
        // and a short edge is what rounding to f32 on export collapses: it is collapsed if it
        // can be. A cap (apex near the middle of the longest edge) is flipped if it can be.
        let shortest = (0..3).min_by(|&i, &j| len[i].total_cmp(&len[j]))?;
        let short_edge = len[shortest] <= 4.0 * height;
        // A thin spike (see [`NEEDLE_THIN`]), not a well-shaped triangle that is a needle only
        // by the area of a shell far larger than itself (an I-beam profile's own detail 0.1 …
        // 1 across, 666,660 from the rest, `bsp_18`): its flips must take it out, and where
        // its longest edge's does not, its other edges' are tried.
        let thin_spike = short_edge && len[longest] > NEEDLE_THIN * height;
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
        consider(&mut flips, self.plan_flip(t, longest, thin_spike));
        // Where a thin spike's longest edge's flip does not help (the neighbour's apex on the
        // spike's line: the short edge and the needle would only move there), the other
        // edges' flips, to the neighbours across them, within twice its own thickness (or the
        // tolerance). Tried on every spike, out to the bound, they edited `bsp_18`'s profile by
        // 6.2·10⁻³ of its volume, under the pass's 1 % guard.
        if thin_spike && flips.is_none() {
            let own = (2.0 * height).max(self.tolerance[self.shell[tri[0] as usize] as usize]);
            for k in (0..3).filter(|&k| k != longest) {
                let plan = self.plan_flip(t, k, true).filter(|plan| plan.dev <= own);
                consider(&mut flips, plan);
            }
            // Where none does, the longest edge's flip as any needle's (the smaller area
            // grows). Refused outright, a thin spike of `bsp_18` went to a collapse out at the
            // bound instead, and the pass then edited the profile by 6.2·10⁻³ of its volume.
            if flips.is_none() {
                consider(&mut flips, self.plan_flip(t, longest, false));
            }
        }
        for k in 0..3 {
            let (p, q) = (tri[k], tri[(k + 1) % 3]);
            consider(&mut collapses, self.plan_collapse(t, p, q));
            consider(&mut collapses, self.plan_collapse(t, q, p));
        }
        // Where no edge collapses and no flip applies (a speck between flat slivers, or on a
        // vertex of valence three), the whole triangle may merge into one vertex.
        let mut merges: Option<(f64, Op)> = None;
        if collapses.is_none() && flips.is_none() {
            consider(&mut merges, self.plan_merge(t));
            // Where the speck is one of a patch of them (every edge below the speck length)
            // and even its merge folds a neighbour there, the whole patch may merge.
            if merges.is_none()
                && let Some(cluster) = self.cluster(t)
            {
                consider(&mut merges, self.plan_merge_of(&cluster, true));
            }
        }
        let best = if short_edge {
            let mut stretches: Option<(f64, Op)> = None;
            if collapses.is_none() && flips.is_none() && merges.is_none() {
                let (p, q) = (tri[shortest], tri[(shortest + 1) % 3]);
                consider(&mut stretches, self.plan_stretch(t, p, q));
                consider(&mut stretches, self.plan_stretch(t, q, p));
            }
            collapses.or(flips).or(merges).or(stretches)
        } else {
            flips.or(collapses).or(merges)
        };
        best.map(|(_, op)| op)
    }
}
