//! Triangulation of simple planar polygons by ear clipping.

use glam::{DVec2, DVec3};

/// Projects points of a plane with `normal` to 2D, dropping the normal's dominant axis and
/// keeping the winding (counter-clockwise seen from the front stays counter-clockwise).
pub(crate) fn project(points: &[DVec3], normal: DVec3) -> Vec<DVec2> {
    let a = normal.abs();
    let (u, v, sign) = if a.x >= a.y && a.x >= a.z {
        (1, 2, normal.x)
    } else if a.y >= a.z {
        (2, 0, normal.y)
    } else {
        (0, 1, normal.z)
    };
    points
        .iter()
        .map(|p| {
            if sign >= 0.0 {
                DVec2::new(p[u], p[v])
            } else {
                DVec2::new(p[v], p[u])
            }
        })
        .collect()
}

fn cross(o: DVec2, a: DVec2, b: DVec2) -> f64 {
    (a - o).perp_dot(b - o)
}

/// Triangulates a simple polygon given counter-clockwise in 2D, returning index triples.
/// Ears are clipped best-first (the fattest ear), which avoids needle triangles where a choice
/// exists. `None` when the polygon is not simple enough to clip (self-intersecting).
pub(crate) fn ear_clip(points: &[DVec2]) -> Option<Vec<[usize; 3]>> {
    let n = points.len();
    if n < 3 {
        return None;
    }
    let mut ring: Vec<usize> = (0..n).collect();
    let mut out = Vec::with_capacity(n - 2);
    while ring.len() > 3 {
        let m = ring.len();
        let mut best: Option<(f64, usize)> = None;
        for k in 0..m {
            let (ip, i, inx) = (ring[(k + m - 1) % m], ring[k], ring[(k + 1) % m]);
            let (p, c, q) = (points[ip], points[i], points[inx]);
            let area2 = cross(p, c, q);
            if area2 <= 0.0 {
                continue;
            }
            let blocked = ring.iter().any(|&j| {
                j != ip
                    && j != i
                    && j != inx
                    && points[j] != p
                    && points[j] != c
                    && points[j] != q
                    && cross(p, c, points[j]) >= 0.0
                    && cross(c, q, points[j]) >= 0.0
                    && cross(q, p, points[j]) >= 0.0
            });
            if blocked {
                continue;
            }
            // Quality: twice the area over the squared longest edge (1 for the fattest shapes).
            let longest = (c - p)
                .length_squared()
                .max((q - c).length_squared())
                .max((p - q).length_squared());
            let quality = area2 / longest;
            if best.is_none_or(|(b, _)| quality > b) {
                best = Some((quality, k));
            }
        }
        let (_, k) = best?;
        let m = ring.len();
        out.push([ring[(k + m - 1) % m], ring[k], ring[(k + 1) % m]]);
        ring.remove(k);
    }
    out.push([ring[0], ring[1], ring[2]]);
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn l_shape() {
        let pts = [
            DVec2::new(0.0, 0.0),
            DVec2::new(2.0, 0.0),
            DVec2::new(2.0, 1.0),
            DVec2::new(1.0, 1.0),
            DVec2::new(1.0, 2.0),
            DVec2::new(0.0, 2.0),
        ];
        let tris = ear_clip(&pts).unwrap();
        assert_eq!(tris.len(), 4);
        let area: f64 = tris
            .iter()
            .map(|t| 0.5 * cross(pts[t[0]], pts[t[1]], pts[t[2]]))
            .sum();
        assert!((area - 3.0).abs() < 1e-12);
    }
}
