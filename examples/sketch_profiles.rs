//! Draw 2D profiles, combine them, and turn them into solids.
//!
//! A flanged plate drawn as a sketch (a rounded rectangle minus bolt holes and a slot), extruded;
//! a twisted, tapered hexagonal column; and a pulley turned from a half profile about the y
//! axis. Every sketch and solid is checked, and the three are written as one glTF file.
//!
//! ```text
//! cargo run --release --example sketch_profiles -- [OUT_DIR]      (default: out/)
//! ```

use std::path::PathBuf;

use bspcsg::glam::{DVec2, DVec3};
use bspcsg::{ExtrudeOptions, Sketch, Solid, write_mesh};

fn main() -> Result<(), bspcsg::Error> {
    let out = PathBuf::from(std::env::args().nth(1).unwrap_or_else(|| "out".into()));

    // Sketches are centred at the origin of the xy plane; round ones take a chordal tolerance.
    let tol = 1e-3;
    let plate = Sketch::rounded_rectangle(4.0, 2.0, 0.4, tol)?;
    let bolt = Sketch::circle(0.2, tol)?;
    let holes = Sketch::union_all(
        [(-1.5, -0.6), (1.5, -0.6), (1.5, 0.6), (-1.5, 0.6)]
            .into_iter()
            .map(|(x, y)| bolt.translate(DVec2::new(x, y)))
            .collect::<Result<Vec<_>, _>>()?,
    );
    let slot = Sketch::rounded_rectangle(1.6, 0.5, 0.25, tol)?;
    // `|` union, `&` intersection, `-` difference, as for solids.
    let flange = &(&plate - &holes) - &slot;
    let report = flange.report();
    assert!(report.is_valid(), "{report:?}");
    println!(
        "flange: {} region(s), {} holes, area {:.5}, perimeter {:.5}",
        flange.regions().len(),
        flange.regions()[0].holes().len(),
        flange.area(),
        flange.perimeter()
    );
    let flange = flange.extrude(0.3)?;

    // A hexagon with a bore, turned 90° and narrowed to 60% over its height.
    let hexagon = &Sketch::regular_polygon(6, 0.8)? - &Sketch::circle(0.3, tol)?;
    let column = hexagon
        .extrude_with(
            3.0,
            &ExtrudeOptions {
                twist: 90.0,
                scale_top: DVec2::splat(0.6),
                ..Default::default()
            },
        )?
        .translate(DVec3::new(3.5, 0.0, 0.0))?;

    // A pulley: the half profile (x is the distance from the axis) turned a full circle about y.
    let rim = Sketch::rectangle(0.6, 0.8)?.translate(DVec2::new(1.2, 0.0))?;
    let groove = Sketch::circle(0.25, tol)?.translate(DVec2::new(1.5, 0.0))?;
    let web = Sketch::rectangle(1.2, 0.3)?.translate(DVec2::new(0.6, 0.0))?;
    let profile = &(&rim - &groove) | &web;
    let segments = bspcsg::segments_for_tolerance(1.5, tol)?;
    let pulley = profile
        .revolve(360.0, segments)?
        .translate(DVec3::new(-3.5, 0.0, 0.0))?;

    let all = Solid::union_all([flange, column, pulley]);
    let mesh = all.to_mesh();
    let report = mesh.report();
    println!("mesh: {report}");
    assert!(report.is_closed_manifold());

    std::fs::create_dir_all(&out).map_err(|source| bspcsg::Error::Io {
        path: out.clone(),
        source,
    })?;
    let path = out.join("sketch_profiles.glb");
    write_mesh(&path, &mesh, &[])?;
    println!("wrote {}", path.display());
    Ok(())
}
