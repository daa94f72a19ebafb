//! Turn a scene document into meshes, both ways, and export them.
//!
//! A scene is a tree of signed distance functions in JSON (`docs/scene-format.md`). It meshes
//! by marching cubes (`Scene::bake`: smooth blends kept, any resolution) or by tessellating its
//! primitives and combining them with exact booleans (`Scene::to_solid`: flat faces stay flat).
//! Both carry the scene's materials on their source ids, which glTF writes as materials.
//!
//! ```text
//! cargo run --release --example bake_scene -- [SCENE.json] [OUT_DIR]
//!     (defaults: examples/scenes/mechanical_part.json, out/)
//! ```

use std::path::PathBuf;

use bspcsg::{BakeOptions, Scene, TessellationOptions, write_mesh};

fn main() -> Result<(), bspcsg::Error> {
    let mut args = std::env::args().skip(1);
    let scene_path = args
        .next()
        .unwrap_or_else(|| "examples/scenes/mechanical_part.json".into());
    let out = PathBuf::from(args.next().unwrap_or_else(|| "out".into()));

    // Faults name the file and the JSON path, e.g. `part.json: $.children[2].data.radius: …`.
    let scene = Scene::from_path(&scene_path)?;
    println!(
        "{scene_path}: {} primitives, {} materials, box {:?}",
        scene.primitive_count(),
        scene.materials().len(),
        scene.bbox()
    );

    // Marching cubes: the cell size sets the detail (here 1/160 of the box's longest side).
    let baked = scene.bake(&BakeOptions::with_resolution(160))?;
    // The BSP route: each primitive tessellated to a chordal tolerance, then exact booleans.
    let solid = scene.to_solid(&TessellationOptions::default())?;
    let tessellated = solid.to_mesh();

    std::fs::create_dir_all(&out).map_err(|source| bspcsg::Error::Io {
        path: out.clone(),
        source,
    })?;
    for (name, mesh) in [("baked.glb", &baked), ("tessellated.glb", &tessellated)] {
        let report = mesh.report();
        println!("{name}: {report}");
        write_mesh(out.join(name), mesh, scene.materials())?;
    }
    println!(
        "volumes: baked {:.4}, tessellated {:.4}",
        baked.volume(),
        tessellated.volume()
    );
    Ok(())
}
