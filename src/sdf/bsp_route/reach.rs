//! Long primitives cut off where they can no longer matter.
//!
//! Nothing outside the scene's box is part of the scene (its bound is conservative through
//! every union, intersection and difference), and a primitive enters each boolean only as
//! membership of points, so cutting a primitive off outside the scene's box changes nothing
//! inside it. A primitive left whole far beyond the scene keeps its long edges only to the
//! rounding of its far coordinates, which can be thousands of the boolean's tolerances where
//! they cross the scene (`scene_bsp_route_of_a_bracket_with_a_slot_1e11_long`). Cut off at the
//! reach, its coordinates are of the scene's size; primitives within the reach are left as
//! they are.

use glam::DVec3;

use super::Ctx;
use crate::error::Result;
use crate::geom::Aabb;
use crate::primitives;
use crate::sdf::eval::map_box;
use crate::sdf::shapes::Shape;
use crate::sdf::tree::Frame;
use crate::solid::Solid;

/// Where a primitive can matter, in its local frame.
struct Reach {
    /// The box holding the scene's box grown by its diagonal on every side.
    reach: Aabb,
    /// The box holding the scene's box itself.
    scene: Aabb,
}

impl Ctx<'_> {
    /// The reach of a primitive in `frame`; `None` for a scene of no size or a frame that
    /// maps it out of range.
    fn reach(&self, frame: &Frame) -> Option<Reach> {
        let d = self.world.diagonal();
        if !(d.is_finite() && d > 0.0) {
            return None;
        }
        let to_local = frame.to_world.inverse();
        let reach = map_box(&to_local, &self.world.expanded(d));
        let scene = map_box(&to_local, &self.world);
        (reach.min.is_finite() && reach.max.is_finite() && !scene.is_empty())
            .then_some(Reach { reach, scene })
    }

    /// True when a primitive's own box, placed in the world, misses the scene's box. Nothing
    /// of it is then part of the scene, and left whole its far coordinates would set the
    /// tolerance of every boolean it enters: it is left out before any polygon is made,
    /// counted against the budget or checked for thickness.
    pub(super) fn outside_scene(&self, shape: &Shape, frame: &Frame) -> bool {
        let placed = map_box(&frame.to_world, &shape.local_bounds());
        !placed.is_empty() && !placed.overlaps(&self.world, 0.0)
    }

    /// A box of half sizes `half`, cut off at the reach where it passes beyond; empty when the
    /// part left misses the scene's box.
    pub(super) fn cut_box(&self, half: DVec3, frame: &Frame) -> Result<Solid> {
        let whole = Aabb::new(-half, half);
        let Some(Reach { reach, scene }) = self.reach(frame) else {
            return Solid::cuboid(half * 2.0);
        };
        if !(whole.min.cmplt(reach.min).any() || whole.max.cmpgt(reach.max).any()) {
            return Solid::cuboid(half * 2.0);
        }
        let cut = whole.intersection(&reach);
        if !(cut.min.cmplt(cut.max).all() && cut.overlaps(&scene, 0.0)) {
            return Ok(Solid::empty());
        }
        // Built from its corners, so a face left uncut keeps its coordinate bit for bit.
        primitives::cuboid_between(cut.min, cut.max).map(Solid::from_polygons)
    }

    /// A frustum along Y with radii `[bottom, top]` at `∓half_height` and `segments` around,
    /// cut off along Y at the reach where it passes beyond (never across its radius); empty
    /// when the part left misses the scene's box.
    pub(super) fn cut_frustum(
        &self,
        r: [f64; 2],
        half_height: f64,
        segments: u32,
        frame: &Frame,
    ) -> Result<Solid> {
        let whole = || Solid::frustum(r[0], r[1], 2.0 * half_height, segments);
        let Some(Reach { reach, scene }) = self.reach(frame) else {
            return whole();
        };
        let (bottom, top) = (-half_height, half_height);
        let (y0, y1) = (bottom.max(reach.min.y), top.min(reach.max.y));
        // The reach across the axis, within the frustum's inscribed radius: inside the reach
        // the frustum is a cuboid. Left whole its caps, far wider than the scene, are cut
        // where they cross it at the rounding of their far corners, hundreds of the
        // boolean's tolerances (`scenes_bsp_route_of_a_box_less_a_cylinder_4e7_wide`).
        let corner = DVec3::new(
            reach.min.x.abs().max(reach.max.x.abs()),
            0.0,
            reach.min.z.abs().max(reach.max.z.abs()),
        );
        let inscribed = r[0].min(r[1]) * (std::f64::consts::PI / f64::from(segments.max(3))).cos();
        if corner.length() < 0.5 * inscribed {
            let cut = Aabb::new(
                DVec3::new(reach.min.x, y0, reach.min.z),
                DVec3::new(reach.max.x, y1, reach.max.z),
            );
            if !(y0 < y1 && cut.overlaps(&scene, 0.0)) {
                return Ok(Solid::empty());
            }
            return primitives::cuboid_between(cut.min, cut.max).map(Solid::from_polygons);
        }
        if !(bottom < reach.min.y || top > reach.max.y) {
            return whole();
        }
        let rmax = r[0].max(r[1]);
        let cut = Aabb::new(DVec3::new(-rmax, y0, -rmax), DVec3::new(rmax, y1, rmax));
        if !(y0 < y1 && cut.overlaps(&scene, 0.0)) {
            return Ok(Solid::empty());
        }
        // An end left uncut keeps its radius and height bit for bit.
        let radius = |y: f64| match y {
            y if y == bottom => r[0],
            y if y == top => r[1],
            y => r[0] + (r[1] - r[0]) * ((y - bottom) / (top - bottom)),
        };
        primitives::frustum_between(radius(y0), radius(y1), y0, y1, segments)
            .map(Solid::from_polygons)
    }
}

#[cfg(test)]
mod tests {
    use glam::{DAffine3, DVec3};

    use super::Ctx;
    use crate::geom::Aabb;
    use crate::sdf::scene::Scene;
    use crate::sdf::tree::Frame;

    /// Long primitives placed `half` along the axis so their near end sits at the scene's
    /// middle: cut off at the far end (the reach is irrational there, the scene's diagonal
    /// being √14), the near end keeps its local coordinate bit for bit. Sized and then moved,
    /// the box's near face came out an ulp off in some of these.
    #[test]
    fn a_cut_primitive_keeps_its_uncut_end_exactly() {
        let scene = Scene::from_json_str(
            r#"{"kind": "sdf_primitive", "data": {"primitive_type": "sphere", "radius": 1}}"#,
        )
        .unwrap();
        let ctx = Ctx {
            scene: &scene,
            tol: 0.01,
            cell: 0.04,
            world: Aabb::new(DVec3::new(0.0, -1.0, -1.5), DVec3::new(1.0, 1.0, 1.5)),
            min_segments: 3,
            max_angle: None,
        };
        for k in 0..40 {
            let half = 1e6 * (1.0 + f64::from(k) / 7.0);
            let along = |axis: DVec3| Frame {
                to_world: DAffine3::from_translation(axis * half),
                sigma: 1.0,
                sigma_max: 1.0,
            };
            let cut = ctx
                .cut_box(DVec3::new(half, 2.0, 2.0), &along(DVec3::X))
                .unwrap();
            let b = cut.bbox();
            assert_eq!(b.min.x, -half, "box of half length {half}");
            assert!(
                b.max.x < -half + 10.0,
                "box of half length {half} not cut: {}",
                b.max.x
            );
            let cut = ctx
                .cut_frustum([1.0, 0.5], half, 16, &along(DVec3::Y))
                .unwrap();
            let b = cut.bbox();
            assert_eq!(b.min.y, -half, "frustum of half height {half}");
            assert!(
                b.max.y < -half + 10.0,
                "frustum of half height {half} not cut: {}",
                b.max.y
            );
            // The bottom radius uncut: the ring's vertex on an axis at 1 exactly.
            let mut bottom = cut.polygons().iter().flat_map(|p| p.vertices().iter());
            assert!(bottom.any(|v| v.y == -half && (v.x.abs() == 1.0 || v.z.abs() == 1.0)));
        }
    }
}
