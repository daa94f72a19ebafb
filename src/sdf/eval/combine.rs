//! The value of one operation from its two operands: the sharp booleans, the smooth blends
//! (overflow-free) and, for coloured output, which operand's material decides.

use super::Op;
use crate::sdf::tree::SmoothKind;
use crate::solid::BoolOp;

/// Smooth minimum, overflow-free: `−ln(e^(−k·a) + e^(−k·b)) / k` rewritten around the
/// smaller value as `m − ln(1 + e^(−k·|a−b|)) / k`.
#[inline]
fn smin(kind: SmoothKind, k: f64, a: f64, b: f64) -> f64 {
    match kind {
        SmoothKind::Exponential => {
            let diff = (a - b).abs();
            if diff.is_nan() {
                // Both infinite (empty operands): nothing to blend.
                return a.min(b);
            }
            a.min(b) - (-k * diff).exp().ln_1p() / k
        }
        SmoothKind::Polynomial => {
            let h = (0.5 + 0.5 * (b - a) / k).clamp(0.0, 1.0);
            if !h.is_finite() || (b - a).abs() >= k {
                return a.min(b);
            }
            b + (a - b) * h - k * h * (1.0 - h)
        }
    }
}

#[inline]
fn smax(kind: SmoothKind, k: f64, a: f64, b: f64) -> f64 {
    -smin(kind, k, -a, -b)
}

#[inline]
pub(super) fn combine(op: Op, a: f64, b: f64) -> f64 {
    match op {
        Op::Union => a.min(b),
        Op::Intersect => a.max(b),
        Op::Subtract => a.max(-b),
        Op::Smooth { op, kind, k } => match op {
            BoolOp::Union => smin(kind, k, a, b),
            BoolOp::Intersection => smax(kind, k, a, b),
            BoolOp::Difference => smax(kind, k, a, -b),
        },
    }
}

/// The combined value and the material of the operand that decides it (the nearer one for a
/// union, the farther for an intersection, the subtracted one where the cut decides).
#[inline]
pub(super) fn combine_material(op: Op, a: (f64, u32), b: (f64, u32)) -> (f64, u32) {
    let base = match op {
        Op::Union => BoolOp::Union,
        Op::Intersect => BoolOp::Intersection,
        Op::Subtract => BoolOp::Difference,
        Op::Smooth { op, .. } => op,
    };
    let m = match base {
        BoolOp::Union => {
            if a.0 <= b.0 {
                a.1
            } else {
                b.1
            }
        }
        BoolOp::Intersection => {
            if a.0 >= b.0 {
                a.1
            } else {
                b.1
            }
        }
        BoolOp::Difference => {
            if a.0 >= -b.0 {
                a.1
            } else {
                b.1
            }
        }
    };
    (combine(op, a.0, b.0), m)
}

pub(super) fn combine_slices(op: Op, a: &mut [f64], b: &[f64]) {
    match op {
        Op::Union => a.iter_mut().zip(b).for_each(|(x, &y)| *x = x.min(y)),
        Op::Intersect => a.iter_mut().zip(b).for_each(|(x, &y)| *x = x.max(y)),
        Op::Subtract => a.iter_mut().zip(b).for_each(|(x, &y)| *x = x.max(-y)),
        _ => a
            .iter_mut()
            .zip(b)
            .for_each(|(x, &y)| *x = combine(op, *x, y)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn smooth_union_is_stable_and_matches_the_spec() {
        let k: f64 = 8.0;
        for &(a, b) in &[(0.1f64, 0.3f64), (-0.2, 0.05), (1.0, 1.0)] {
            let spec: f64 = -((-k * a).exp() + (-k * b).exp()).ln() / k;
            let ours = smin(SmoothKind::Exponential, k, a, b);
            assert!((spec - ours).abs() < 1e-12, "{a} {b}: {spec} vs {ours}");
        }
        // The naive form overflows here; ours returns min − ln2/k.
        let big = smin(SmoothKind::Exponential, 1000.0, -5.0, -5.0);
        assert!((big - (-5.0 - std::f64::consts::LN_2 / 1000.0)).abs() < 1e-12);
        assert_eq!(smin(SmoothKind::Exponential, 10.0, 1e300, 1e-3), 1e-3);
    }

    #[test]
    fn polynomial_smin_matches_seed_000() {
        let k: f64 = 0.5;
        for &(left, right) in &[(0.1f64, 0.3f64), (-0.2, 0.05), (1.0, 2.0)] {
            let h: f64 = (0.5 + (right - left) / (2.0 * k)).clamp(0.0, 1.0);
            let seed = right + (left - right) * h - k * h * (1.0 - h);
            let ours = smin(SmoothKind::Polynomial, k, left, right);
            assert!((seed - ours).abs() < 1e-12);
        }
    }
}
