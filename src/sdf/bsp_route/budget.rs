//! The scene's budget for the BSP route: polygons and boolean work estimated from the
//! primitives' segment counts before anything is tessellated, and a refusal that says what to
//! change.

use super::Ctx;
use crate::error::{Error, Result};
use crate::sdf::shapes::Shape;
use crate::sdf::shapes2d::{Prim2, Shape2};
use crate::sdf::tree::{Frame, NodeId, NodeKind};
use crate::sketch::TWIST_DEGREES_PER_SLICE;

/// The most polygons the BSP route tessellates for a whole scene: as many as one primitive may
/// have ([`crate::MAX_POLYGONS`], about 800 MB of polygons). The booleans that combine them
/// need several times the memory of their operands, so a scene of several primitives each just
/// under the per-primitive limit (four unit spheres at a tolerance of 10⁻⁶) would otherwise run
/// out of memory.
pub const MAX_SCENE_POLYGONS: u64 = crate::primitives::MAX_POLYGONS;

/// The most boolean work the BSP route takes on for a scene: the polygon corners of all its
/// primitives times the levels of the balanced reduction that combines them
/// (`⌈log₂ primitives⌉`, at least 1), each level clipping every corner once or more. 2²⁴
/// ([`crate::MAX_BOOLEAN_WORK`]): about a minute and 1–2 GB on a 2-core machine (twenty unions
/// of one 10,000-point polygon extruded, 6·10⁶, take 38 s and 1 GB). Past it — 300 references
/// to one 10,000-point polygon, 100,000 overlapping boxes, four unit spheres at a tolerance of
/// 2.4·10⁻⁶ — the export is refused at once, saying what to change.
///
/// The estimate counts corners, not how the kernel fares with them: faces of different
/// primitives that nearly coincide (copies of one 10,000-point outline a little apart) cost far
/// more. So the scene's booleans also share one work meter with the same limit, counting the
/// corners of the pieces their tree builds and clipping cut (see
/// [`crate::Solid::check_budget`]), and stop past it: 46 such copies are refused after 4.6 CPU-s
/// and 1.3 GB (they ran past 14 GB), eight after 5.1 CPU-s and 1.1 GB, four after 3.4 CPU-s and
/// 1.0 GB (in their first unions; unmetered, the last union cuts 21 M in clipping alone and
/// takes 34 CPU-s).
pub const MAX_SCENE_WORK: u64 = crate::solid::MAX_BOOLEAN_WORK;

/// What the BSP route would make of a scene at one tolerance, counted before tessellating.
#[derive(Clone, Copy, Debug)]
struct Estimate {
    /// Polygons of all primitives.
    polygons: u64,
    /// Polygon corners of all primitives.
    corners: u64,
    /// Of them, corners of round primitives (which a coarser tolerance reduces).
    round: u64,
    /// Primitives.
    leaves: u64,
}

impl Estimate {
    /// Levels of the balanced reduction that combines the primitives: `⌈log₂ leaves⌉`, at
    /// least 1.
    fn levels(&self) -> u64 {
        u64::from(self.leaves.max(2).next_power_of_two().trailing_zeros())
    }

    /// The boolean work: every corner clipped once per level.
    fn work(&self) -> u64 {
        self.corners.saturating_mul(self.levels())
    }

    /// Within both budgets.
    fn fits(&self) -> bool {
        self.polygons <= MAX_SCENE_POLYGONS && self.work() <= MAX_SCENE_WORK
    }

    /// How many times over the larger budget it is (1 or less when it fits).
    fn over(&self) -> f64 {
        (self.polygons as f64 / MAX_SCENE_POLYGONS as f64)
            .max(self.work() as f64 / MAX_SCENE_WORK as f64)
    }
}

impl Ctx<'_> {
    /// Refuses a scene whose primitives would need more than [`MAX_SCENE_POLYGONS`] polygons
    /// in all, or more than [`MAX_SCENE_WORK`] of boolean work, at this tolerance, before any
    /// is made. Where a coarser tolerance brings the scene within both, the message names one,
    /// checked by the same estimate (a tolerance that only meets the polygon budget was
    /// suggested once, then refused by the work budget); else it says to use fewer primitives
    /// or points, or the marching-cubes route. Each primitive's count is estimated from its
    /// segment counts (the same the tessellation uses); smooth subtrees baked by marching cubes
    /// are bounded by their own grid budget.
    pub(super) fn check_budget(&self, root: NodeId) -> Result<()> {
        let e = self.estimate_scene(root)?;
        if e.fits() {
            return Ok(());
        }
        let over = if e.polygons > MAX_SCENE_POLYGONS {
            format!(
                "the scene's primitives would need about {} polygons in all, more than the \
                 {MAX_SCENE_POLYGONS}-polygon budget of a scene",
                e.polygons
            )
        } else {
            format!(
                "the scene's {} primitives would have about {} polygon corners, combined over \
                 {} levels of booleans: about {} units of work, more than the budget of \
                 {MAX_SCENE_WORK} (about a minute)",
                e.leaves,
                e.corners,
                e.levels(),
                e.work()
            )
        };
        // Round primitives' polygons go as 1/tolerance: a coarser one is the remedy where it
        // fits. Where most corners are boxes and outlines it would not, and naming it would
        // point at an option the user may never have given: the scene itself is refused.
        let fitting = if e.polygons > MAX_SCENE_POLYGONS || 2 * e.round > e.corners {
            self.tolerance_that_fits(root, e)?
        } else {
            None
        };
        Err(match (fitting, self.max_angle) {
            (Some(t), _) => Error::param(
                "tolerance",
                self.tol,
                format!("{over}; use a tolerance of at least {t:.2e}, or fewer round primitives"),
            ),
            // A max_angle given sets the round parts' segments at any tolerance: name it.
            (None, Some(angle)) if 2 * e.round > e.corners => Error::param(
                "max_angle",
                angle,
                format!(
                    "{over}; it sets {} segments to a turn at any tolerance: use a larger one, \
                     or fewer round primitives",
                    self.min_segments
                ),
            ),
            (None, _) => Error::Scene {
                file: None,
                json_path: "$".into(),
                message: format!(
                    "{over}; use fewer primitives or 2D shapes of fewer points (a tolerance \
                     changes only round parts), or the marching-cubes route (--via sdf)"
                ),
            },
        })
    }

    /// The counts of every primitive of the scene that lies in it.
    fn estimate_scene(&self, root: NodeId) -> Result<Estimate> {
        let tree = &self.scene.tree;
        let mut e = Estimate {
            polygons: 0,
            corners: 0,
            round: 0,
            leaves: 0,
        };
        let mut work = vec![(root, Frame::WORLD)];
        while let Some((id, parent)) = work.pop() {
            let node = tree.node(id);
            match &node.kind {
                NodeKind::Op {
                    smooth: None,
                    children,
                    ..
                } => {
                    let frame = parent.child(&node.transform);
                    work.extend(children.iter().map(|&c| (c, frame)));
                }
                NodeKind::Op { .. } => {}
                NodeKind::Leaf { shape, .. } => {
                    let frame = parent.child(&node.transform);
                    if self.outside_scene(shape, &frame) {
                        continue;
                    }
                    let (p, c) = self.estimate(shape, &frame)?;
                    if p > 6 {
                        e.round = e.round.saturating_add(c);
                    }
                    e.polygons = e.polygons.saturating_add(p);
                    e.corners = e.corners.saturating_add(c);
                    e.leaves += 1;
                }
            }
        }
        Ok(e)
    }

    /// A tolerance, to three significant digits as the message prints it, at which the
    /// scene's estimate `e` (at `self.tol`) comes within both budgets: about the finest, as
    /// each step scales the last by how far over it still is. `None` where none does within a
    /// factor of 10⁶ (boxes and outlines dominate, or the angle bound sets the segment counts).
    fn tolerance_that_fits(&self, root: NodeId, mut e: Estimate) -> Result<Option<f64>> {
        let mut tol = self.tol;
        for _ in 0..64 {
            // Polygons go as 1/tolerance; a step of at least 1 % where rounding of segment
            // counts keeps the estimate just over.
            let next = tol * e.over().max(1.01);
            if next > 1e6 * self.tol {
                break;
            }
            // The value as printed, read back: what the user will pass.
            tol = format!("{:.2e}", round_up(next)).parse().unwrap_or(next);
            e = Ctx { tol, ..*self }.estimate_scene(root)?;
            if e.fits() {
                return Ok(Some(tol));
            }
        }
        Ok(None)
    }

    /// About how many polygons and polygon corners the tessellation of `shape` has (exact
    /// for round primitives; profiles by their points and the turn's or twist's slices).
    fn estimate(&self, shape: &Shape, frame: &Frame) -> Result<(u64, u64)> {
        let n = |r: f64| self.segments(r, frame).map(u64::from);
        Ok(match shape {
            Shape::Sphere { radius } => {
                let s = n(*radius)?;
                let p = s * (s / 2).max(2);
                (p, 4 * p)
            }
            Shape::Cylinder { radius, .. } => (n(*radius)? + 2, 6 * n(*radius)?),
            Shape::Cone {
                r_bottom, r_top, ..
            } => {
                let s = n(r_bottom.max(*r_top))?;
                (s + 2, 6 * s)
            }
            Shape::Torus { major, minor } => {
                let p = n(major + minor)? * n(*minor)?;
                (p, 4 * p)
            }
            // Profiles: their own point budget bounds the polygons; the corners count.
            Shape::Extrude(e) => {
                let points = self.profile_points(&e.shape, frame)?;
                let slices = (e.twist.abs() / TWIST_DEGREES_PER_SLICE).ceil().max(1.0) as u64;
                // Walls: a quad per edge, or two triangles per edge and slice when twisted.
                let walls = if e.twist == 0.0 { 4 } else { 6 * slices };
                (0, points * walls + 2 * points)
            }
            Shape::Revolve { shape, angle } => {
                let points = self.profile_points(shape, frame)?;
                let turn = (angle.abs() / 360.0).min(1.0);
                let segments = (n(self.profile_reach(shape))? as f64 * turn).ceil() as u64;
                (0, 4 * points * segments.max(1))
            }
            Shape::Box { .. } | Shape::Plane { .. } => (6, 24),
            Shape::Pyramid { .. } => (5, 16),
        })
    }

    /// About how many points the outline of a 2D shape has at this tolerance: every placed
    /// primitive's, round ones by their chordal segment counts.
    fn profile_points(&self, shape: &Shape2, frame: &Frame) -> Result<u64> {
        let mut points: u64 = 0;
        for (prim, _) in shape.parts().0 {
            points = points.saturating_add(match prim {
                Prim2::Rect { .. } => 4,
                Prim2::Polygon { points } => points.len() as u64,
                Prim2::RegularPolygon { sides, .. } => u64::from(*sides),
                Prim2::Circle { radius } => u64::from(self.segments(*radius, frame)?),
                Prim2::RoundedRect { radius, .. } => 4 + u64::from(self.segments(*radius, frame)?),
            });
        }
        Ok(points)
    }

    /// The farthest a 2D shape's primitives reach from the axis (for a revolution's segments).
    fn profile_reach(&self, shape: &Shape2) -> f64 {
        shape
            .parts()
            .0
            .iter()
            .map(|(prim, place)| {
                let r = match prim {
                    Prim2::Rect { half } | Prim2::RoundedRect { half, .. } => half.length(),
                    Prim2::Circle { radius } | Prim2::RegularPolygon { radius, .. } => *radius,
                    Prim2::Polygon { points } => {
                        points.iter().map(|p| p.length()).fold(0.0, f64::max)
                    }
                };
                place.pos.length() + r
            })
            .fold(0.0, f64::max)
    }
}

/// `x` rounded up to three significant digits (so that printing it with `{:.2e}` does not
/// round it down).
fn round_up(x: f64) -> f64 {
    let unit = 10f64.powi(x.log10().floor() as i32 - 2);
    (x / unit).ceil() * unit * (1.0 + 4.0 * f64::EPSILON)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sdf::bsp_route::TessellationOptions;
    use crate::sdf::scene::Scene;

    /// The tolerance named in a budget refusal's message.
    fn named_tolerance(e: &Error) -> f64 {
        let text = e.to_string();
        text.split("at least ")
            .nth(1)
            .and_then(|r| r.split(',').next())
            .and_then(|t| t.parse().ok())
            .unwrap_or_else(|| panic!("no tolerance named: {text}"))
    }

    /// Issue 12 item 6: four unit spheres at a tolerance of 10⁻⁶ were refused by the polygon
    /// budget with "use a tolerance of at least 2.35e-6", which the work budget then refused
    /// ("at least 4.71e-6"). Whichever budget refuses, the tolerance it names passes both.
    #[test]
    fn a_budget_refusal_names_a_tolerance_that_passes_both_budgets() {
        let sphere = |x: f64, y: f64, z: f64| {
            format!(
                r#"{{"kind":"sdf_primitive","pos":[{x},{y},{z}],"data":{{"primitive_type":"sphere","radius":1}}}}"#
            )
        };
        let four = format!(
            r#"{{"op":"union","children":[{},{},{},{}]}}"#,
            sphere(0.0, 0.0, 0.0),
            sphere(0.5, 0.0, 0.0),
            sphere(0.0, 0.5, 0.0),
            sphere(0.0, 0.0, 0.5)
        );
        let many: Vec<String> = (0..40)
            .map(|i| sphere(0.1 * f64::from(i), 0.0, 0.0))
            .collect();
        let many = format!(r#"{{"op":"union","children":[{}]}}"#, many.join(","));
        for (doc, tolerances) in [(&four, [1e-7, 1e-6, 2.36e-6]), (&many, [1e-6, 1e-5, 1e-4])] {
            let scene = Scene::from_json_str(doc).unwrap();
            for tol in tolerances {
                let opts = TessellationOptions::with_tolerance(tol);
                let ctx = scene.bsp_context(&opts).unwrap().unwrap();
                let refusal = ctx.check_budget(scene.root).unwrap_err();
                let named = named_tolerance(&refusal);
                let at_named = TessellationOptions::with_tolerance(named);
                let ctx = scene.bsp_context(&at_named).unwrap().unwrap();
                assert!(
                    ctx.check_budget(scene.root).is_ok(),
                    "at {tol:e}: {refusal}; at {named:e}: {}",
                    ctx.check_budget(scene.root).unwrap_err()
                );
                // And it is about the finest that does: 5 % finer is refused.
                let finer = TessellationOptions::with_tolerance(named / 1.05);
                let ctx = scene.bsp_context(&finer).unwrap().unwrap();
                assert!(
                    ctx.check_budget(scene.root).is_err(),
                    "{named:e} / 1.05 fits"
                );
            }
        }
    }

    /// A sphere at `max_angle` 0.1° has 3,600 segments to a turn, 6.48 million polygons, at
    /// any tolerance: the refusal names the angle (it was an `Error::Scene` saying a tolerance
    /// changes only round parts, with a sphere the only part).
    #[test]
    fn a_budget_refusal_where_the_angle_bound_decides_names_max_angle() {
        let scene = Scene::from_json_str(
            r#"{"kind":"sdf_primitive","data":{"primitive_type":"sphere","radius":1}}"#,
        )
        .unwrap();
        let opts = TessellationOptions {
            max_angle: Some(0.1),
            ..TessellationOptions::with_tolerance(0.01)
        };
        let refusal = scene.to_solid(&opts).unwrap_err();
        let Error::InvalidParameter {
            name,
            value,
            reason,
        } = &refusal
        else {
            panic!("{refusal:?}");
        };
        assert_eq!((*name, *value), ("max_angle", 0.1), "{refusal}");
        assert!(reason.contains("3600 segments to a turn"), "{refusal}");
        // A larger angle fits.
        let opts = TessellationOptions {
            max_angle: Some(1.0),
            ..opts
        };
        let ctx = scene.bsp_context(&opts).unwrap().unwrap();
        assert!(ctx.check_budget(scene.root).is_ok());
    }
}
