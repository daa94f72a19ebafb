//! Double-double arithmetic (a value as the unevaluated sum of two `f64`s, about 106 bits), for
//! the one quantity of nearly parallel planes that rounding to `f64` left uncertain beyond what
//! the clip allows for: where three of them meet (see [`super::planes::meet`]).
//!
//! Products are split by Dekker's method rather than fused, so every platform gets the same
//! bits.

use glam::DVec3;

/// `hi + lo`, with `|lo|` at most half an ulp of `hi`.
#[derive(Clone, Copy, Debug)]
pub(super) struct Dd {
    hi: f64,
    lo: f64,
}

/// The sum of `a` and `b` and its rounding error, exactly (Knuth).
#[inline]
fn two_sum(a: f64, b: f64) -> Dd {
    let s = a + b;
    let bb = s - a;
    let lo = (a - (s - bb)) + (b - bb);
    Dd { hi: s, lo }
}

/// `a` in two halves of 26 bits each (Dekker).
#[inline]
fn halves(a: f64) -> (f64, f64) {
    let c = 134_217_729.0 * a; // 2^27 + 1
    let hi = c - (c - a);
    (hi, a - hi)
}

/// The product of `a` and `b` and its rounding error, exactly (Dekker).
#[inline]
fn two_prod(a: f64, b: f64) -> Dd {
    let p = a * b;
    let (ah, al) = halves(a);
    let (bh, bl) = halves(b);
    let lo = ((ah * bh - p) + ah * bl + al * bh) + al * bl;
    Dd { hi: p, lo }
}

impl Dd {
    #[inline]
    pub(super) fn from(a: f64) -> Dd {
        Dd { hi: a, lo: 0.0 }
    }

    /// `a − b`, exactly.
    #[inline]
    pub(super) fn diff(a: f64, b: f64) -> Dd {
        two_sum(a, -b)
    }

    #[inline]
    pub(super) fn value(self) -> f64 {
        self.hi + self.lo
    }

    #[inline]
    pub(super) fn add(self, b: Dd) -> Dd {
        let s = two_sum(self.hi, b.hi);
        let t = two_sum(self.lo, b.lo);
        let s = two_sum(s.hi, s.lo + t.hi);
        two_sum(s.hi, s.lo + t.lo)
    }

    #[inline]
    pub(super) fn neg(self) -> Dd {
        Dd {
            hi: -self.hi,
            lo: -self.lo,
        }
    }

    #[inline]
    pub(super) fn mul(self, b: Dd) -> Dd {
        let p = two_prod(self.hi, b.hi);
        two_sum(p.hi, p.lo + (self.hi * b.lo + self.lo * b.hi))
    }

    #[inline]
    pub(super) fn mul_f(self, b: f64) -> Dd {
        let p = two_prod(self.hi, b);
        two_sum(p.hi, p.lo + self.lo * b)
    }

    /// `self / b`; `None` where `b` is zero or the quotient not finite.
    pub(super) fn div(self, b: Dd) -> Option<Dd> {
        let q1 = self.hi / b.hi;
        if !q1.is_finite() {
            return None;
        }
        let r = self.add(b.mul_f(q1).neg());
        let q2 = r.hi / b.hi;
        let r = r.add(b.mul_f(q2).neg());
        let q3 = r.hi / b.hi;
        let q = two_sum(q1, q2);
        Some(two_sum(q.hi, q.lo + q3))
    }
}

/// `a · b` for `a` of doubles and `b` of double-doubles.
#[inline]
pub(super) fn dot(a: DVec3, b: [Dd; 3]) -> Dd {
    b[0].mul_f(a.x).add(b[1].mul_f(a.y)).add(b[2].mul_f(a.z))
}

/// `a − b`, each component exactly.
#[inline]
pub(super) fn diff(a: DVec3, b: DVec3) -> [Dd; 3] {
    [Dd::diff(a.x, b.x), Dd::diff(a.y, b.y), Dd::diff(a.z, b.z)]
}

/// `a × b` of doubles, each component to double-double precision.
#[inline]
pub(super) fn cross(a: DVec3, b: DVec3) -> [Dd; 3] {
    let c = |p: f64, q: f64, r: f64, s: f64| two_prod(p, q).add(two_prod(r, s).neg());
    [
        c(a.y, b.z, a.z, b.y),
        c(a.z, b.x, a.x, b.z),
        c(a.x, b.y, a.y, b.x),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn products_and_sums_keep_what_doubles_round_away() {
        let a = 1.0 + f64::EPSILON;
        let p = two_prod(a, a); // 1 + 2ε + ε²
        assert_eq!(p.hi, 1.0 + 2.0 * f64::EPSILON);
        assert_eq!(p.lo, f64::EPSILON * f64::EPSILON);
        let s = Dd::from(1.0).add(Dd::from(1e-20)).add(Dd::from(-1.0));
        assert_eq!(s.value(), 1e-20);
        let third = Dd::from(1.0).div(Dd::from(3.0)).unwrap();
        let back = third.mul_f(3.0).add(Dd::from(-1.0));
        assert!(back.value().abs() < 1e-30, "{back:?}");
    }
}
