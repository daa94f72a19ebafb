//! The BSP route: a scene as a [`Solid`], each primitive tessellated from a chordal tolerance
//! and the tree's booleans done by the kernel. Smooth operations have no exact polygonal form,
//! so their subtrees are baked by marching cubes and then take part in the booleans like any
//! other solid. Materials ride on the polygons' source ids throughout.

use glam::{DAffine3, DQuat, DVec2, DVec3};

use super::eval::{Program, map_box};
use super::marching_cubes::{Lattice, Refine, march};
use super::scene::Scene;
use super::shapes::Shape;
use super::shapes2d::{Prim2, Shape2};
use super::tree::{Frame, NodeId, NodeKind};
use crate::error::{Error, Result};
use crate::geom::{Aabb, Tolerance};
use crate::mesh::repair::WELD_TOLERANCES;
use crate::polygon::Polygon;
use crate::primitives::{MIN_SEGMENTS, segments_for_tolerance};
use crate::sketch::{ExtrudeOptions, Sketch, TWIST_DEGREES_PER_SLICE};
use crate::solid::BoolOp;
use crate::solid::Solid;

mod reach;

/// How to turn a scene into a [`Solid`] (the BSP route).
///
/// Round primitives (spheres, cylinders, cones, tori, revolved profiles) get enough segments
/// that no chord strays more than the tolerance from the true surface *and* no segment turns
/// through more than the angle. The chordal bound alone makes large shapes fine and small ones
/// coarse (at the default tolerance a hole 1/50 of the scene would be a 12-gon); the angle
/// bound alone would ignore size. With the defaults (1/500 of the scene's diagonal and 10°,
/// manifold's default circular angle) a circle has at least 36 segments:
///
/// ```
/// use bspcsg::{Scene, TessellationOptions};
///
/// let scene = Scene::from_json_str(
///     r#"{"kind": "sdf_primitive", "data": {"primitive_type": "sphere", "radius": 1.0}}"#,
/// )?;
/// let sphere = scene.to_solid(&TessellationOptions::default())?;
/// let exact = 4.0 / 3.0 * std::f64::consts::PI;
/// // 36 segments and 18 rings: within 1.5 % of the sphere's volume (27 × 13, 2.3 % short,
/// // by the tolerance alone).
/// assert!((sphere.volume() - exact).abs() < 0.015 * exact);
/// // A chosen tolerance is the whole request unless an angle is given too.
/// let coarse = scene.to_solid(&TessellationOptions::with_tolerance(0.1))?;
/// assert!(coarse.polygons().len() < sphere.polygons().len());
/// # Ok::<(), bspcsg::Error>(())
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TessellationOptions {
    /// The largest distance a chord may stray from a round surface. `None`: 1/500 of the
    /// scene's bounding diagonal.
    pub tolerance: Option<f64>,
    /// The marching-cubes cell for smooth subtrees. `None`: four times the tolerance.
    pub cell: Option<f64>,
    /// The largest angle, in degrees, one segment of a round surface may turn through (in
    /// (0, 120]). `None`: [`DEFAULT_MAX_ANGLE`] when the tolerance is the default too, no angle
    /// bound when a tolerance is given.
    pub max_angle: Option<f64>,
}

/// The angle bound of the default tessellation, in degrees: 36 segments to a circle.
pub const DEFAULT_MAX_ANGLE: f64 = 10.0;

impl TessellationOptions {
    /// Options with a chordal tolerance (and no angle bound).
    #[must_use]
    pub fn with_tolerance(tolerance: f64) -> Self {
        TessellationOptions {
            tolerance: Some(tolerance),
            cell: None,
            max_angle: None,
        }
    }

    /// The angle bound in degrees that applies, if any.
    fn angle(&self) -> Option<f64> {
        match (self.max_angle, self.tolerance) {
            (Some(a), _) => Some(a),
            (None, None) => Some(DEFAULT_MAX_ANGLE),
            (None, Some(_)) => None,
        }
    }
}

impl Scene {
    /// The scene as a solid by the BSP route (see the module docs of `sdf`). Fails for an
    /// unbounded scene or an out-of-range tolerance.
    ///
    /// # Errors
    ///
    /// [`Error::Unbounded`] for a scene with an unbounded half-space,
    /// [`Error::InvalidParameter`] for a tolerance or cell that is not finite and positive or
    /// too fine for a primitive; [`Error::BeyondPrecision`] where parts meet (or a part lies)
    /// too far from the origin for their size (see [`Solid::check_precision`]).
    pub fn to_solid(&self, opts: &TessellationOptions) -> Result<Solid> {
        let Some(ctx) = self.bsp_context(opts)? else {
            return Ok(Solid::empty());
        };
        ctx.check_budget(self.root)?;
        let solid = ctx.solid(self.root)?;
        solid.check_precision()?;
        Ok(solid)
    }

    /// The BSP route's settings for this scene (`None` for an empty scene), checked.
    fn bsp_context(&self, opts: &TessellationOptions) -> Result<Option<Ctx<'_>>> {
        let world = self.bound.bbox;
        if world.is_empty() {
            return Ok(None);
        }
        if !(world.min.is_finite() && world.max.is_finite()) {
            return Err(Error::Unbounded {
                what: "the scene",
                why: "a half-space not intersected with a bounded shape",
                remedy: "it has no solid; intersect the half-space with a bounded shape",
            });
        }
        let tol = opts.tolerance.unwrap_or(world.diagonal() / 500.0);
        if !(tol.is_finite() && tol > 0.0) {
            return Err(Error::param("tolerance", tol, "must be finite and > 0"));
        }
        let cell = opts.cell.unwrap_or(4.0 * tol);
        let min_segments = match opts.angle() {
            None => MIN_SEGMENTS,
            Some(a) if a.is_finite() && a > 0.0 && a <= 120.0 => (360.0 / a).ceil() as u32,
            Some(a) => return Err(Error::param("max_angle", a, "must be in (0, 120] degrees")),
        };
        Ok(Some(Ctx {
            scene: self,
            tol,
            cell,
            world,
            min_segments,
            max_angle: opts.max_angle,
        }))
    }
}

#[derive(Clone, Copy)]
struct Ctx<'a> {
    scene: &'a Scene,
    tol: f64,
    cell: f64,
    world: Aabb,
    /// The fewest segments a full turn gets, from the angle bound.
    min_segments: u32,
    /// The angle bound, where the options give one (not the default tessellation's).
    max_angle: Option<f64>,
}

/// The most polygons the BSP route tessellates for a whole scene: as many as one primitive may
/// have ([`crate::MAX_POLYGONS`], about 800 MB of polygons). The booleans that combine them
/// need several times the memory of their operands, so a scene of several primitives each just
/// under the per-primitive limit (four unit spheres at a tolerance of 10⁻⁶) would otherwise run
/// out of memory.
pub const MAX_SCENE_POLYGONS: u64 = crate::primitives::MAX_POLYGONS;

/// The most boolean work the BSP route takes on for a scene: the polygon corners of all its
/// primitives times the levels of the balanced reduction that combines them
/// (`⌈log₂ primitives⌉`, at least 1), each level clipping every corner once or more. 2²⁴:
/// about a minute and 1–2 GB on a 2-core machine (twenty unions of one 10,000-point polygon
/// extruded, 6·10⁶, take 38 s and 1 GB). Past it — 300 references to one 10,000-point polygon,
/// 100,000 overlapping boxes, four unit spheres at a tolerance of 2.4·10⁻⁶ — the export is
/// refused at once, saying what to change. The estimate counts corners, not how the kernel
/// fares with them: faces of different primitives that nearly coincide (copies of one
/// 10,000-point outline a little apart: four took over 10 minutes and 3 GB) cost far more, and
/// are not bounded by it.
pub const MAX_SCENE_WORK: u64 = 1 << 24;

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
    fn check_budget(&self, root: NodeId) -> Result<()> {
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

    fn solid(&self, root: NodeId) -> Result<Solid> {
        enum Work {
            Visit(NodeId, Frame),
            Combine(BoolOp, usize),
        }
        let tree = &self.scene.tree;
        let mut work = vec![Work::Visit(root, Frame::WORLD)];
        let mut done: Vec<Solid> = Vec::new();
        while let Some(w) = work.pop() {
            match w {
                Work::Combine(op, n) => {
                    let children = done.split_off(done.len() - n);
                    done.push(combine(op, children));
                }
                Work::Visit(id, parent) => {
                    let node = tree.node(id);
                    match &node.kind {
                        NodeKind::Op {
                            smooth: Some(_), ..
                        } => done.push(self.bake(id, parent)?),
                        NodeKind::Op {
                            op,
                            smooth: None,
                            children,
                        } => {
                            let frame = parent.child(&node.transform);
                            work.push(Work::Combine(*op, children.len()));
                            for &c in children.iter().rev() {
                                work.push(Work::Visit(c, frame));
                            }
                        }
                        NodeKind::Leaf { shape, material } => {
                            let frame = parent.child(&node.transform);
                            if self.outside_scene(shape, &frame) {
                                done.push(Solid::empty());
                                continue;
                            }
                            let local = self.tessellate(shape, &frame)?;
                            let local_box = local.bbox();
                            let world = local.transform(frame.to_world)?;
                            check_thickness(&local_box, &world, &frame)?;
                            done.push(world.with_source(*material));
                        }
                    }
                }
            }
        }
        Ok(done.pop().unwrap_or_default())
    }

    /// Bakes a smooth subtree by marching cubes into a solid of triangles.
    fn bake(&self, id: NodeId, parent: Frame) -> Result<Solid> {
        let program = Program::compile(&self.scene.tree, id, parent)?;
        let bound = program.bound();
        // Every bake of the scene samples one lattice, that of the grid over the whole scene
        // (its box grown by the cell), each on the part of it around its own bound: where two
        // smooth subtrees hold the same surface (a shape in both), its vertices come out the
        // same in both (the roots refined until they no longer move), so the booleans meet
        // coincident faces, not walls 10⁻⁹ apart cut into slivers.
        let scene = self.world.expanded(self.cell);
        let Some(grid) =
            Lattice::over(&scene, self.cell)?.around(&bound.bbox.intersection(&scene))?
        else {
            return Ok(Solid::empty());
        };
        super::bake_budget::check_bake_work(&program, &grid)?;
        let mut mesh = march(&program, grid, Refine::Converge)?;
        super::assign_sources(&program, &mut mesh);
        let polygons = (0..mesh.triangle_count())
            .filter_map(|t| Polygon::new(mesh.triangle(t).as_slice(), mesh.sources[t]))
            .collect();
        Ok(Solid::from_polygons(polygons))
    }

    /// Segments for a full turn of `radius` (in the local frame): the chordal tolerance's
    /// count, at least the angle bound's.
    fn segments(&self, radius: f64, frame: &Frame) -> Result<u32> {
        self.bounded(segments_for_tolerance(radius * frame.sigma_max, self.tol)?)
    }

    fn bounded(&self, chordal: u32) -> Result<u32> {
        Ok(chordal.max(self.min_segments))
    }

    /// The primitive in its local frame.
    ///
    /// A box that reaches more than the scene's diagonal beyond the scene's box, or a cylinder
    /// or cone that does so along its axis, is cut off there first (see [`reach`]); a cut one
    /// that then misses the scene's box is empty.
    fn tessellate(&self, shape: &Shape, frame: &Frame) -> Result<Solid> {
        match shape {
            Shape::Box { half } => self.cut_box(*half, frame),
            Shape::Sphere { radius } => {
                let n = self.segments(*radius, frame)?;
                Solid::sphere(*radius, n, (n / 2).max(2))
            }
            Shape::Cylinder {
                radius,
                half_height,
            } => self.cut_frustum(
                [*radius; 2],
                *half_height,
                self.segments(*radius, frame)?,
                frame,
            ),
            Shape::Cone {
                r_bottom,
                r_top,
                half_height,
            } => self.cut_frustum(
                [*r_bottom, *r_top],
                *half_height,
                self.segments(r_bottom.max(*r_top), frame)?,
                frame,
            ),
            Shape::Pyramid { base, height } => {
                let (b, h) = (0.5 * base, 0.5 * height);
                let v = [
                    DVec3::new(-b, -h, -b),
                    DVec3::new(b, -h, -b),
                    DVec3::new(b, -h, b),
                    DVec3::new(-b, -h, b),
                    DVec3::new(0.0, h, 0.0),
                ];
                Solid::polyhedron(
                    &v,
                    &[
                        vec![0, 1, 2, 3],
                        vec![0, 4, 1],
                        vec![1, 4, 2],
                        vec![2, 4, 3],
                        vec![3, 4, 0],
                    ],
                )
            }
            Shape::Torus { major, minor } => Solid::torus(
                *major,
                *minor,
                self.segments(major + minor, frame)?,
                self.segments(*minor, frame)?,
            ),
            Shape::Plane { normal, offset } => {
                // A slab that covers the scene's box on the solid side of the plane.
                let local = map_box(&frame.to_world.inverse(), &self.world);
                let c = local.center();
                let lift = normal.dot(c) + offset;
                let l = 2.0 * (local.diagonal() + lift.abs()) + self.tol;
                let on_plane = c - *normal * lift;
                let place = DAffine3::from_rotation_translation(
                    DQuat::from_rotation_arc(DVec3::Z, *normal),
                    on_plane - *normal * (0.5 * l),
                );
                Solid::cuboid(DVec3::new(2.0 * l, 2.0 * l, l))?.transform(place)
            }
            Shape::Extrude(e) => e.shape.to_sketch(self.tol / frame.sigma_max)?.extrude_with(
                2.0 * e.half_depth,
                &ExtrudeOptions {
                    twist: e.twist,
                    slices: None,
                    scale_top: e.scale_top,
                    center: true,
                },
            ),
            Shape::Revolve { shape, angle } => {
                // The profile's chords and the turn's chords both cut inside the true surface:
                // half the tolerance each keeps their sum within it.
                let profile = shape.to_sketch(0.5 * self.tol / frame.sigma_max)?;
                // The half-plane x ≥ 0: a rectangle from the axis past the profile's reach.
                let [lo, hi] = profile.bounds().unwrap_or([DVec2::ZERO; 2]);
                let reach = hi.x.max(0.0);
                if reach == 0.0 {
                    return Ok(Solid::empty());
                }
                let span = hi - lo;
                let half_plane = Sketch::rectangle(2.0 * reach, 2.0 * span.y)?
                    .translate(DVec2::new(reach, 0.5 * (lo.y + hi.y)))?;
                let segments = self.bounded(segments_for_tolerance(
                    reach * frame.sigma_max,
                    0.5 * self.tol,
                )?)?;
                (&profile & &half_plane).revolve(*angle, segments)
            }
        }
    }
}

/// Refuses a primitive thinner, where it lies, than twice the distance at which the kernel
/// welds points (`WELD_TOLERANCES` tolerances of the floor its coordinates set): its opposite
/// faces would round onto each other (a cylinder of radius 10⁻¹⁰³ at x = 1.5 becomes a segment
/// of flat polygons, and cutting it left 8 boundary edges). Its thinnest extent is its local
/// box's thinnest side times the frame's least stretch.
fn check_thickness(lb: &Aabb, world: &Solid, frame: &Frame) -> Result<()> {
    let wb = world.bbox();
    if lb.is_empty() || wb.is_empty() {
        return Ok(());
    }
    let thinnest = (lb.max - lb.min).min_element() * frame.sigma;
    let magnitude = wb.max_abs();
    let eps = Tolerance::floor(magnitude);
    if thinnest > 2.0 * WELD_TOLERANCES * eps {
        return Ok(());
    }
    Err(Error::BeyondPrecision {
        region: thinnest,
        magnitude,
        eps,
    })
}

/// `x` rounded up to three significant digits (so that printing it with `{:.2e}` does not
/// round it down).
fn round_up(x: f64) -> f64 {
    let unit = 10f64.powi(x.log10().floor() as i32 - 2);
    (x / unit).ceil() * unit * (1.0 + 4.0 * f64::EPSILON)
}

fn combine(op: BoolOp, children: Vec<Solid>) -> Solid {
    crate::solid::boolean_all(children, op)
}

#[cfg(test)]
mod tests {
    use super::*;

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
