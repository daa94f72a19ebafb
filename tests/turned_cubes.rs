//! A unit cube less itself turned by a hair (10⁻⁷° … 10⁻⁴°) about several axes: the result is
//! a few wedges 10⁻¹⁰ … 10⁻⁶ thick, which the kernel does not resolve at every angle. The
//! promise (issue 12, "no silent wrong answer"): a closed 2-manifold of the right volume, or a
//! refusal — `Err` from [`Solid::to_checked_mesh`], exit 2 on the command line — never a
//! success with a wrong volume (an empty mesh, or a wedge flattened away by a wide weld).

mod common;

use bspcsg::glam::DVec3;
use bspcsg::{Solid, Tolerance};
use common::hostile::right_or_refused;
use common::run::{Scratch, bspcsg_to};

/// The axes: the cube's diagonal (through two corners, which the turn leaves in place: six
/// planes meet there to rounding), one along an edge, and two skew ones.
const AXES: [DVec3; 4] = [
    DVec3::ONE,
    DVec3::Z,
    DVec3::new(0.3, 1.0, 0.2),
    DVec3::new(1.0, 0.1, -0.4),
];

const DEGREES: [f64; 10] = [1e-7, 3e-7, 1e-6, 2e-6, 3e-6, 5e-6, 1e-5, 3e-5, 1e-4, 2e-4];

/// The unit cube [0, 1]³.
fn cube() -> Solid {
    Solid::cube(1.0)
        .unwrap()
        .translate(DVec3::splat(0.5))
        .unwrap()
}

/// The first-order volume of the cube less itself turned by `degrees` about `axis` through the
/// origin: (θ / 2) ∫ |(ŵ × x) · n| dA over the cube's faces (each face point moves by θ ŵ × x,
/// and the part moving inwards uncovers a wedge of that thickness). Midpoint quadrature, 400²
/// points a face (the integrand is piecewise linear: relative error below 10⁻⁵); the second
/// order is θ² smaller.
fn first_order_volume(axis: DVec3, degrees: f64) -> f64 {
    let w = axis.normalize();
    let n = 400;
    let h = 1.0 / n as f64;
    let mut sum = 0.0;
    for k in 0..3 {
        for side in [0.0, 1.0] {
            let mut normal = DVec3::ZERO;
            normal[k] = if side == 0.0 { -1.0 } else { 1.0 };
            for i in 0..n {
                for j in 0..n {
                    let mut x = DVec3::ZERO;
                    x[k] = side;
                    x[(k + 1) % 3] = (i as f64 + 0.5) * h;
                    x[(k + 2) % 3] = (j as f64 + 0.5) * h;
                    sum += w.cross(x).dot(normal).abs() * h * h;
                }
            }
        }
    }
    degrees.to_radians() / 2.0 * sum
}

/// How far a right answer's volume may be from the first-order one: 10⁻³ of it (the solid's own
/// polygons are that close at 10⁻⁵°, where the corners lie 10⁻¹⁴ off the twin faces), and
/// what the repair's first weld explains, 4 × 8 tolerances × the wedges' area (both sides of
/// every face, 6): 5·10⁻¹⁰ here, 2 % of the thinnest result's volume.
fn slack(want: f64) -> f64 {
    let eps = Tolerance::RELATIVE * 3f64.sqrt();
    1e-3 * want + 4.0 * 8.0 * eps * 6.0
}

#[test]
fn a_cube_less_itself_turned_a_hair_is_right_or_refused() {
    let cube = cube();
    let (mut right, mut refused) = (Vec::new(), Vec::new());
    for axis in AXES {
        for degrees in DEGREES {
            let what = format!("cube − cube turned {degrees:e}° about {axis}");
            let turned = cube.clone().rotate_axis_angle(axis, degrees).unwrap();
            let result = &cube - &turned;
            let want = first_order_volume(axis, degrees);
            match result.to_checked_mesh() {
                Err(e) => {
                    assert!(
                        e.to_string().contains("not a closed 2-manifold"),
                        "{what}: {e}"
                    );
                    refused.push(what);
                }
                Ok(mesh) => {
                    let report = mesh.report();
                    assert!(report.is_closed_manifold(), "{what}: {report}");
                    let got = mesh.volume();
                    println!(
                        "{what}: mesh {got:.6e}, solid {:.6e}, first order {want:.6e}",
                        result.volume()
                    );
                    assert!(
                        (got - want).abs() <= slack(want),
                        "{what}: {got:e} want {want:e}"
                    );
                    right.push(what);
                }
            }
        }
    }
    println!("refused: {refused:#?}");
    // Most are resolved; the refusals are where the kernel's polygons do not close (corners
    // where six planes meet to rounding).
    assert!(
        right.len() >= 30,
        "{} right, refused: {refused:#?}",
        right.len()
    );
}

/// The same on the command line, about the diagonal (where the kernel refuses at 10⁻⁶° and
/// 2·10⁻⁶°, and once gave an empty mesh reported closed, exit 0) and a skew axis: exit 0 with a
/// closed mesh of the right volume, or exit 2 saying it is not a closed 2-manifold, and nothing
/// written. Down to 10⁻⁹° (issue 12 item 3 named 10⁻⁹° … 10⁻⁵°), where the wedges, at most
/// 3·10⁻¹¹ thick, lie within the weld of the faces that bound them: a thinner or empty result
/// is within the slack there, an open one is not.
#[test]
fn the_command_line_never_writes_a_wrong_turned_cube_difference() {
    let dir = Scratch::new("turned-cubes");
    let cube = cube();
    let a = dir.path("cube.obj");
    bspcsg::write_mesh(&a, &cube.to_mesh(), &[]).unwrap();
    for axis in [DVec3::ONE, DVec3::new(0.3, 1.0, 0.2)] {
        for degrees in [1e-9, 1e-8, 1e-7, 1e-6, 2e-6, 3e-6, 1e-5, 1e-4] {
            let what = format!("difference, turned {degrees:e}° about {axis}");
            let turned = cube.clone().rotate_axis_angle(axis, degrees).unwrap();
            let b = dir.path(&format!("turned{degrees:e}.obj"));
            bspcsg::write_mesh(&b, &turned.to_mesh(), &[]).unwrap();
            let out = dir.path(&format!("out{degrees:e}.obj"));
            let run = bspcsg_to(&["difference".as_ref(), a.as_os_str(), b.as_os_str()], &out);
            let want = first_order_volume(axis, degrees);
            right_or_refused(run, &out, &what, |report| {
                assert!(
                    (report.volume - want).abs() <= slack(want),
                    "{what}: {report} want {want:e}"
                );
            });
        }
    }
}
