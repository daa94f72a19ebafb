//! Sketch constructors, centred at the origin. Round shapes take a chordal tolerance: no chord
//! strays further than it from the true curve.

use std::f64::consts::{FRAC_PI_2, TAU};

use glam::DVec2;

use super::{Region, Sketch};
use crate::error::{Error, Result};
use crate::primitives::{MAX_SEGMENTS, MIN_SEGMENTS, positive, segments_for_tolerance};

impl Sketch {
    /// A `width` × `height` rectangle centred at the origin.
    ///
    /// # Errors
    ///
    /// [`Error::InvalidParameter`](crate::Error::InvalidParameter) for a size that is not
    /// finite and positive or out of range.
    pub fn rectangle(width: f64, height: f64) -> Result<Sketch> {
        positive("width", width)?;
        positive("height", height)?;
        let (w, h) = (0.5 * width, 0.5 * height);
        Ok(Sketch::ring(vec![
            DVec2::new(-w, -h),
            DVec2::new(w, -h),
            DVec2::new(w, h),
            DVec2::new(-w, h),
        ]))
    }

    /// A circle of `radius` centred at the origin, as a regular polygon inscribed in it with
    /// enough sides that no chord strays more than `tolerance` from the circle (see
    /// [`segments_for_tolerance`](crate::segments_for_tolerance)).
    ///
    /// # Errors
    ///
    /// [`Error::InvalidParameter`](crate::Error::InvalidParameter) for a radius or tolerance
    /// that is not finite and positive, or a tolerance needing too many segments.
    pub fn circle(radius: f64, tolerance: f64) -> Result<Sketch> {
        let n = segments_for_tolerance(radius, tolerance)?;
        Sketch::circle_with_segments(radius, n)
    }

    /// A circle of `radius` as a regular polygon of `segments` sides inscribed in it, with a
    /// vertex on +x.
    ///
    /// # Errors
    ///
    /// [`Error::InvalidParameter`](crate::Error::InvalidParameter) for a radius that is not
    /// finite and positive or a segment count out of range.
    pub fn circle_with_segments(radius: f64, segments: u32) -> Result<Sketch> {
        positive("radius", radius)?;
        segment_count(segments)?;
        Ok(Sketch::ring(arc(
            DVec2::ZERO,
            radius,
            0.0,
            TAU,
            segments,
            false,
        )))
    }

    /// A regular polygon with `sides` sides inscribed in a circle of `circumradius`, a vertex on
    /// +y (so a triangle points up and a square stands on a corner).
    ///
    /// # Errors
    ///
    /// [`Error::InvalidParameter`](crate::Error::InvalidParameter) for a radius that is not
    /// finite and positive or a side count out of range.
    pub fn regular_polygon(sides: u32, circumradius: f64) -> Result<Sketch> {
        positive("circumradius", circumradius)?;
        segment_count(sides)?;
        Ok(Sketch::ring(arc(
            DVec2::ZERO,
            circumradius,
            FRAC_PI_2,
            TAU,
            sides,
            false,
        )))
    }

    /// A `width` × `height` rectangle centred at the origin with corners rounded to `radius`
    /// (at most half the shorter side; 0 gives the plain rectangle), each quarter circle with
    /// enough segments for the chordal `tolerance`.
    ///
    /// # Errors
    ///
    /// [`Error::InvalidParameter`](crate::Error::InvalidParameter) for sizes, a radius or a
    /// tolerance out of range.
    pub fn rounded_rectangle(
        width: f64,
        height: f64,
        radius: f64,
        tolerance: f64,
    ) -> Result<Sketch> {
        positive("width", width)?;
        positive("height", height)?;
        if !(radius.is_finite() && radius >= 0.0) {
            return Err(Error::param("radius", radius, "must be finite and ≥ 0"));
        }
        if radius > 0.5 * width.min(height) {
            return Err(Error::param(
                "radius",
                radius,
                "must be at most half the shorter side",
            ));
        }
        if radius == 0.0 {
            return Sketch::rectangle(width, height);
        }
        let quarter = segments_for_tolerance(radius, tolerance)?
            .div_ceil(4)
            .max(1);
        let (w, h) = (0.5 * width - radius, 0.5 * height - radius);
        let mut pts = Vec::new();
        for (k, c) in [
            DVec2::new(w, -h),
            DVec2::new(w, h),
            DVec2::new(-w, h),
            DVec2::new(-w, -h),
        ]
        .into_iter()
        .enumerate()
        {
            let start = -FRAC_PI_2 + FRAC_PI_2 * k as f64;
            pts.extend(arc(c, radius, start, FRAC_PI_2, quarter, true));
        }
        // Where the radius is the whole half side, neighbouring arcs meet in one point.
        pts.dedup();
        if pts.first() == pts.last() {
            pts.pop();
        }
        Ok(Sketch::ring(pts))
    }

    /// A sketch of one counter-clockwise simple ring (the constructors' output).
    fn ring(points: Vec<DVec2>) -> Sketch {
        Sketch {
            regions: vec![Region {
                outer: points,
                holes: Vec::new(),
            }],
            eps: 0.0,
        }
    }
}

/// Points on a circle of `radius` about `centre`, from angle `start` over `sweep` in `n` steps;
/// with `closed_end` the last point (at `start + sweep`) is included. Quarter and half turns
/// land exactly on the axes.
fn arc(centre: DVec2, radius: f64, start: f64, sweep: f64, n: u32, closed_end: bool) -> Vec<DVec2> {
    let count = if closed_end { n + 1 } else { n };
    (0..count)
        .map(|i| {
            let a = start + sweep * i as f64 / n as f64;
            centre + radius * unit(a)
        })
        .collect()
}

/// The unit vector at angle `a`, exact at multiples of a quarter turn.
fn unit(a: f64) -> DVec2 {
    let quarters = a / FRAC_PI_2;
    if (quarters - quarters.round()).abs() < 1e-12 {
        match (quarters.round() as i64).rem_euclid(4) {
            0 => DVec2::X,
            1 => DVec2::Y,
            2 => -DVec2::X,
            _ => -DVec2::Y,
        }
    } else {
        DVec2::new(a.cos(), a.sin())
    }
}

fn segment_count(n: u32) -> Result<()> {
    if n < MIN_SEGMENTS {
        Err(Error::param("segments", n as f64, "must be at least 3"))
    } else if n > MAX_SEGMENTS {
        Err(Error::param("segments", n as f64, "must be at most 16384"))
    } else {
        Ok(())
    }
}
