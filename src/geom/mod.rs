//! Basic geometry: boxes, planes, the tolerance that classifies points against planes, rotations,
//! planar triangulation and the geometric predicates everything above shares. Imports nothing
//! from the rest of the crate.

mod aabb;
pub(crate) mod bvh;
mod plane;
mod rotation;
mod tolerance;
pub(crate) mod triangulate;

pub use aabb::Aabb;
pub use plane::{Plane, Side};
pub(crate) use rotation::euler_degrees;
pub use tolerance::Tolerance;

/// The largest coordinate magnitude the kernel accepts. Volumes multiply three coordinates,
/// so beyond about 10¹⁰² they overflow f64; inputs past this bound are refused where they enter
/// (primitive sizes, transforms, meshes) rather than giving infinite or empty results.
pub const MAX_COORDINATE: f64 = 1e100;

/// The power of two that brings a magnitude of `reach` (finite, > 0) to at most 1. Scaling by
/// it is exact, so exact predicates can work on the scaled values without overflow.
pub(crate) fn unit_scale(reach: f64) -> f64 {
    2f64.powi(-reach.log2().ceil() as i32)
}

/// The signed solid angle of triangle `abc` seen from the origin (Van Oosterom–Strackee), for
/// generalised winding numbers: the angles of a closed surface sum to 4π at a point inside.
pub(crate) fn solid_angle(a: glam::DVec3, b: glam::DVec3, c: glam::DVec3) -> f64 {
    let (la, lb, lc) = (a.length(), b.length(), c.length());
    let num = a.dot(b.cross(c));
    let den = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
    2.0 * num.atan2(den)
}

/// A triangle is a *needle* when its area is below this fraction of the square of its shell's
/// bounding-box diagonal `d`.
///
/// Why 10⁻¹²: a needle's height over its longest edge `L ≤ d` is below `2·10⁻¹² d² / L`. For a
/// long one (`L` near `d`) that is twice the plane tolerance booleans use (`10⁻¹²` of the
/// region they work in): its apex cannot be told from its base's line by the kernel itself. A
/// short one is a speck below `1.4·10⁻⁶ d` across, or thinner still: far below any feature a
/// slicer, a mesher or a renderer resolves, and what manifold3d's own cleanup removes. Relative
/// to the shell, not the whole mesh, so a unit part beside a box a million times larger keeps
/// its triangles. (A part joined to such a box is one shell: the report then counts the part's
/// triangles as needles, but `to_mesh` judges needles at no more than 16 times the scale of the
/// region where the boolean's operands met, so it leaves them be.) Larger thresholds would start eating real detail of tessellated curves (a
/// 10⁻³ fillet on a 10³ model has triangles of area 10⁻¹¹ d²).
///
/// The two halves are why a needle by area is not always one the kernel must remove. The
/// needles booleans and welds make are *thin* (a vertex a hair from a neighbour's edge: the
/// longest edge over 100 heights) or *specks* (within a weld's reach, or a speck of the shell
/// itself). A shell thinner than it is long changes the second half: a well-shaped triangle of
/// its own detail can be under `1.4·10⁻⁶ d` across and still span the shell (a prism 6.7·10⁶
/// long on a 6 × 3 end: its end triangles, of area 9, are below `10⁻¹² d² = 44`, and
/// collapsing one would take a third of its volume, so the needle pass leaves them). The
/// report counts every needle by area. The needle pass removes every needle by area, and in a
/// shell where that changes the volume beyond its bound, only thin ones and specks, a speck
/// judged against the shell's thickness (6 × `2V/A`) on a shell under 10⁻⁵ of its diagonal
/// thick, else against the diagonal ([`is_needle_to_remove`]); the `scenes` fuzz target's
/// check demands away only those.
pub(crate) const NEEDLE_AREA: f64 = 1e-12;

/// The size, as a fraction of the shell's diagonal, of a speck that counts as a needle:
/// `√NEEDLE_AREA`. Removing a needle may move the surface twice this (a speck's shortest edge
/// can be up to 1.52 times it; see `mesh::needles`).
pub(crate) const MAX_MOVE: f64 = 1e-6;

/// A needle the kernel removes is *thin*: its longest edge more than this many times its
/// height (a cut or weld put a vertex a hair from a neighbour's edge; `bsp_1`'s notch slivers,
/// 3·10⁻⁵ wide, are 320 to 5,000).
pub const NEEDLE_THIN: f64 = 100.0;

/// ... or within a weld's reach: every edge shorter than this many plane tolerances
/// (`Tolerance::RELATIVE` of the diagonal): four first welds (`repair::WELD_TOLERANCES`, 8),
/// the needle pass's own sweep allowance.
pub const NEEDLE_WELD_TOLERANCES: f64 = 32.0;

/// ... or a speck of its shell: area below `NEEDLE_AREA · s²`, where `s` is this many slab
/// thicknesses `2V/A` of the shell (volume `V`, area `A`) when that is below
/// [`NEEDLE_THIN_SHELL`] of its diagonal, else the shell's diagonal.
pub const NEEDLE_SPECK_THICKNESSES: f64 = 6.0;

/// A shell is thinner than a speck of its own length when [`NEEDLE_SPECK_THICKNESSES`] of its
/// slab thicknesses are below this fraction of its diagonal: there a speck is judged by its
/// thickness. Everywhere else it is judged by the diagonal, as the report judges it: the output
/// shells of the stored scene findings, brackets and bakes, are 8.7 to 10⁸ slab thicknesses
/// across (a cube or a sphere 5.2), so "the smaller of the two" judged almost every real shell
/// by its thickness, 3 to 300 times looser than the report. A prism 6.7·10⁶ long on a 6 × 3
/// end (6 × `2V/A` = 9, under 10⁻⁵ d = 67) is judged by its thickness; a bracket is not.
pub const NEEDLE_THIN_SHELL: f64 = 1e-5;

/// True when triangle `corners`, in a shell whose bounding-box diagonal (as capped) is
/// `diagonal` and whose slab thickness `2V/A` is `slab` (`f64::INFINITY` when unknown), is a
/// needle the kernel removes: a needle by area (`NEEDLE_AREA`) that is thin
/// ([`NEEDLE_THIN`]), within a weld's reach ([`NEEDLE_WELD_TOLERANCES`]) or a speck of its
/// shell ([`NEEDLE_SPECK_THICKNESSES`]). A well-shaped triangle larger than a weld on a shell
/// thinner than it is long is the shape's own detail, and stays. The needle pass falls back on
/// this rule in a shell where removing every needle by area would change its volume beyond the
/// bound; the `scenes` fuzz target's check counts by it; `MeshReport` counts every needle by
/// area.
#[must_use]
pub fn is_needle_to_remove(corners: [glam::DVec3; 3], diagonal: f64, slab: f64) -> bool {
    let [a, b, c] = corners;
    let area = 0.5 * (b - a).cross(c - a).length();
    area < NEEDLE_AREA * diagonal * diagonal && needle_of_kernel(corners, area, diagonal, slab)
}

/// The second half of [`is_needle_to_remove`], for a triangle of `area` already known to be a
/// needle by area.
pub(crate) fn needle_of_kernel(
    [a, b, c]: [glam::DVec3; 3],
    area: f64,
    diagonal: f64,
    slab: f64,
) -> bool {
    let thickness = NEEDLE_SPECK_THICKNESSES * slab;
    let s = if thickness < NEEDLE_THIN_SHELL * diagonal {
        thickness
    } else {
        diagonal
    };
    if area < NEEDLE_AREA * s * s {
        return true;
    }
    let longest = a
        .distance_squared(b)
        .max(b.distance_squared(c))
        .max(c.distance_squared(a));
    let weld = NEEDLE_WELD_TOLERANCES * Tolerance::RELATIVE * diagonal;
    is_thin([a, b, c], area) || longest < weld * weld
}

/// Whether triangle `[a, b, c]` of `area` is thin: its longest edge more than [`NEEDLE_THIN`]
/// times its height.
pub(crate) fn is_thin([a, b, c]: [glam::DVec3; 3], area: f64) -> bool {
    let longest = a
        .distance_squared(b)
        .max(b.distance_squared(c))
        .max(c.distance_squared(a));
    // Height = 2·area / longest: thin when longest > THIN · height.
    longest > 2.0 * NEEDLE_THIN * area
}

/// True when triangle `c` is a needle in a shell whose bounding-box diagonal is `diagonal`.
pub(crate) fn is_needle([a, b, c]: [glam::DVec3; 3], diagonal: f64) -> bool {
    0.5 * (b - a).cross(c - a).length() < NEEDLE_AREA * diagonal * diagonal
}

/// A triangle is degenerate when twice its area is at most this many units of rounding:
/// `ε · Σ |corner| · |opposite edge|` (see [`is_zero_area`]).
pub(crate) const ZERO_AREA_ULPS: f64 = 32.0;

/// True when twice the triangle's area is at most [`ZERO_AREA_ULPS`] units of the
/// rounding its corners carry. Coordinates are first scaled by a power of two (exact) so that
/// nothing overflows or underflows.
pub(crate) fn is_zero_area([a, b, c]: [glam::DVec3; 3]) -> bool {
    let reach = a.abs().max(b.abs()).max(c.abs()).max_element();
    if !reach.is_finite() {
        return false;
    }
    if reach == 0.0 {
        return true;
    }
    !clearly_spans_area(a, b, c, reach) && flat_to_rounding(a, b, c, reach)
}

/// [`is_zero_area`]'s measure itself, for corners within `reach` (finite, not 0) of the origin.
fn flat_to_rounding(a: glam::DVec3, b: glam::DVec3, c: glam::DVec3, reach: f64) -> bool {
    let s = unit_scale(reach);
    let (a, b, c) = (a * s, b * s, c * s);
    // Cross the two shorter edges, at the corner opposite the longest: differences taken at a
    // far corner would round the near corners together.
    let (ab, bc, ca) = (
        (b - a).length_squared(),
        (c - b).length_squared(),
        (a - c).length_squared(),
    );
    let twice = if ab >= bc && ab >= ca {
        (a - c).cross(b - c).length()
    } else if bc >= ca {
        (b - a).cross(c - a).length()
    } else {
        (c - b).cross(a - b).length()
    };
    let rounding = a.length() * (b - c).length()
        + b.length() * (c - a).length()
        + c.length() * (a - b).length();
    twice <= ZERO_AREA_ULPS * f64::EPSILON * rounding
}

/// A quick sufficient test that [`is_zero_area`] is false, without its scaling and square
/// roots: most triangles a boolean or `to_mesh` asks about are far from flat (the core fans of
/// an indexed boolean: a tenth of `to_mesh` on a sphere union went to the full test).
///
/// Every corner is at most `√3·reach` from the origin and every edge at most `2√3·reach` long,
/// so the full test's rounding term is at most `18·reach²`, and its bound at most
/// `ZERO_AREA_ULPS·ε·18·reach²`. The cross product here and the full test's differ from the
/// true twice-area by a few `ε·reach²` each, so a squared cross product above four times
/// that bound, squared, leaves the full test nothing to find. Only where `reach²` neither
/// overflows nor underflows (else the full test, which scales first, decides).
fn clearly_spans_area(a: glam::DVec3, b: glam::DVec3, c: glam::DVec3, reach: f64) -> bool {
    if !(1e-60..=1e60).contains(&reach) {
        return false;
    }
    let bound = 4.0 * ZERO_AREA_ULPS * f64::EPSILON * 18.0 * reach * reach;
    (b - a).cross(c - a).length_squared() > bound * bound
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;

    #[test]
    fn zero_area_is_scale_free() {
        let line = [DVec3::ZERO, DVec3::X, DVec3::X * 2.0];
        let fat = [DVec3::ZERO, DVec3::X, DVec3::Y];
        for scale in [1e-200, 1e-6, 1.0, 1e6, 1e200] {
            assert!(is_zero_area(line.map(|p| p * scale)));
            assert!(!is_zero_area(fat.map(|p| p * scale)), "{scale}");
        }
        // A cap whose apex is off the base by about its own rounding is flat; by 10⁻¹³, not.
        let cap = |h: f64, at: DVec3| [at, at + DVec3::X, at + DVec3::new(0.5, h, 0.0)];
        assert!(is_zero_area(cap(1e-15, DVec3::ZERO)));
        assert!(!is_zero_area(cap(1e-13, DVec3::ZERO)));
        // A million units from the origin, corners carry 10⁻¹⁰ of rounding.
        assert!(is_zero_area(cap(1e-11, DVec3::splat(1e6))));
        assert!(!is_zero_area(cap(1e-7, DVec3::splat(1e6))));
        // Thin is not flat: a 1-wide base joined to a corner 10³⁸ away has area 10³⁸.
        let far = [DVec3::ZERO, DVec3::X, DVec3::new(3e38, 3e38, 0.0)];
        assert!(!is_zero_area(far));
        assert!(is_zero_area([DVec3::ONE; 3]));
        assert!(!is_zero_area([DVec3::ZERO, DVec3::X, DVec3::NAN]));
    }

    /// The quick test never says "spans area" where the full one says flat: caps of every
    /// height from far below to far above the threshold, at many scales and offsets.
    #[test]
    fn the_quick_test_agrees_with_the_full_one() {
        let (mut checked, mut flat) = (0, 0);
        for scale in [1e-70, 1e-59, 1e-30, 1e-3, 1.0, 7.3, 1e5, 1e30, 1e59, 1e70] {
            for offset in [0.0, 0.5, 3.0, 1e3, 1e6] {
                for k in -40..=8 {
                    let h = 10f64.powf(k as f64 * 0.5) * scale;
                    let at = DVec3::new(offset, -0.7 * offset, 0.3 * offset) * scale;
                    let tri = [
                        at,
                        at + DVec3::new(1.0, 0.2, -0.1) * scale,
                        at + DVec3::new(0.4, 0.08, -0.04) * scale + DVec3::new(0.1, -0.3, 1.0) * h,
                    ];
                    let reach = tri[0].abs().max(tri[1].abs()).max(tri[2].abs());
                    let reach = reach.max_element();
                    if clearly_spans_area(tri[0], tri[1], tri[2], reach) {
                        assert!(
                            !flat_to_rounding(tri[0], tri[1], tri[2], reach),
                            "{scale} {offset} {k}"
                        );
                        checked += 1;
                    } else if flat_to_rounding(tri[0], tri[1], tri[2], reach) {
                        flat += 1;
                    }
                }
            }
        }
        assert!(checked > 500 && flat > 50, "{checked} {flat}");
    }
}
