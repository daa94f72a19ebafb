//! Make a part from primitives, check it, and write it.
//!
//! A block with a boss on top, drilled through by a row of holes: primitives, rigid motions,
//! the boolean operators, and a mesh that is a closed 2-manifold, written as glTF and OBJ.
//!
//! ```text
//! cargo run --release --example drill_part -- [OUT_DIR]      (default: out/)
//! ```

use std::path::PathBuf;

use bspcsg::glam::DVec3;
use bspcsg::{Solid, segments_for_tolerance, write_mesh};

fn main() -> Result<(), bspcsg::Error> {
    let out = PathBuf::from(std::env::args().nth(1).unwrap_or_else(|| "out".into()));

    // Primitives are centred at the origin; cylinders run along Y.
    let block = Solid::cuboid(DVec3::new(6.0, 1.0, 2.0))?;
    let boss = Solid::cylinder(0.8, 1.0, 64)?.translate(DVec3::new(0.0, 0.75, 0.0))?;

    // Segment counts from a chordal tolerance: no facet strays more than 0.5 mm from the circle.
    let r = 0.3;
    let segments = segments_for_tolerance(r, 0.0005)?;
    let drill = Solid::cylinder(r, 4.0, segments)?;
    let holes = Solid::union_all(
        [-2.0, 2.0]
            .into_iter()
            .map(|x| drill.clone().translate(DVec3::new(x, 0.0, 0.0)))
            .collect::<Result<Vec<_>, _>>()?,
    );
    let bore = Solid::cylinder(0.4, 4.0, 64)?;

    // `|` union, `&` intersection, `-` difference; each takes references or values.
    let part = (&block | &boss) - &holes - &bore;
    println!(
        "part: {} polygons, volume {:.4} (block {:.4})",
        part.polygon_count(),
        part.volume(),
        block.volume()
    );

    // The mesh of a valid solid is a closed, oriented 2-manifold: check it anyway.
    let mesh = part.to_mesh();
    let report = mesh.report();
    println!("mesh: {report}");
    assert!(report.is_closed_manifold());
    assert_eq!(report.genus, Some(3), "three holes through one body");

    std::fs::create_dir_all(&out).map_err(|source| bspcsg::Error::Io {
        path: out.clone(),
        source,
    })?;
    for name in ["part.glb", "part.obj"] {
        // The format follows the extension; writes are atomic.
        write_mesh(out.join(name), &mesh, &[])?;
        println!("wrote {}", out.join(name).display());
    }
    Ok(())
}
