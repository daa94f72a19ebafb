//! Root refinement on every vertex's bracket at once.

use glam::DVec3;

use super::leaf::Work;
use super::options::MAX_REFINE_STEPS;
use super::{Field, Source};

/// How far each vertex's root is refined.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Refine {
    /// This many steps for every vertex.
    Steps(u32),
    /// Until the vertex's bracket stops shrinking (its probe lands on an end or on a zero), at
    /// most [`MAX_REFINE_STEPS`] steps. The root then no longer depends on the values at the
    /// grid points the bracket started from, only on the field near the root: two bakes of
    /// fields equal near a surface (a shape alone and in a smooth union whose blend reaches
    /// some grid points beside it but not the surface) place its vertices the same to the last
    /// bit or two, where a few steps left them 10⁻¹⁴ … 10⁻⁸ apart.
    Converge,
}

/// Illinois regula falsi on every bracket at once: each step evaluates one probe per vertex
/// still refined.
pub(super) fn refine<S: Source + ?Sized>(field: &Field<S>, how: Refine, w: &mut Work) {
    let n = w.a.len();
    w.side.clear();
    w.side.resize(n, 0);
    let (steps, converge) = match how {
        Refine::Steps(steps) => (steps, false),
        Refine::Converge => (MAX_REFINE_STEPS, true),
    };
    w.active.clear();
    w.active.extend(0..n as u32);
    for _ in 0..steps {
        if w.active.is_empty() {
            break;
        }
        w.probe.clear();
        for &i in &w.active {
            let i = i as usize;
            w.probe.push(probe(w.a[i], w.b[i], w.fa[i], w.fb[i]));
        }
        w.fprobe.resize(w.probe.len(), 0.0);
        field.eval_batch(&mut w.scratch, &w.probe, &mut w.fprobe);
        let mut kept = 0;
        for x in 0..w.active.len() {
            let i = w.active[x] as usize;
            let (p, f) = (w.probe[x], w.fprobe[x]);
            let stalled = p == w.a[i] || p == w.b[i] || f == 0.0;
            if f < 0.0 {
                w.a[i] = p;
                w.fa[i] = f;
                // The outside end stayed twice: halve its weight (Illinois).
                if w.side[i] == -1 {
                    w.fb[i] *= 0.5;
                }
                w.side[i] = -1;
            } else {
                w.b[i] = p;
                w.fb[i] = f;
                if w.side[i] == 1 {
                    w.fa[i] *= 0.5;
                }
                w.side[i] = 1;
            }
            if !(converge && stalled) {
                w.active[kept] = i as u32;
                kept += 1;
            }
        }
        w.active.truncate(kept);
    }
}

/// The bracket's linear guess (its middle where the values give none).
#[inline]
fn probe(a: DVec3, b: DVec3, fa: f64, fb: f64) -> DVec3 {
    let t = fa / (fa - fb);
    let t = if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        0.5
    };
    a + (b - a) * t
}
