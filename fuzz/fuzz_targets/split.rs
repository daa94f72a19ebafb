//! Polygon splitting: a convex polygon (a regular n-gon placed by the input) cut by a plane
//! the input chooses, often nearly through a vertex or nearly parallel.
//!
//! Checks: no panic; each piece keeps three or more finite vertices, its parent's plane and
//! source; the front piece lies in front (within the tolerance) and the back piece behind;
//! the pieces' areas add up to the polygon's.
#![no_main]

use bspcsg::glam::{DQuat, DVec3};
use bspcsg::{Plane, Polygon, Split};
use libfuzzer_sys::fuzz_target;

fn unit(bytes: &[u8], at: usize) -> f64 {
    let b = bytes.get(at..at + 2).unwrap_or(&[0, 0]);
    u16::from_le_bytes([b[0], b[1]]) as f64 / 65535.0
}

fuzz_target!(|data: &[u8]| {
    if data.len() < 24 {
        return;
    }
    let sides = 3 + (data[0] % 14) as usize;
    let scale = 10f64.powi((data[1] % 13) as i32 - 6);
    let far = 10f64.powi((data[2] % 7) as i32) * (unit(data, 3) - 0.5);
    let q = DQuat::from_euler(
        bspcsg::glam::EulerRot::XYZ,
        unit(data, 5) * 6.3,
        unit(data, 7) * 6.3,
        unit(data, 9) * 6.3,
    );
    let centre = DVec3::new(far, far * 0.5, -far);
    let ring: Vec<DVec3> = (0..sides)
        .map(|k| {
            let a = std::f64::consts::TAU * k as f64 / sides as f64;
            centre + q * DVec3::new(a.cos(), a.sin(), 0.0) * scale
        })
        .collect();
    let Some(polygon) = Polygon::new(ring.as_slice(), 7) else {
        return;
    };
    // The cutting plane passes near a vertex, tilted by an input-chosen (possibly tiny) angle.
    let through = ring[data[11] as usize % sides]
        + q * DVec3::new(unit(data, 12) - 0.5, 0.0, 0.0)
            * scale
            * 10f64.powi(-((data[14] % 12) as i32));
    let tilt = 10f64.powi(-((data[15] % 15) as i32));
    let normal = q * DVec3::new(unit(data, 16) - 0.5, unit(data, 18) - 0.5, tilt);
    let Some(plane) = Plane::from_point_normal(through, normal) else {
        return;
    };
    let eps = 1e-12 * scale.max(far.abs());
    match polygon.split(&plane, eps) {
        Split::Front | Split::Back | Split::Coplanar => {}
        Split::Spanning { front, back } => {
            for (piece, sign) in [(&front, 1.0), (&back, -1.0)] {
                assert!(piece.vertices().len() >= 3, "{piece:?}");
                assert!(piece.vertices().iter().all(|v| v.is_finite()));
                assert_eq!(piece.plane(), polygon.plane());
                assert_eq!(piece.source(), 7);
                for v in piece.vertices() {
                    let d = plane.distance(*v) * sign;
                    assert!(d >= -eps * 4.0, "a vertex on the wrong side by {d}");
                }
            }
            // The pieces cover the polygon, and overlap at most where vertices within `eps` of
            // the plane went to both: inside the band |distance| ≤ eps. Coordinates `far` from
            // the origin carry absolute error ~ulp(far): `far / scale` ulps of the polygon.
            let (a, f, b) = (polygon.area(), front.area(), back.area());
            let rel = 1e-9 + 64.0 * f64::EPSILON * (far.abs() / scale);
            let band = band_area(polygon.vertices(), &plane, eps);
            assert!(f + b >= a * (1.0 - rel), "areas {f} + {b} < {a}: a gap");
            assert!(
                f + b <= a * (1.0 + rel) + band,
                "areas {f} + {b} > {a} + band {band}"
            );
        }
    }
});

/// The area of the polygon's part within `eps` of the plane, by exact clipping.
fn band_area(ring: &[DVec3], plane: &Plane, eps: f64) -> f64 {
    let clip = |ring: Vec<DVec3>, keep: &dyn Fn(f64) -> f64| {
        let mut out = Vec::new();
        for i in 0..ring.len() {
            let (p, q) = (ring[i], ring[(i + 1) % ring.len()]);
            let (dp, dq) = (keep(plane.distance(p)), keep(plane.distance(q)));
            if dp >= 0.0 {
                out.push(p);
            }
            if (dp > 0.0 && dq < 0.0) || (dp < 0.0 && dq > 0.0) {
                out.push(p + (q - p) * (dp / (dp - dq)));
            }
        }
        out
    };
    let below = clip(ring.to_vec(), &|d| eps - d);
    let band = clip(below, &|d| d + eps);
    if band.len() < 3 {
        return 0.0;
    }
    let mut twice = DVec3::ZERO;
    for k in 1..band.len() - 1 {
        twice += (band[k] - band[0]).cross(band[k + 1] - band[0]);
    }
    0.5 * twice.length()
}
