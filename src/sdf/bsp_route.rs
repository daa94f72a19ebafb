//! The BSP route: a scene as a [`Solid`], each primitive tessellated from a chordal tolerance
//! and the tree's booleans done by the kernel. Smooth operations have no exact polygonal form,
//! so their subtrees are baked by marching cubes and then take part in the booleans like any
//! other solid. Materials ride on the polygons' source ids throughout.

use glam::{DAffine3, DQuat, DVec2, DVec3};

use super::eval::{Program, map_box};
use super::marching_cubes::{Lattice, Refine, march};
use super::scene::Scene;
use super::shapes::Shape;
use super::tree::{Frame, NodeId, NodeKind};
use crate::bsp::Meter;
use crate::error::{Error, Result};
use crate::geom::{Aabb, Tolerance};
use crate::mesh::repair::WELD_TOLERANCES;
use crate::polygon::Polygon;
use crate::primitives::{MIN_SEGMENTS, segments_for_tolerance};
use crate::sketch::{ExtrudeOptions, Sketch};
use crate::solid::BoolOp;
use crate::solid::Solid;

mod budget;
mod reach;

pub use budget::{MAX_SCENE_POLYGONS, MAX_SCENE_WORK};

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
    /// too far from the origin for their size (see [`Solid::check_precision`]);
    /// [`Error::Scene`] (at `$`) for a scene over its budget of polygons or boolean work:
    /// before tessellating by the estimate from its primitives' segment counts, or when its
    /// booleans are stopped at [`MAX_SCENE_WORK`] (see [`Solid::check_budget`]: faces of
    /// different primitives that nearly coincide over a wide area).
    pub fn to_solid(&self, opts: &TessellationOptions) -> Result<Solid> {
        self.to_solid_within(opts, MAX_SCENE_WORK)
    }

    /// [`Scene::to_solid`] with its booleans' work stopped past `work` (the cut corners of
    /// [`Solid::check_budget`], all the scene's booleans together).
    fn to_solid_within(&self, opts: &TessellationOptions, work: u64) -> Result<Solid> {
        let Some(ctx) = self.bsp_context(opts)? else {
            return Ok(Solid::empty());
        };
        ctx.check_budget(self.root)?;
        let meter = Meter::new(work);
        let solid = ctx.solid(self.root, &meter)?;
        // The scene's own kind of budget refusal, as the estimate's: what to change in it.
        solid.check_budget().map_err(|e| Error::Scene {
            file: None,
            json_path: "$".into(),
            message: format!(
                "{e}; or use fewer primitives or 2D shapes of fewer points, or the \
                 marching-cubes route (--via sdf)"
            ),
        })?;
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

impl Ctx<'_> {
    /// The scene's solid, its booleans' work charged to `meter`.
    fn solid(&self, root: NodeId, meter: &Meter) -> Result<Solid> {
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
                    done.push(crate::solid::boolean_all_metered(children, op, meter));
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
        super::bake_budget::check_bake_work(&program, &grid, |cell| {
            let scene = self.world.expanded(cell);
            Lattice::over(&scene, cell)?.around(&bound.bbox.intersection(&scene))
        })?;
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
