//! The work booleans may do: the corners of the pieces clipping cuts and the pieces building
//! their trees cuts, counted as they go and charged to a [`Meter`] shared by every boolean that
//! serves one result (a boolean, an n-ary reduction, a scene), which stops building and
//! clipping once its limit is passed.
//!
//! The cut pieces are what grows without bound where faces of the operands nearly coincide
//! over a wide area: a polygon that lies along a wall of the other operand crosses the many
//! planes of that wall's faces and is cut at each. Four copies of one 10,000-point wavy outline
//! extruded, each 0.016 from the last, cut pieces of 21 M corners in all (1.2 M polygons out of
//! the last union); ordinary booleans cut a few per polygon clipped (rocker-arm ∪ moved 0.32 M,
//! the 512 × 256 sphere ∪ moved 0.28 M, fandisk − moved 0.14 M). Tree builds cut nearly coinciding
//! walls as badly: with them charged, the four copies stop in their first unions (the two
//! copies' union charges 9.0 M, building and clipping), at 1.0 GB where clipping alone let
//! the last union's trees be built first (3.1 GB). Ordinary booleans, both together: rocker-arm
//! ∪ moved 0.25 M, fandisk − moved 0.09 M, the 256 × 128 sphere ∪ moved 0.10 M.

use std::sync::atomic::{AtomicU64, Ordering};

/// Corners a clip counts on its own before charging them to the meter: one atomic add per
/// this many, and the overrun past the limit at most this much per thread.
pub(crate) const CHARGE_EVERY: u64 = 1 << 12;

/// The cut corners charged so far against a limit (see the module docs).
#[derive(Debug)]
pub(crate) struct Meter {
    used: AtomicU64,
    limit: u64,
}

impl Meter {
    /// A meter that stops work past `limit` cut corners.
    pub(crate) fn new(limit: u64) -> Self {
        Meter {
            used: AtomicU64::new(0),
            limit,
        }
    }

    /// Charges `corners`; false once the total is past the limit.
    #[inline]
    pub(crate) fn charge(&self, corners: u64) -> bool {
        let before = self.used.fetch_add(corners, Ordering::Relaxed);
        before.saturating_add(corners) <= self.limit
    }

    /// True once the charges are past the limit.
    #[inline]
    pub(crate) fn exceeded(&self) -> bool {
        self.used() > self.limit
    }

    /// The corners charged so far.
    pub(crate) fn used(&self) -> u64 {
        self.used.load(Ordering::Relaxed)
    }

    /// The limit.
    pub(crate) fn limit(&self) -> u64 {
        self.limit
    }
}
