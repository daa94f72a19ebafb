//! The exact decision for one candidate pair: do two triangles cross (Shewchuk's adaptive
//! `orient3d` and `orient2d`, so rounding never invents or hides a crossing).

use glam::DVec3;

/// The sign of the exact orientation of `d` against the plane through `a`, `b`, `c`.
#[inline]
pub(super) fn orient([a, b, c]: [DVec3; 3], d: DVec3) -> f64 {
    // Four points with one coordinate equal lie in a plane across that axis: exactly zero.
    // Coplanar points take `orient3d` through its adaptive stages (about 1,200 instructions a
    // call), and axis-aligned faces (a Menger sponge's) give most of them.
    let same = |k: usize| a[k] == b[k] && a[k] == c[k] && a[k] == d[k];
    if same(0) || same(1) || same(2) {
        return 0.0;
    }
    let p = |v: DVec3| robust::Coord3D {
        x: v.x,
        y: v.y,
        z: v.z,
    };
    robust::orient3d(p(a), p(b), p(c), p(d))
}

/// True when segment `pq`, whose ends lie on the sides `sp`, `sq` of triangle `abc`'s plane
/// (signs of [`orient`]), passes strictly through the triangle's interior.
fn pierces([p, q]: [DVec3; 2], [sp, sq]: [f64; 2], [a, b, c]: [DVec3; 3]) -> bool {
    if !(sp > 0.0 && sq < 0.0 || sp < 0.0 && sq > 0.0) {
        return false;
    }
    let (s1, s2, s3) = (
        orient([p, q, a], b),
        orient([p, q, b], c),
        orient([p, q, c], a),
    );
    s1 > 0.0 && s2 > 0.0 && s3 > 0.0 || s1 < 0.0 && s2 < 0.0 && s3 < 0.0
}

/// True when triangles `t` and `u` (vertex indices `ti`, `ui`; corners `tc`, `uc`) cross: an
/// edge of either passes strictly through the other, or they lie in one plane, face the same
/// way and their interiors overlap. Triangles sharing one corner `v` meet on the line where
/// their planes cross, from `v`; if both run along it into their interiors, the one that stops
/// first stops on its far edge inside the other: that edge passes through it.
#[inline]
pub(super) fn cross(ti: [u32; 3], ui: [u32; 3], tc: [DVec3; 3], uc: [DVec3; 3]) -> bool {
    if ui.iter().filter(|i| ti.contains(i)).count() >= 2 {
        // Neighbours across an edge: their planes meet in that edge unless they are one plane.
        // Shared corners lie on both planes by construction, so only the other corners decide
        // whether the two are coplanar (rarely: then the 2D test). Triangles sharing one
        // corner take the general test below, where that corner's signs are exactly zero.
        let off_plane = |own: [u32; 3], c: [DVec3; 3], other: [u32; 3], plane: [DVec3; 3]| {
            (0..3).any(|k| !other.contains(&own[k]) && orient(plane, c[k]) != 0.0)
        };
        return !off_plane(ui, uc, ti, tc)
            && !off_plane(ti, tc, ui, uc)
            && coplanar_overlap(tc, uc);
    }
    let st = tc.map(|p| orient(uc, p));
    let su = uc.map(|p| orient(tc, p));
    if st.iter().chain(&su).all(|&s| s == 0.0) {
        return coplanar_overlap(tc, uc);
    }
    let edges = |v: [DVec3; 3], s: [f64; 3]| {
        [(0, 1), (1, 2), (2, 0)].map(|(i, j)| ([v[i], v[j]], [s[i], s[j]]))
    };
    edges(tc, st).into_iter().any(|(e, s)| pierces(e, s, uc))
        || edges(uc, su).into_iter().any(|(e, s)| pierces(e, s, tc))
}

/// For two triangles in one plane: true when they face the same way and their interiors
/// overlap. Exact: both are projected by dropping the coordinate along which the plane's
/// normal is largest (which only forgets a coordinate, and keeps the plane one-to-one with its
/// image), then decided by `orient2d`. Two convex polygons' interiors are disjoint exactly
/// when the line through some edge of one has the other wholly on its closed outer side; this
/// also settles the cases a test of crossing edges and strictly inner corners misses (one
/// triangle inside the other with every corner on its boundary, or the same triangle twice).
pub(super) fn coplanar_overlap(t: [DVec3; 3], u: [DVec3; 3]) -> bool {
    let normal = |v: [DVec3; 3]| (v[1] - v[0]).cross(v[2] - v[0]).abs();
    let n = normal(t) + normal(u);
    let (i, j) = if n.x >= n.y && n.x >= n.z {
        (1, 2)
    } else if n.y >= n.z {
        (2, 0)
    } else {
        (0, 1)
    };
    let flat = |v: [DVec3; 3]| v.map(|p| robust::Coord { x: p[i], y: p[j] });
    let (t, u) = (flat(t), flat(u));
    let turn = |v: [robust::Coord<f64>; 3]| robust::orient2d(v[0], v[1], v[2]);
    let (ot, ou) = (turn(t), turn(u));
    // A triangle of no area has no interior; opposite turns are opposite facings (touching).
    if ot == 0.0 || ou == 0.0 || (ot > 0.0) != (ou > 0.0) {
        return false;
    }
    // Both turn the same way, so one sign says which side of an edge is inside, for either.
    let inner = |o: f64| if ot > 0.0 { o > 0.0 } else { o < 0.0 };
    let separates = |v: [robust::Coord<f64>; 3], w: [robust::Coord<f64>; 3]| {
        (0..3).any(|k| {
            let (a, b) = (v[k], v[(k + 1) % 3]);
            !w.iter().any(|&p| inner(robust::orient2d(a, b, p)))
        })
    };
    !separates(t, u) && !separates(u, t)
}
