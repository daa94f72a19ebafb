//! Times a boolean on OBJ inputs, the way `../shared/bench/manifold_reference.py` times
//! manifold3d on the same files, so speed claims are ratios measured in one session.
//!
//! usage: cargo run --release --example bench_obj -- union|intersection|difference A.obj B.obj
//!        [C.obj ...] [--runs N] [--one-pool]
//!
//! `tools/speed_table.sh` builds it with `--profile fast` (one codegen unit, fat LTO: about 3 %
//! fewer instructions than `--release`); compare like with like, before and after a change.
//!
//! `--one-pool` runs everything inside a one-thread rayon pool, so a profiler that counts per
//! thread (callgrind) sees the `par_iter` work under its callers: without it, that work runs on
//! the pool's worker threads and every parallel stage reads as nearly free.
//!
//! Prints one JSON line: op, input and output triangles, the output's volume and whether it is
//! a closed 2-manifold, the time to make the solids of all inputs from their meshes (once,
//! files already read: `load_ms`, so a one-shot load, boolean and mesh can be quoted), the median and minimum over the runs (after one warm-up) of the boolean
//! alone and of the boolean plus `to_mesh` (manifold3d's result is already a mesh), and every
//! run's times (`tools/speed_table.sh` pools them across rounds).

use std::time::Instant;

use bspcsg::{BoolOp, Solid, read_mesh};

const USAGE: &str =
    "usage: bench_obj union|intersection|difference A.obj [B.obj ...] [--runs N] [--one-pool]";

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    if let Some(i) = args.iter().position(|a| a == "--one-pool") {
        args.remove(i);
        let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build()?;
        // The error is made a String inside: the boxed error is not `Send`.
        return Ok(pool.install(|| run(args).map_err(|e| e.to_string()))?);
    }
    run(args)
}

fn run(mut args: Vec<String>) -> Result<(), Box<dyn std::error::Error>> {
    let mut runs = 9usize;
    if let Some(i) = args.iter().position(|a| a == "--runs") {
        runs = args.get(i + 1).ok_or("--runs needs a number")?.parse()?;
        args.drain(i..i + 2);
    }
    let op = match args.first().map(String::as_str) {
        Some("union") => BoolOp::Union,
        Some("intersection") => BoolOp::Intersection,
        Some("difference") => BoolOp::Difference,
        _ => return Err(USAGE.into()),
    };
    if args.len() < 2 {
        return Err(USAGE.into());
    }
    let meshes = args[1..]
        .iter()
        .map(read_mesh)
        .collect::<Result<Vec<_>, _>>()?;
    let triangles_in: usize = meshes.iter().map(|m| m.triangle_count()).sum();
    let t0 = Instant::now();
    let solids = meshes
        .iter()
        .map(Solid::from_mesh)
        .collect::<Result<Vec<_>, _>>()?;
    let load_ms = t0.elapsed().as_secs_f64() * 1e3;
    drop(meshes);
    // The first boolean reads both inputs in place, as the reference's `out = solids[0]` does:
    // no copy of an input is timed.
    let combine = || match solids.as_slice() {
        [first, second, rest @ ..] => rest
            .iter()
            .fold(bspcsg::boolean(first, second, op), |out, s| {
                bspcsg::boolean(&out, s, op)
            }),
        _ => solids[0].clone(),
    };
    let (mut boolean_ms, mut total_ms) = (Vec::new(), Vec::new());
    let mut last = bspcsg::Mesh::default();
    for run in 0..=runs {
        let t0 = Instant::now();
        let result = combine();
        let t1 = Instant::now();
        let mesh = result.to_mesh();
        let t2 = Instant::now();
        if run > 0 {
            boolean_ms.push((t1 - t0).as_secs_f64() * 1e3);
            total_ms.push((t2 - t0).as_secs_f64() * 1e3);
        }
        last = mesh;
    }
    let list = |v: &[f64]| {
        v.iter()
            .map(|t| format!("{t:.3}"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let (boolean_all, total_all) = (list(&boolean_ms), list(&total_ms));
    let median = |v: &mut Vec<f64>| {
        v.sort_by(f64::total_cmp);
        (v[v.len() / 2], v[0])
    };
    let (b_med, b_min) = median(&mut boolean_ms);
    let (t_med, t_min) = median(&mut total_ms);
    println!(
        "{{\"op\": \"{}\", \"input_triangles\": {triangles_in}, \"output_triangles\": {}, \
         \"volume\": {:.9e}, \"closed_manifold\": {}, \"load_ms\": {load_ms:.3}, \
         \"boolean_median_ms\": {b_med:.3}, \"boolean_min_ms\": {b_min:.3}, \
         \"with_mesh_median_ms\": {t_med:.3}, \"with_mesh_min_ms\": {t_min:.3}, \"runs\": {runs}, \
         \"boolean_ms\": [{boolean_all}], \"with_mesh_ms\": [{total_all}]}}",
        args[0],
        last.triangle_count(),
        last.volume(),
        last.report().is_closed_manifold(),
    );
    Ok(())
}
