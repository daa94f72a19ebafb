//! Removing needles from a closed triangle mesh by edge flips and edge collapses.
//!
//! A *needle* is a triangle whose area is below [`NEEDLE_AREA`] × d², d the diagonal of its
//! shell's bounding box (see [`crate::geom::NEEDLE_AREA`] for why that threshold). Booleans
//! make them where a vertex lies within the tolerance of a neighbour's edge (two planes meeting
//! at a tiny angle, a weld cluster), and marching cubes where the surface passes within a hair
//! of a grid vertex. Both are valid topology but useless geometry, and slicers, FEM meshers and
//! manifold3d treat them as defects.
//!
//! Local operations remove them, each moving the surface by at most [`SPECK_MOVE`] × d:
//!
//! * **Flip** the needle's longest edge `ab` (apex `v`, neighbour `bac`) to `vc`. The new
//!   triangles lie in the tetrahedron `abcv`, whose every point is within the apex height of
//!   `abc`: the surface moves by at most that height. Taken when `v` is far from both ends of
//!   `ab` (a *cap*).
//! * **Collapse** the needle's shortest edge `pq`, moving `p` onto `q` and deleting the two
//!   triangles beside it; where that would change the volume, `q` moves off its place along
//!   the fan's normal by what puts it back (a collapse keeps the volume). The surface moves by
//!   about `|pq|`. Taken when the needle has a short edge (a *spike* or a speck).
//! * **Stretch** a spike no flip or collapse can take (the tip of a thin wedge): one end of its
//!   short edge moves away from the other along it, about the needle's height, until the
//!   area is half again the threshold ([`Work::plan_stretch`]).
//!
//! None is taken where it would change topology or fold the surface: a flip needs the new
//! edge not to exist already; a collapse needs the link condition (the two ends share exactly
//! the two opposite vertices as neighbours) and a shell of more than four triangles; both need
//! every new triangle to keep its orientation and have more than zero area. A needle that no
//! operation can remove stays (the report still counts it).

use glam::DVec3;
use smallvec::SmallVec;

use super::Mesh;
use crate::disjoint_sets::DisjointSets;
use crate::geom::{Aabb, MAX_MOVE, NEEDLE_AREA, Tolerance, is_zero_area};

/// The farthest, as a fraction of the shell's diagonal `d`, that removing one needle may move
/// the surface. Collapsing a speck's shortest edge moves a vertex by up to that edge's length,
/// and a triangle under `NEEDLE_AREA × d²` may have a shortest edge up to
/// `√(4/√3 · NEEDLE_AREA) d ≈ 1.52·10⁻⁶ d` (an equilateral speck). [`MAX_MOVE`] alone
/// (`√NEEDLE_AREA`) left a speck about 1.2·10⁻⁶ d on a side where a turned bar's face passes a
/// hair from a box's corner, each way of removing it moving the surface 1.06·10⁻⁶ d. Twice
/// `MAX_MOVE` covers every speck's shortest edge, with room for the volume-keeping offset.
const SPECK_MOVE: f64 = 2.0 * MAX_MOVE;

/// Removes the needles it can from `mesh`, keeping it closed and oriented. Returns how many
/// needles (by the thresholds used here) remain; 0 also where the mesh is left alone: triangles
/// that use an index out of range or a non-finite position (not a mesh this pass can reason
/// about).
///
/// `scale`, where given, caps the diagonal the thresholds are taken from: a boolean passes 16
/// times the size of the region where its operands met, so a part joined to a box 10³⁸ across
/// keeps its triangles (by the box's diagonal, every one of them would be a needle).
pub(crate) fn remove_needles(mesh: &mut Mesh, scale: Option<f64>) -> usize {
    let n = mesh.positions.len();
    if mesh
        .triangles
        .iter()
        .flatten()
        .any(|&i| i as usize >= n || !mesh.positions[i as usize].is_finite())
    {
        return 0;
    }
    // Most meshes hold no needle. No shell's diagonal exceeds the whole mesh's, so one pass by
    // the mesh's threshold proves that before the shells and the edge map are built.
    let scale = scale.unwrap_or(f64::INFINITY);
    let mut bbox = Aabb::EMPTY;
    for &p in &mesh.positions {
        bbox.grow(p);
    }
    let largest_threshold = NEEDLE_AREA * bbox.diagonal().min(scale).powi(2);
    // Twice the area, squared, against twice the threshold, squared: no square root per
    // triangle (this check is all the pass does on most meshes). Relaxed by a hair so rounding
    // never skips a triangle the exact test below takes.
    let bar = (2.0 * largest_threshold).powi(2) * (1.0 + 1e-9);
    let corners = |t: &[u32; 3]| t.map(|i| mesh.positions[i as usize]);
    if !mesh
        .triangles
        .iter()
        .any(|t| twice_normal(corners(t)).length_squared() < bar)
    {
        return 0;
    }
    let mut work = Work::new(std::mem::take(mesh), scale);
    let mut queue: Vec<u32> = (0..work.tris.len() as u32)
        .filter(|&t| work.is_needle(t))
        .collect();
    if queue.is_empty() {
        *mesh = Mesh {
            positions: work.positions,
            triangles: work.tris,
            sources: work.sources,
        };
        return 0;
    }
    // Each operation removes a needle or makes one's smallest area larger; the budget only
    // guards against cycling between equally bad choices.
    let mut budget = 16 * queue.len() + 64;
    while let Some(t) = queue.pop() {
        if budget == 0 {
            break;
        }
        budget -= 1;
        if !work.alive[t as usize] || !work.is_needle(t) {
            continue;
        }
        if let Some(touched) = work.fix(t) {
            queue.extend(touched.into_iter().filter(|&u| work.is_needle(u)));
        }
    }
    work.finish(mesh)
}

/// The mesh being edited: triangles with liveness, triangles per vertex and the scale of each
/// vertex's shell.
///
/// A directed edge is found among the few triangles around its start ([`Work::with_edge`]),
/// not in a map of all edges: one needle in a sphere of 10⁶ triangles made the pass hash every
/// edge (166 ms of 860 in `to_mesh`), for a handful of lookups.
struct Work {
    positions: Vec<DVec3>,
    tris: Vec<[u32; 3]>,
    sources: Vec<u32>,
    alive: Vec<bool>,
    /// Live triangles around each vertex.
    around: Vec<SmallVec<[u32; 8]>>,
    /// Per vertex: its shell's index.
    shell: Vec<u32>,
    /// Per shell: needle area, largest move, live triangle count.
    needle_area: Vec<f64>,
    max_move: Vec<f64>,
    /// The plane tolerance of booleans at the shell's scale: moves this small are always fine.
    tolerance: Vec<f64>,
    shell_tris: Vec<usize>,
}

impl Work {
    fn new(mesh: Mesh, scale: f64) -> Self {
        let n = mesh.positions.len();
        let mut sets = DisjointSets::new(n);
        for t in &mesh.triangles {
            sets.union(t[0] as usize, t[1] as usize);
            sets.union(t[0] as usize, t[2] as usize);
        }
        let mut shell = vec![u32::MAX; n];
        let mut boxes: Vec<Aabb> = Vec::new();
        let mut shell_tris: Vec<usize> = Vec::new();
        for t in &mesh.triangles {
            let root = sets.find(t[0] as usize);
            if shell[root] == u32::MAX {
                shell[root] = boxes.len() as u32;
                boxes.push(Aabb::EMPTY);
                shell_tris.push(0);
            }
            let s = shell[root] as usize;
            shell_tris[s] += 1;
            for &v in t {
                boxes[s].grow(mesh.positions[v as usize]);
            }
        }
        for v in 0..n {
            shell[v] = shell[sets.find(v)];
        }
        let diag: Vec<f64> = boxes.iter().map(|b| b.diagonal().min(scale)).collect();
        let mut around: Vec<SmallVec<[u32; 8]>> = vec![SmallVec::new(); n];
        for (t, tri) in mesh.triangles.iter().enumerate() {
            for &v in tri {
                around[v as usize].push(t as u32);
            }
        }
        Work {
            alive: vec![true; mesh.triangles.len()],
            positions: mesh.positions,
            tris: mesh.triangles,
            sources: mesh.sources,
            around,
            shell,
            needle_area: diag.iter().map(|d| NEEDLE_AREA * d * d).collect(),
            max_move: diag.iter().map(|d| SPECK_MOVE * d).collect(),
            tolerance: diag.iter().map(|d| Tolerance::RELATIVE * d).collect(),
            shell_tris,
        }
    }

    /// The live triangle with directed edge `a`→`b`, if any.
    fn with_edge(&self, a: u32, b: u32) -> Option<u32> {
        self.around[a as usize].iter().copied().find(|&t| {
            let tri = self.tris[t as usize];
            (0..3).any(|k| tri[k] == a && tri[(k + 1) % 3] == b)
        })
    }

    fn corners(&self, tri: [u32; 3]) -> [DVec3; 3] {
        tri.map(|i| self.positions[i as usize])
    }

    fn threshold(&self, tri: [u32; 3]) -> f64 {
        self.needle_area[self.shell[tri[0] as usize] as usize]
    }

    fn is_needle(&self, t: u32) -> bool {
        let tri = self.tris[t as usize];
        self.alive[t as usize] && area(self.corners(tri)) < self.threshold(tri)
    }

    /// A triangle that may replace another facing `normal`: not flat, not folded over.
    fn acceptable(&self, tri: [u32; 3], normal: DVec3) -> bool {
        let c = self.corners(tri);
        !is_zero_area(c) && twice_normal(c).dot(normal) > 0.0
    }

    /// One operation on needle `t`, of those that apply the one that moves the surface least;
    /// the triangles it changed, or `None` when none applies.
    fn fix(&mut self, t: u32) -> Option<Vec<u32>> {
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

    /// Flipping edge `k` of triangle `t` (from corner `k` to `k + 1`): the move (the apex's
    /// distance from the neighbour's plane) and the operation, if the flip is valid and helps.
    fn plan_flip(&self, t: u32, k: usize) -> Option<Plan> {
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
        // Only a change that helps: the smaller of the two areas grows.
        let before = area(self.corners(tri)).min(area(self.corners(other)));
        let after = area(self.corners(new_t)).min(area(self.corners(new_u)));
        if after <= before {
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

    fn apply_flip(&mut self, t: u32, u: u32, new_t: [u32; 3], new_u: [u32; 3]) -> Vec<u32> {
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

    /// Collapsing edge `from`–`to` of triangle `t` by moving `from` onto `to`: the move and the
    /// operation, if the topology allows it and every triangle around both ends stays
    /// acceptable.
    ///
    /// The merged vertex keeps the volume: where moving `from` onto `to` would add or cut
    /// some (the fan around `from` is not flat), it goes to the point off `to` along the merged
    /// fan's area-weighted normal that puts it back. Specks fanned over a face where a sphere
    /// grazes a box's corner cut volume at each collapse, all of one sign, whichever end was
    /// kept (6.8·10⁻⁹ over eleven collapses); the offsets are at most 6·10⁻⁸ there. Where the fan around
    /// `from` is flat, nothing moves off it.
    ///
    /// The move is measured both ways: how far the merged vertex lies from the plane of each
    /// triangle around either end as it was, and each old end from each triangle as it
    /// becomes. Sliding a vertex along a flat region or a straight crease moves nothing,
    /// however long the edge.
    fn plan_collapse(&self, t: u32, from: u32, to: u32) -> Option<Plan> {
        if self.shell_tris[self.shell[from as usize] as usize] <= 4 {
            return None;
        }
        let t2 = self
            .with_edge(to, from)
            .or_else(|| self.with_edge(from, to).filter(|&u| u != t))?;
        let t1 = self
            .with_edge(from, to)
            .or_else(|| self.with_edge(to, from))?;
        let (t1, t2) = if t1 == t2 { (t, t2) } else { (t1, t2) };
        if t1 == t2 {
            return None;
        }
        let opposite = |u: u32| {
            self.tris[u as usize]
                .iter()
                .copied()
                .find(|&w| w != from && w != to)
        };
        let (o1, o2) = (opposite(t1)?, opposite(t2)?);
        if o1 == o2 || !self.link_condition(from, to, o1, o2) {
            return None;
        }
        let (source, target) = (self.positions[from as usize], self.positions[to as usize]);
        // The volume is linear in a vertex's position: moving `from` by `m` changes it by
        // (area-weighted normal of its fan) · m / 6, `t1` and `t2` flattening to nothing.
        let fan = |v: u32| {
            self.around[v as usize]
                .iter()
                .copied()
                .filter(move |&u| u != t1 && u != t2)
        };
        let moved = |old: [u32; 3]| old.map(|w| if w == from { to } else { w });
        let mut change = 0.0;
        for &u in &self.around[from as usize] {
            change += twice_normal(self.corners(self.tris[u as usize])).dot(target - source) / 6.0;
        }
        let mut gradient = DVec3::ZERO;
        for u in fan(from).chain(fan(to)) {
            gradient += twice_normal(self.corners(moved(self.tris[u as usize])));
        }
        let at = match (6.0 * change / gradient.length_squared()) * gradient {
            fix if fix.is_finite() && change != 0.0 => target - fix,
            _ => target,
        };
        let corners = |tri: [u32; 3]| {
            tri.map(|w| {
                if w == to {
                    at
                } else {
                    self.positions[w as usize]
                }
            })
        };
        let mut dev: f64 = 0.0;
        let mut swept = 0.0;
        for (u, end) in fan(from)
            .map(|u| (u, source))
            .chain(fan(to).map(|u| (u, target)))
        {
            let old = self.tris[u as usize];
            let new = moved(old);
            let (before, after) = (self.corners(old), corners(new));
            // A needle's own plane is noise: then only flatness is checked.
            let needle = area(before) < self.threshold(old);
            let reference = if needle {
                twice_normal(after)
            } else {
                twice_normal(before)
            };
            if is_zero_area(after) || twice_normal(after).dot(reference) <= 0.0 {
                return None;
            }
            swept += (twice_normal(before).dot(at - end) / 6.0).abs();
            if !needle {
                dev = dev
                    .max(plane_distance(before, at))
                    .max(plane_distance(after, end));
            }
        }
        Some(Plan {
            dev,
            swept,
            op: Op::Collapse {
                from,
                to,
                at,
                t1,
                t2,
            },
        })
    }

    /// Moving `from`, an end of needle `t`'s short edge, away from its other end `to` along
    /// that edge, until the needle's area is half again the threshold. Where a thin wedge ends
    /// in a face narrower than the bound (a prism's cap turned 0.001° passing 3.9e-10 from a
    /// cube's corner: an end face 3.9e-10 × 4.4e-5), no flip applies and every collapse folds
    /// the wedge's tip into a sheet of no thickness, whose removal would cut 4.4e-5 off the
    /// wedge; this moves one vertex by about the needle's height and keeps the wedge. Checked
    /// as a collapse is: every triangle around `from` keeps its orientation and area.
    fn plan_stretch(&self, t: u32, from: u32, to: u32) -> Option<Plan> {
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

    /// The ends of edge `pq` share exactly the neighbours `o1` and `o2`.
    fn link_condition(&self, p: u32, q: u32, o1: u32, o2: u32) -> bool {
        let neighbours = |v: u32| -> SmallVec<[u32; 16]> {
            let mut out: SmallVec<[u32; 16]> = SmallVec::new();
            for &t in &self.around[v as usize] {
                for &w in &self.tris[t as usize] {
                    if w != v && !out.contains(&w) {
                        out.push(w);
                    }
                }
            }
            out
        };
        let (np, nq) = (neighbours(p), neighbours(q));
        let shared = np.iter().filter(|w| nq.contains(w)).count();
        shared == 2 && np.contains(&o1) && np.contains(&o2) && nq.contains(&o1) && nq.contains(&o2)
    }

    /// Moves vertex `from` onto `to`, and that to `at`, deleting `t1` and `t2` (the triangles
    /// on edge from–to).
    fn apply_collapse(&mut self, from: u32, to: u32, at: DVec3, t1: u32, t2: u32) -> Vec<u32> {
        self.positions[to as usize] = at;
        let fan: SmallVec<[u32; 8]> = self.around[from as usize]
            .iter()
            .copied()
            .filter(|&u| u != t1 && u != t2)
            .collect();
        self.unlink(t1);
        self.unlink(t2);
        self.alive[t1 as usize] = false;
        self.alive[t2 as usize] = false;
        self.shell_tris[self.shell[from as usize] as usize] -= 2;
        for &u in &fan {
            self.unlink(u);
        }
        for &u in &fan {
            for w in self.tris[u as usize].iter_mut() {
                if *w == from {
                    *w = to;
                }
            }
            self.link(u);
        }
        let mut changed: Vec<u32> = self.around[to as usize].to_vec();
        changed.extend(fan);
        changed
    }

    fn unlink(&mut self, t: u32) {
        let tri = self.tris[t as usize];
        for v in tri {
            self.around[v as usize].retain(|u| *u != t);
        }
    }

    fn link(&mut self, t: u32) {
        let tri = self.tris[t as usize];
        for v in tri {
            self.around[v as usize].push(t);
        }
    }

    /// Writes the live triangles and the positions they use back; returns the needles left.
    fn finish(self, mesh: &mut Mesh) -> usize {
        let left = (0..self.tris.len() as u32)
            .filter(|&t| self.is_needle(t))
            .count();
        let mut index = vec![u32::MAX; self.positions.len()];
        let mut positions = Vec::with_capacity(self.positions.len());
        let mut triangles = Vec::with_capacity(self.tris.len());
        let mut sources = Vec::with_capacity(self.tris.len());
        for (t, tri) in self.tris.iter().enumerate() {
            if !self.alive[t] {
                continue;
            }
            triangles.push(tri.map(|v| {
                if index[v as usize] == u32::MAX {
                    index[v as usize] = positions.len() as u32;
                    positions.push(self.positions[v as usize]);
                }
                index[v as usize]
            }));
            sources.push(self.sources[t]);
        }
        *mesh = Mesh {
            positions,
            triangles,
            sources,
        };
        left
    }
}

/// A planned change: how far it moves the surface, the volume it sweeps, what it does.
struct Plan {
    dev: f64,
    swept: f64,
    op: Op,
}

/// A change to the mesh.
enum Op {
    Flip {
        t: u32,
        u: u32,
        new_t: [u32; 3],
        new_u: [u32; 3],
    },
    /// `from` onto `to`, which moves to `at`.
    Collapse {
        from: u32,
        to: u32,
        at: DVec3,
        t1: u32,
        t2: u32,
    },
    /// Vertex `v` to `at`.
    Move { v: u32, at: DVec3 },
}

/// The distance of `p` from the plane of triangle `c` (its distance from `c[0]` if `c` is flat).
fn plane_distance(c: [DVec3; 3], p: DVec3) -> f64 {
    match twice_normal(c).try_normalize() {
        Some(n) => n.dot(p - c[0]).abs(),
        None => p.distance(c[0]),
    }
}

fn twice_normal([a, b, c]: [DVec3; 3]) -> DVec3 {
    (b - a).cross(c - a)
}

fn area(c: [DVec3; 3]) -> f64 {
    0.5 * twice_normal(c).length()
}
