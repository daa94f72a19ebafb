//! # bspcsg
//!
//! Constructive solid geometry on polygon meshes: union, intersection and difference of solids
//! by BSP trees and the csg.js clipping rules, with output that is a closed 2-manifold.
//!
//! ```
//! use bspcsg::Solid;
//! use bspcsg::glam::DVec3; // the glam version this crate uses, re-exported
//!
//! let block = Solid::cuboid(DVec3::new(2.0, 1.0, 1.0))?;
//! let hole = Solid::cylinder(0.3, 2.0, 48)?;
//! let part = &block - &hole;
//! assert!(part.volume() < block.volume());
//! // Checked: a closed 2-manifold within the precision contract, or an error saying why not.
//! let mesh = part.to_checked_mesh()?;
//! assert!(mesh.triangle_count() > 0);
//! # Ok::<(), bspcsg::Error>(())
//! ```
//!
//! # Features
//!
//! - `cli` (default): the `bspcsg` command line tool and the dependencies only it needs
//!   (`clap`, `indicatif`). Libraries depending on this crate can turn it off with
//!   `default-features = false`; the whole library API stays.
//!
//! The modules, bottom to top, and the import order CI enforces are in `ARCHITECTURE.md`.
//!
//! # Scenes
//!
//! A [`Scene`] is a tree of signed distance functions read from JSON (the format is in
//! `docs/scene-format.md`). It meshes two ways: [`Scene::bake`] by marching cubes (closed
//! 2-manifold output), and [`Scene::to_solid`] by tessellating each primitive and combining them
//! with this crate's booleans.
//!
//! # Sketches
//!
//! A [`Sketch`] is a 2D region of the xy plane (polygons with holes). Its booleans cut each
//! operand's edges by a BSP tree of the other's, each edge a knife whose line splits what it
//! meets into in, on and out parts; [`Sketch::extrude_with`] (twist, taper to a point) and
//! [`Sketch::revolve`] (about Y) turn it into a [`Solid`].
//!
//! ```
//! use bspcsg::Sketch;
//! use bspcsg::glam::DVec2;
//! let washer = &Sketch::circle(1.0, 1e-3)? - &Sketch::circle(0.5, 1e-3)?;
//! assert_eq!(washer.extrude(0.2)?.to_mesh().report().genus, Some(1));
//! // Turned about the y axis, the washer is a torus with a torus-shaped cavity: two shells.
//! let hollow = washer.translate(DVec2::new(2.0, 0.0))?.revolve(360.0, 64)?;
//! assert_eq!(hollow.to_mesh().report().shells.len(), 2);
//! # Ok::<(), bspcsg::Error>(())
//! ```
//!
//! # Conventions
//!
//! Right-handed, Y up; primitives are centred at the origin and cylinders run along Y. Faces
//! wind counter-clockwise seen from outside, so a closed solid has positive volume. All
//! arithmetic is `f64` (glam's `DVec3`).
//!
//! # Tolerance
//!
//! Every boolean uses one plane-side epsilon: a vertex within `eps` of a plane lies on it, both
//! when polygons are classified and when they are split.
//!
//! `eps = max(1e-12 × d, 2⁻⁴⁰ × m)`, where `d` is the diagonal of the region where the two
//! operands' bounding boxes meet and `m` the largest coordinate magnitude in it (the floor keeps
//! `eps` above rounding error far from the origin). Scaling both operands by any factor scales
//! `eps` with them, so results at scale 10⁻⁶, 1 and 10⁶ are the same up to that scale; a huge
//! operand does not blur a small one, because only the region they share counts. A solid made
//! by a boolean carries its `eps`, and later booleans never use a smaller one.
//!
//! # Precision
//!
//! Far from the origin the floor `2⁻⁴³ × m` can dwarf `10⁻¹² × d`. A boolean whose tolerance
//! (from the floor, or carried from an earlier, larger boolean) exceeds
//! [`Tolerance::PRECISION_LIMIT`] (10⁻⁵) of the region where its operands meet cannot promise
//! its answer: it marks its result, the mark passes to every solid made from it, and
//! [`Solid::check_precision`] turns it into [`Error::BeyondPrecision`] (the command line exits
//! 2, [`Scene::to_solid`] fails). Within the limit the surface is within a few `eps` of the
//! exact one, so a unit part is exact up to about 10⁸ from the origin and refused from about
//! 10⁹ on; a part 10³ across, up to about 10¹¹.
//!
//! # Input range
//!
//! Coordinates must be finite and at most [`MAX_COORDINATE`] (10¹⁰⁰) in magnitude; primitive
//! sizes, transforms and imported meshes that go beyond are refused with an error. Within the
//! range, features down to about 10⁻¹² of the region where two operands meet are kept: a
//! 2-unit part inside a box reaching 10³⁸ comes out exact.
//!
//! # Stack safety
//!
//! Trees live in arenas (`Vec` with `u32` links) and every pass — build, clip, point location,
//! drop — walks them with an explicit work stack, so no input can overflow the stack.
//!
//! # Panics
//!
//! Public functions do not panic on any input; constructors return [`Result`].

#![warn(missing_docs)]

mod bsp;
mod disjoint_sets;
pub mod edit;
mod error;
mod geom;
mod hash;
mod io;
mod mesh;
mod polygon;
mod primitives;
pub mod raymarch;
mod sdf;
mod sketch;
mod solid;
mod topology;

pub use error::{Error, MeshDefect, Result};
pub use geom::{
    Aabb, MAX_COORDINATE, NEEDLE_SPECK_THICKNESSES, NEEDLE_THIN, NEEDLE_THIN_SHELL,
    NEEDLE_WELD_TOLERANCES, Plane, Side, Tolerance, is_needle_to_remove,
};
pub use io::{
    Format, MAX_BUFFER_BYTES, MAX_READ_TRIANGLES, OutFile, ParseFormatError, as_read_back_from,
    cleanup_interrupted_writes, encode_mesh, read_mesh, read_mesh_as, read_mesh_from_bytes,
    read_solid, referenced_files, write_mesh, write_mesh_as,
};
pub use mesh::{
    FromMeshOptions, MAX_CROSSING_PAIRS, Material, Mesh, MeshReport, PAIR_BUDGET_BASE,
    PAIR_BUDGET_PER_TRIANGLE, ShellReport,
};
pub use polygon::{Polygon, Split};
pub use primitives::{MAX_POLYGONS, MAX_SEGMENTS, MIN_SEGMENTS, segments_for_tolerance};
pub use sdf::{
    BakeOptions, DEFAULT_MAX_ANGLE, MAX_BAKE_TRIANGLES, MAX_BAKE_WORK, MAX_GRID_CELLS,
    MAX_GRID_TOTAL, MAX_POLYGON_POINTS, MAX_REFINE_STEPS, MAX_SCENE_MAGNITUDE, MAX_SCENE_POLYGONS,
    MAX_SCENE_WORK, RenderProfile, Scene, SceneCamera, TessellationOptions,
};
pub use sketch::{ExtrudeOptions, FillRule, Region, Sketch, SketchReport, TWIST_DEGREES_PER_SLICE};
pub use solid::{
    BoolOp, Containment, MAX_BOOLEAN_WORK, MESH_VOLUME_RELATIVE, MESH_VOLUME_TOLERANCES,
    ParseBoolOpError, PointClassifier, Solid, WORK_PER_POLYGON, boolean, boolean_all, boolean_with,
};

pub use glam;

/// The README's example, compiled and run as a doctest.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
