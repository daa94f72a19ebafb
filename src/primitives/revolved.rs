//! Round primitives, all made by revolving a profile in the (radius, y) half-plane about Y.

use std::f64::consts::TAU;

use glam::DVec3;

use super::{budget, count, face, positive};
use crate::error::{Error, Result};
use crate::polygon::Polygon;

/// The faces of a UV sphere: `segments` around the Y axis, `rings` from pole to pole.
pub(crate) fn sphere(radius: f64, segments: u32, rings: u32) -> Result<Vec<Polygon>> {
    positive("radius", radius)?;
    count("segments", segments, 3)?;
    count("rings", rings, 2)?;
    budget(segments, rings)?;
    let profile: Vec<(f64, f64)> = (0..=rings)
        .map(|i| {
            if i == 0 {
                (0.0, radius)
            } else if i == rings {
                (0.0, -radius)
            } else {
                let t = std::f64::consts::PI * i as f64 / rings as f64;
                (radius * t.sin(), radius * t.cos())
            }
        })
        .collect();
    revolve(&profile, segments, false)
}

/// The faces of a frustum along Y (one radius may be zero: a cone); caps are single polygons.
pub(crate) fn frustum(
    r_bottom: f64,
    r_top: f64,
    height: f64,
    segments: u32,
) -> Result<Vec<Polygon>> {
    positive("height", height)?;
    let h = height * 0.5;
    frustum_between(r_bottom, r_top, -h, h, segments)
}

/// The faces of a frustum along Y from `y0` (radius `r_bottom`) to `y1` (radius `r_top`), its
/// caps at `y0` and `y1` bit for bit (a frustum sized and then moved can shift a cap by a
/// rounding).
pub(crate) fn frustum_between(
    r_bottom: f64,
    r_top: f64,
    y0: f64,
    y1: f64,
    segments: u32,
) -> Result<Vec<Polygon>> {
    for (name, r) in [("r_bottom", r_bottom), ("r_top", r_top)] {
        if !(r.is_finite() && r >= 0.0) {
            return Err(Error::param(name, r, "must be finite and ≥ 0"));
        }
    }
    if r_bottom == 0.0 && r_top == 0.0 {
        return Err(Error::param("r_bottom", 0.0, "and r_top cannot both be 0"));
    }
    positive("height", y1 - y0)?;
    count("segments", segments, 3)?;
    // The cap centres on the axis close the profile; revolve() turns them into flat caps.
    let profile = [(0.0, y1), (r_top, y1), (r_bottom, y0), (0.0, y0)];
    let profile: Vec<(f64, f64)> = dedup_axis_points(&profile);
    revolve(&profile, segments, false)
}

/// The faces of a torus about the Y axis.
pub(crate) fn torus(major: f64, minor: f64, segments: u32, rings: u32) -> Result<Vec<Polygon>> {
    positive("major", major)?;
    positive("minor", minor)?;
    if minor >= major {
        return Err(Error::param("minor", minor, "must be smaller than major"));
    }
    count("segments", segments, 3)?;
    count("rings", rings, 3)?;
    budget(segments, rings)?;
    // Round the tube downward on its outer side, so faces point out of the tube.
    let profile: Vec<(f64, f64)> = (0..rings)
        .map(|k| {
            let v = -TAU * k as f64 / rings as f64;
            (major + minor * v.cos(), minor * v.sin())
        })
        .collect();
    revolve(&profile, segments, true)
}

/// A cone's profile has its apex on the axis twice over (cap centre and apex); keep one.
fn dedup_axis_points(profile: &[(f64, f64)]) -> Vec<(f64, f64)> {
    let mut out: Vec<(f64, f64)> = Vec::with_capacity(profile.len());
    for &(r, y) in profile {
        if let Some(&(pr, py)) = out.last()
            && pr == 0.0
            && r == 0.0
            && py == y
        {
            continue;
        }
        out.push((r, y));
    }
    out
}

/// Revolves a profile of (radius, y) points about Y with `segments` steps.
///
/// An open profile runs from the axis, down the outside, back to the axis. Where two
/// consecutive profile points both have the same `y` and one of them lies on the axis, the band
/// between them is a flat cap and becomes one polygon; other axis points become poles (fans of
/// triangles). A closed profile (torus) wraps around.
fn revolve(profile: &[(f64, f64)], segments: u32, closed: bool) -> Result<Vec<Polygon>> {
    let n = segments as usize;
    let angle: Vec<(f64, f64)> = (0..n)
        .map(|j| {
            let a = TAU * j as f64 / n as f64;
            (a.cos(), a.sin())
        })
        .collect();
    let point = |(r, y): (f64, f64), j: usize| {
        let (c, s) = angle[j % n];
        DVec3::new(r * c, y, r * s)
    };
    let bands = if closed {
        profile.len()
    } else {
        profile.len() - 1
    };
    let mut polygons: Vec<Polygon> = Vec::with_capacity(bands * n);
    for k in 0..bands {
        let a = profile[k];
        let b = profile[(k + 1) % profile.len()];
        let flat_cap = a.1 == b.1 && (a.0 == 0.0 || b.0 == 0.0);
        if flat_cap {
            let rim = if a.0 == 0.0 { b } else { a };
            // Counter-clockwise from outside: the top cap (a on the axis) faces +Y.
            let ring: Vec<DVec3> = if a.0 == 0.0 {
                (0..n).rev().map(|j| point(rim, j)).collect()
            } else {
                (0..n).map(|j| point(rim, j)).collect()
            };
            polygons.push(face(&ring)?);
            continue;
        }
        for j in 0..n {
            let quad = if a.0 == 0.0 {
                vec![point(a, 0), point(b, j + 1), point(b, j)]
            } else if b.0 == 0.0 {
                vec![point(a, j), point(a, j + 1), point(b, 0)]
            } else {
                vec![point(a, j), point(a, j + 1), point(b, j + 1), point(b, j)]
            };
            polygons.push(face(&quad)?);
        }
    }
    Ok(polygons)
}
