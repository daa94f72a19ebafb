//! Root refinement on every vertex's bracket at once.

use super::leaf::Work;
use super::{Field, Source};

/// Illinois regula falsi on every bracket at once: each step evaluates one probe per vertex.
pub(super) fn refine<S: Source + ?Sized>(field: &Field<S>, steps: u32, w: &mut Work) {
    let n = w.a.len();
    w.side.clear();
    w.side.resize(n, 0);
    for _ in 0..steps {
        w.probe.clear();
        for i in 0..n {
            let t = w.fa[i] / (w.fa[i] - w.fb[i]);
            let t = if t.is_finite() {
                t.clamp(0.0, 1.0)
            } else {
                0.5
            };
            w.probe.push(w.a[i] + (w.b[i] - w.a[i]) * t);
        }
        w.fprobe.resize(n, 0.0);
        field.eval_batch(&mut w.scratch, &w.probe, &mut w.fprobe);
        for i in 0..n {
            let (p, f) = (w.probe[i], w.fprobe[i]);
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
        }
    }
}
