//! The octree walk's culling: blocks of cells, split in eight, and skipped whole where the
//! field's value at the centre proves that no surface passes through.

use super::Field;
use super::Source;
use crate::sdf::eval::Scratch;

/// A block of cells `lo..hi` (per axis).
#[derive(Clone, Copy, Debug)]
pub(super) struct Block {
    pub(super) lo: [usize; 3],
    pub(super) hi: [usize; 3],
}

pub(super) fn cannot_hold_surface<S: Source + ?Sized>(
    field: &Field<S>,
    scratch: &mut Scratch,
    b: &Block,
) -> bool {
    let g = &field.grid;
    let lo = g.point(b.lo[0], b.lo[1], b.lo[2]);
    let hi = g.point(b.hi[0], b.hi[1], b.hi[2]);
    let c = (lo + hi) * 0.5;
    let r = (hi - lo).length() * 0.5;
    // A margin for rounding in the field and in the corner coordinates.
    field.eval(scratch, c).abs() > r * (1.0 + 1e-9) + 1e-12 * (g.cell + c.abs().max_element())
}

pub(super) fn split(b: &Block, stack: &mut Vec<Block>) {
    let mid = [0, 1, 2].map(|i| b.lo[i] + (b.hi[i] - b.lo[i]).div_ceil(2));
    for o in 0..8 {
        let mut c = *b;
        for (i, &m) in mid.iter().enumerate() {
            if o >> i & 1 == 0 {
                c.hi[i] = m;
            } else {
                c.lo[i] = m;
            }
        }
        if (0..3).all(|i| c.lo[i] < c.hi[i]) {
            stack.push(c);
        }
    }
}
