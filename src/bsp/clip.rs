//! Clipping polygons against a tree: csg.js's `clipPolygons`, with a work stack instead of
//! recursion, whole-fragment classification away from the surface, and a choice of which way
//! coplanar polygons go.

use glam::DVec3;
use rayon::prelude::*;

use super::meter::{CHARGE_EVERY, Meter};
use super::{Kind, Label, Link, Surface, Tree};
use crate::geom::Aabb;
use crate::hash::FxHashMap;
use crate::polygon::{Polygon, Split};

/// Where a polygon lying in a face node's plane goes.
///
/// csg.js sends a coplanar polygon facing the same way as the node to the front and one facing
/// the other way to the back (`SameFront`). Clipping the *inverted* polygons, as its
/// invert-clip-invert step does, reverses that (`SameBack`); expressing it as a rule saves
/// inverting polygon lists twice.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Coplanar {
    SameFront,
    SameBack,
}

/// A fragment that survived clipping, and whether any face node routed it as coplanar (only
/// those can come out differently under the other [`Coplanar`] rule).
pub(crate) struct Clipped {
    pub polygon: Polygon,
    pub coplanar: bool,
}

/// Below this many polygons clipping runs on the calling thread.
const PARALLEL_MIN: usize = 512;
const CHUNK: usize = 256;

struct Work {
    polygon: Polygon,
    bbox: Aabb,
    link: Link,
    coplanar: bool,
    /// For a fragment routed as coplanar: the unit normal pointing to the side it was sent to.
    /// It lies on the tree's surface, so a ray from it would be meaningless; the ray starts a
    /// little way off on that side instead.
    side: DVec3,
}

impl Tree {
    /// Clips `polygons` against the tree and keeps the fragments in regions labelled `keep`.
    /// `surface` (the tree's solid) labels fragments whose point location ends in an unbuilt
    /// cell. The corners of the pieces cut are charged to `meter`; once it is past its limit
    /// the clip stops, and what it returns is incomplete (the caller asks the meter).
    pub fn clip(
        &self,
        polygons: Vec<Polygon>,
        keep: Label,
        rule: Coplanar,
        surface: &Surface,
        meter: &Meter,
    ) -> Vec<Clipped> {
        if meter.exceeded() {
            return Vec::new();
        }
        if polygons.len() < PARALLEL_MIN {
            let mut out = Vec::with_capacity(polygons.len());
            let mut scratch = Scratch::default();
            for p in polygons {
                self.clip_one(p, keep, rule, surface, &mut scratch, &mut out);
                if scratch.cut >= CHARGE_EVERY && !meter.charge(std::mem::take(&mut scratch.cut)) {
                    break;
                }
            }
            meter.charge(scratch.cut);
            return out;
        }
        // One scratch per piece of work rayon splits off, not per chunk: the points labelled
        // in unbuilt cells serve every later chunk it clips.
        let parts: Vec<Vec<Clipped>> = polygons
            .into_par_iter()
            .chunks(CHUNK)
            .map_init(Scratch::default, |scratch, chunk| {
                let mut out = Vec::with_capacity(chunk.len());
                if meter.exceeded() {
                    return out;
                }
                for p in chunk {
                    self.clip_one(p, keep, rule, surface, scratch, &mut out);
                    if scratch.cut >= CHARGE_EVERY
                        && !meter.charge(std::mem::take(&mut scratch.cut))
                    {
                        break;
                    }
                }
                // The rest now: the scratch may serve no further chunk.
                meter.charge(std::mem::take(&mut scratch.cut));
                out
            })
            .collect();
        parts.into_iter().flatten().collect()
    }

    fn clip_one(
        &self,
        polygon: Polygon,
        keep: Label,
        rule: Coplanar,
        surface: &Surface,
        scratch: &mut Scratch,
        out: &mut Vec<Clipped>,
    ) {
        let Scratch {
            stack,
            labelled,
            recent,
            cut,
        } = scratch;
        let eps = self.eps;
        let margin = 2.0 * eps;
        let bbox = polygon.bbox();
        stack.push(Work {
            polygon,
            bbox,
            link: self.root,
            coplanar: false,
            side: DVec3::ZERO,
        });
        // One fragment is followed down in place while it stays whole; a cut leaves its back
        // piece on the stack. Popping and pushing a fragment at every node copied ~300 bytes
        // twice per step (a third of all copying on real models); the order is the same.
        while let Some(mut w) = stack.pop() {
            loop {
                let i = match w.link {
                    Link::Leaf(label) => {
                        if label == keep {
                            out.push(Clipped {
                                polygon: w.polygon,
                                coplanar: w.coplanar,
                            });
                        }
                        break;
                    }
                    Link::Node(i) => i,
                };
                let node = &self.nodes[i as usize];
                let is_face = matches!(node.kind, Kind::Face { .. });
                // No surface below this node comes near the fragment: it lies in one region.
                // Or a cell plane, axis-aligned, that the fragment's box spans with no surface
                // near: only the cell's box came near, so classify whole rather than cut for
                // nothing.
                let whole = !w.bbox.overlaps(&node.content, margin)
                    || matches!(node.kind, Kind::Stub { .. })
                    || (!is_face
                        && spans_axis_plane(&w.bbox, &node.plane, eps)
                        && !self.near_surface(w.link, &w.bbox, margin));
                if whole {
                    if self.label_whole(&w, surface, labelled, recent) == keep {
                        out.push(Clipped {
                            polygon: w.polygon,
                            coplanar: w.coplanar,
                        });
                    }
                    break;
                }
                let split = if is_face {
                    w.polygon.split(&node.plane, eps)
                } else {
                    match cell_side(&w, &node.plane, eps) {
                        Some(true) => Split::Front,
                        Some(false) => Split::Back,
                        None => w.polygon.split(&node.plane, eps),
                    }
                };
                match split {
                    Split::Front => w.link = node.front,
                    Split::Back => w.link = node.back,
                    Split::Coplanar => {
                        let same = w.polygon.plane().normal.dot(node.plane.normal) > 0.0;
                        // A cell plane carries no polygon, so either side sees the same surface.
                        let to_front = if is_face {
                            same == (rule == Coplanar::SameFront)
                        } else {
                            same
                        };
                        if is_face {
                            w.side = if to_front {
                                node.plane.normal
                            } else {
                                -node.plane.normal
                            };
                        }
                        w.link = if to_front { node.front } else { node.back };
                        w.coplanar |= is_face;
                    }
                    Split::Spanning { front, back } => {
                        *cut += (front.vertices().len() + back.vertices().len()) as u64;
                        stack.push(Work {
                            bbox: back.bbox(),
                            polygon: back,
                            link: node.back,
                            coplanar: w.coplanar,
                            side: w.side,
                        });
                        w.bbox = front.bbox();
                        w.polygon = front;
                        w.link = node.front;
                    }
                }
            }
        }
    }

    /// The label of a fragment that no surface below its node comes near: by point location
    /// in the tree, or where that ends in an unbuilt cell, for a fragment routed along a face
    /// by a ray from two tolerances off it, for any other from its centroid: by the crossings
    /// between it and the last point labelled in that cell, or in a cell seen for the first
    /// time (with the centroid clear and at most [`LOCAL_MAX`] polygons listed) a point just
    /// off one of its polygons ([`Tree::seed`]), or else the nearest of the
    /// last few labelled in any cell, or failing that by a ray.
    ///
    /// Two points of one unbuilt cell both farther than [`CLEAR`] tolerances from every plane
    /// on the way to it: the segment between them stays that far inside the cell (it is
    /// convex), where only the pieces stored in the cell reach, so only the polygons they were
    /// cut from can cross it (a piece elsewhere lies within a tolerance beyond a plane on the
    /// way). Those few are tested instead of walking the surface's hierarchy.
    fn label_whole(
        &self,
        w: &Work,
        surface: &Surface,
        labelled: &mut FxHashMap<u32, (DVec3, Label, bool)>,
        recent: &mut Recent,
    ) -> Label {
        let c = w.polygon.centroid();
        self.locate(w.link, c).unwrap_or_else(|stub| {
            if w.side != DVec3::ZERO {
                return self.label_routed(w, surface);
            }
            let clear = self.locate_clear(c, (CLEAR + 2.0) * self.eps) == Some(stub);
            let local = self.stub_polygons(stub);
            let small = clear && local.len() <= LOCAL_MAX;
            let label = match labelled.get(&stub).copied() {
                Some((q, l, true)) if small => surface.label_from_among(c, (q, l), local),
                Some((q, l, _)) => surface.label_from(c, (q, l)),
                None => small
                    .then(|| self.seed(c, stub, surface))
                    .flatten()
                    .and_then(|known| surface.label_from_among(c, known, local))
                    .or_else(|| {
                        recent
                            .nearest(c)
                            .and_then(|known| surface.label_from(c, known))
                    }),
            }
            .unwrap_or_else(|| surface.label(c));
            labelled.insert(stub, (c, label, clear));
            recent.push((c, label));
            label
        })
    }

    /// The label of a fragment routed along a face of the tree into an unbuilt cell: by a ray
    /// from two tolerances off its centroid on the side it was sent to, the point kept from the
    /// labels other fragments start from (a segment from so near the surface labelled a union of
    /// grid boxes' fragments wrongly). A face of the surface crossing that one at a small angle
    /// may lie between the fragment and that point, nearer than the tolerance: see
    /// [`Surface::crossings_off`]. Where the short segment grazes an edge of such a face, the
    /// points halfway to the fragment's corners are tried in turn (the first label kept if
    /// every one grazes).
    ///
    /// A fragment reaching an unbuilt cell lies clear of the cell's polygons, but not of faces
    /// a nearly parallel plane on the way put elsewhere: a slab's top z = −0.4375 over a bar
    /// turned 10⁻¹⁰° (the bar's top 2·10⁻¹³ below it there) and beside it was cut by no face of
    /// the bar, which lie behind the bar's top, and its centroid fell on the bar's side face,
    /// whose edge the segment grazed. The ray from beside the bar's edge read inside and the
    /// union dropped 1.2·10⁻² of the slab's top (round 20's fork input c095e8fc, once a cube's
    /// side faces followed its corners into the region above the bar's top: see `Corners` in
    /// `bsp/build/face.rs`). From a point away from the edge it reads outside.
    fn label_routed(&self, w: &Work, surface: &Surface) -> Label {
        let c = w.polygon.centroid();
        let off = |at: DVec3| at + w.side * (2.0 * self.eps);
        let halfway = w.polygon.vertices().iter().map(|&v| 0.5 * (v + c));
        for at in std::iter::once(c).chain(halfway) {
            // A ray only where the short segment settles the side: a grazing one costs none.
            if let Some(n) = surface.crossings_off(at, off(at), w.side, w.polygon.plane()) {
                let label = surface.label(off(at));
                return if n % 2 == 1 { label.flipped() } else { label };
            }
        }
        // Every short segment grazes: the centroid's ray, as it reads.
        surface.label(off(c))
    }

    /// A point of the unbuilt cell `stub` whose label is known without walking the surface's
    /// hierarchy, for labelling `c`, a clear point of the cell: just off a point of one of the
    /// cell's own polygons, where the segment across it meets no other (see
    /// [`Surface::across`]). Both of that segment's ends are in the cell, clear of the planes
    /// on the way as [`CLEAR`] asks, so the cell being convex, the segment from `c` meets only
    /// the cell's polygons. The points tried are a polygon's centroid and those halfway to its
    /// corners (a polygon reaching into the cell from outside may have some of them in it), on the
    /// first few polygons; `None` when none gives one.
    fn seed(&self, c: DVec3, stub: u32, surface: &Surface) -> Option<(DVec3, Label)> {
        let local = self.stub_polygons(stub);
        let off = (CLEAR + 3.0) * self.eps;
        // Both ends `off` from `at`: `at` clear of the planes by that much more.
        let clear = (CLEAR + 2.0) * self.eps + off;
        // The cell's polygons within it lie in its content box: a cheap test first.
        let content = self.nodes[stub as usize].content;
        let inside =
            |p: DVec3| content.contains_point(p, 0.0) && self.locate_clear(p, clear) == Some(stub);
        for &g in local.iter().take(SEED_TRIES) {
            let poly = surface.polygon(g);
            let centroid = poly.centroid();
            let halfway = poly.vertices().iter().map(|&v| 0.5 * (v + centroid));
            for at in std::iter::once(centroid).chain(halfway) {
                if !inside(at) {
                    continue;
                }
                if let Some(known) = surface.across(g, at, c, off, local) {
                    return Some(known);
                }
            }
        }
        None
    }
}

/// How many of an unbuilt cell's polygons [`Tree::seed`] tries.
const SEED_TRIES: usize = 8;

/// How far, in tolerances, two points of an unbuilt cell must be from the planes on their way
/// for the segment between them to be tested against the cell's own polygons only.
const CLEAR: f64 = 4.0;
/// Up to this many polygons in an unbuilt cell they are tested one by one; more, and the
/// surface's hierarchy is walked. A polygon of the list costs one box test when the segment's
/// box misses it, a walk thousands of instructions: 64 → 256 took rocker-arm ∪ moved's whole
/// run 1,597.2 → 1,592.3 M instructions and fandisk − moved's 946.8 → 944.2; 1,024 gave 1,592.9
/// and 944.5.
const LOCAL_MAX: usize = 256;

/// Per rayon job of a clip: the work stack; per unbuilt cell the last point labelled in it (the
/// cell is convex: a segment between two of its points meets only its few polygons), and the
/// last few labelled anywhere (fragments in a row are neighbours, so a segment from the
/// nearest of them to a cell not seen yet is still short); the corners of the pieces cut and
/// not yet charged to the clip's [`Meter`].
#[derive(Default)]
struct Scratch {
    stack: Vec<Work>,
    labelled: FxHashMap<u32, (DVec3, Label, bool)>,
    recent: Recent,
    cut: u64,
}

/// The last few points labelled in unbuilt cells, anywhere: a cell seen for the first time
/// where no seed point is found ([`Tree::seed`]) is labelled by a segment from the nearest of
/// them. A segment walks the surface's hierarchy through every box it passes, so a shorter one
/// is cheaper; far polygons carried whole leave many cells each reached once (a Menger sponge:
/// ~2,400 per boolean, ~9 k instructions a segment). Eight points: rocker-arm ∪ moved
/// 2,208.9 → 2,202.6 M instructions per whole run, Menger 1,730.2 → 1,727.1; thirty-two:
/// 2,202.5 and 1,729.5 (the search costs more).
#[derive(Default)]
struct Recent {
    points: [Option<(DVec3, Label)>; RECENT],
    next: usize,
}

/// How many points [`Recent`] keeps.
const RECENT: usize = 8;

impl Recent {
    fn push(&mut self, known: (DVec3, Label)) {
        self.points[self.next] = Some(known);
        self.next = (self.next + 1) % RECENT;
    }

    fn nearest(&self, p: DVec3) -> Option<(DVec3, Label)> {
        self.points
            .iter()
            .flatten()
            .min_by(|a, b| a.0.distance_squared(p).total_cmp(&b.0.distance_squared(p)))
            .copied()
    }
}

/// [`Polygon::split`]'s answer by a cell's axis-aligned plane for a fragment whose box lies
/// wholly farther than `eps` to one side of it, from the box alone: whether it lies in front.
/// The plane's distance is then `v[axis] - anchor[axis]` exactly (the normal's other components
/// are zero) and the box's extreme is the extreme vertex, so this is `split`'s own test, bit
/// for bit, without its loop over the vertices. `None` where the box does not settle it. (A
/// `bool`, not a [`Split`]: a `Split` is two polygons wide, and returned from a call that the
/// compiler does not inline, it is copied: +3.7 M instructions per rocker-arm run in round 32.)
fn cell_side(w: &Work, plane: &crate::geom::Plane, eps: f64) -> Option<bool> {
    let axis = plane.normal.abs().max_position();
    let at = plane.anchor[axis];
    if w.polygon.plane().is_same_or_flipped(plane) {
        return None;
    }
    if w.bbox.min[axis] - at > eps {
        Some(true)
    } else if w.bbox.max[axis] - at < -eps {
        Some(false)
    } else {
        None
    }
}

/// True when a box reaches more than `eps` to both sides of an axis-aligned plane.
fn spans_axis_plane(bbox: &Aabb, plane: &crate::geom::Plane, eps: f64) -> bool {
    let axis = plane.normal.abs().max_position();
    let at = plane.anchor[axis];
    bbox.min[axis] < at - eps && bbox.max[axis] > at + eps
}
