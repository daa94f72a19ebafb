//! The report's one-paragraph summary.

use std::fmt;

use super::MeshReport;

impl fmt::Display for MeshReport {
    /// A compact summary: one line of counts and verdict, then one line per kind of defect
    /// found.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let plural =
            |n: usize, one: &str, many: &str| format!("{n} {}", if n == 1 { one } else { many });
        write!(
            f,
            "{}, {}, {}, {}: ",
            plural(self.triangles, "triangle", "triangles"),
            plural(self.vertices, "vertex", "vertices"),
            plural(self.edges, "edge", "edges"),
            plural(self.shells.len(), "shell", "shells"),
        )?;
        if self.is_closed_manifold() {
            f.write_str("closed 2-manifold")?;
        } else {
            f.write_str("NOT a closed 2-manifold")?;
        }
        match self.genus {
            Some(g) => write!(f, ", genus {g}")?,
            None => f.write_str(", genus undefined")?,
        }
        write!(f, ", volume {}", Number(self.volume))?;
        let cavities = self.shells.iter().filter(|s| s.cavity).count();
        if cavities > 0 {
            write!(f, ", {}", plural(cavities, "cavity", "cavities"))?;
        }
        let defects = [
            (self.boundary_edges, "boundary edges"),
            (
                self.non_manifold_edges,
                "non-manifold edges (more than two triangles)",
            ),
            (self.inconsistent_edges, "inconsistently oriented edges"),
            (self.non_manifold_vertices, "non-manifold vertices"),
            (
                self.invalid_index_triangles,
                "triangles with an index out of range",
            ),
            (
                self.non_finite_vertices,
                "vertices with a non-finite coordinate",
            ),
            (
                self.inverted_shells,
                "closed shells of non-positive volume (inside out or flat)",
            ),
        ];
        for (n, what) in defects.iter().filter(|(n, _)| *n > 0) {
            write!(f, "\n  {what}: {n}")?;
        }
        if self.needles > 0 {
            write!(
                f,
                "\n  needles (area below 1e-12 × shell diagonal², not defects of topology): {}",
                self.needles
            )?;
        }
        let (degenerate, repeated) = (self.degenerate_triangles, self.repeated_index_triangles);
        if repeated == 0 && degenerate > 0 {
            write!(f, "\n  degenerate triangles (zero area): {degenerate}")?;
        } else if repeated == degenerate && degenerate > 0 {
            write!(f, "\n  degenerate triangles (repeated index): {degenerate}")?;
        } else if degenerate > 0 {
            write!(
                f,
                "\n  degenerate triangles: {degenerate} ({repeated} repeat an index, the rest \
                 have zero area)"
            )?;
        }
        Ok(())
    }
}

/// A number printed plainly, or in scientific notation when very large or small (a box out to
/// 10³⁸ has a volume of 81 digits).
struct Number(f64);

impl fmt::Display for Number {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let v = self.0.abs();
        if v == 0.0 || (1e-4..1e9).contains(&v) || !v.is_finite() {
            write!(f, "{}", self.0)
        } else {
            write!(f, "{:e}", self.0)
        }
    }
}
