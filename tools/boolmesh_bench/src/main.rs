//! Times boolmesh's boolean on OBJ inputs the way bspcsg's `tools/bench_obj.rs` times ours, for
//! the third column of `tools/speed_table.sh`.
//!
//! usage: boolmesh_bench union|intersection|difference A.obj B.obj [C.obj ...] [--runs N]
//!
//! Each input is read outside the timed region (positions as f64, faces fanned into
//! triangles, indices as written: no welding, as the manifold3d column reads them) and made a
//! `boolmesh::Manifold`. A run is the boolean of the inputs left to right (`compute_boolean`,
//! whose result is already a closed halfedge mesh) plus taking its positions and triangle
//! indices out as flat arrays, the mesh a caller gets. One warm-up run, then `--runs` timed.
//! Prints one JSON line: op, input and output triangles, the output's volume and whether every
//! edge is used once in each direction, the median and minimum, and every run's time.

use std::time::Instant;

use boolmesh::prelude::{Manifold, OpType, compute_boolean};

/// Positions (x, y, z flat) and triangle indices (flat) of an OBJ file: `v` and `f` lines,
/// `f` entries as `i`, `i/t`, `i//n` or `i/t/n`, negative indices relative, polygons fanned.
fn read_obj(path: &str) -> Result<(Vec<f64>, Vec<usize>), String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{path}: {e}"))?;
    let (mut pos, mut idx) = (Vec::new(), Vec::new());
    for (n, line) in text.lines().enumerate() {
        let bad = |what: &str| format!("{path}:{}: {what}", n + 1);
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => {
                for w in words.take(3) {
                    pos.push(w.parse::<f64>().map_err(|_| bad("a bad coordinate"))?);
                }
            }
            Some("f") => {
                let count = pos.len() / 3;
                let face = words
                    .map(|w| {
                        let i: i64 = w
                            .split('/')
                            .next()
                            .unwrap_or("")
                            .parse()
                            .map_err(|_| bad("a bad index"))?;
                        let i = if i < 0 { count as i64 + i } else { i - 1 };
                        usize::try_from(i)
                            .ok()
                            .filter(|&i| i < count)
                            .ok_or_else(|| bad("an index out of range"))
                    })
                    .collect::<Result<Vec<usize>, String>>()?;
                for k in 1..face.len().saturating_sub(1) {
                    idx.extend([face[0], face[k], face[k + 1]]);
                }
            }
            _ => {}
        }
    }
    Ok((pos, idx))
}

/// The signed volume of a triangle mesh (divergence theorem).
fn volume(pos: &[[f64; 3]], tris: &[usize]) -> f64 {
    tris.chunks_exact(3)
        .map(|t| {
            let [a, b, c] = [pos[t[0]], pos[t[1]], pos[t[2]]];
            let cross = [
                b[1] * c[2] - b[2] * c[1],
                b[2] * c[0] - b[0] * c[2],
                b[0] * c[1] - b[1] * c[0],
            ];
            a[0] * cross[0] + a[1] * cross[1] + a[2] * cross[2]
        })
        .sum::<f64>()
        / 6.0
}

/// Every directed edge used once and its reverse once: a closed, consistently wound
/// 2-manifold (by indices, as bspcsg's report counts it).
fn closed_manifold(tris: &[usize]) -> bool {
    let mut edges: std::collections::HashMap<(usize, usize), i32> = Default::default();
    for t in tris.chunks_exact(3) {
        for k in 0..3 {
            *edges.entry((t[k], t[(k + 1) % 3])).or_default() += 1;
        }
    }
    edges
        .iter()
        .all(|(&(a, b), &n)| n == 1 && edges.get(&(b, a)) == Some(&1))
}

fn main() -> Result<(), String> {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    let mut runs = 9usize;
    if let Some(i) = args.iter().position(|a| a == "--runs") {
        let n = args.get(i + 1).ok_or("--runs needs a number")?;
        runs = n
            .parse()
            .ok()
            .filter(|&r| r > 0)
            .ok_or_else(|| format!("--runs: `{n}` is not a positive number"))?;
        args.drain(i..i + 2);
    }
    let usage = "usage: boolmesh_bench union|intersection|difference A.obj B.obj [...] [--runs N]";
    let op = match args.first().map(String::as_str) {
        Some("union") => || OpType::Add,
        Some("intersection") => || OpType::Intersect,
        Some("difference") => || OpType::Subtract,
        _ => return Err(usage.into()),
    };
    if args.len() < 3 {
        return Err(usage.into());
    }
    let mut inputs = Vec::new();
    let mut triangles_in = 0;
    for path in &args[1..] {
        let (pos, idx) = read_obj(path)?;
        triangles_in += idx.len() / 3;
        inputs
            .push(Manifold::new(&pos, &idx).map_err(|e| format!("boolmesh refuses {path}: {e}"))?);
    }
    let mut times = Vec::new();
    let (mut out_pos, mut out_tris) = (Vec::new(), Vec::new());
    for run in 0..=runs {
        let t0 = Instant::now();
        let mut result = compute_boolean(&inputs[0], &inputs[1], op())?;
        for m in &inputs[2..] {
            result = compute_boolean(&result, m, op())?;
        }
        let pos: Vec<[f64; 3]> = result.ps.iter().map(|p| [p.x, p.y, p.z]).collect();
        let tris: Vec<usize> = result.hs.iter().map(|h| h.tail).collect();
        let t1 = Instant::now();
        if run > 0 {
            times.push((t1 - t0).as_secs_f64() * 1e3);
        }
        (out_pos, out_tris) = (pos, tris);
    }
    let all = times
        .iter()
        .map(|t| format!("{t:.3}"))
        .collect::<Vec<_>>()
        .join(", ");
    times.sort_by(f64::total_cmp);
    println!(
        "{{\"op\": \"{}\", \"input_triangles\": {triangles_in}, \"output_triangles\": {}, \
         \"volume\": {:.9e}, \"closed_manifold\": {}, \"median_ms\": {:.3}, \"min_ms\": {:.3}, \
         \"runs\": {runs}, \"ms\": [{all}]}}",
        args[0],
        out_tris.len() / 3,
        volume(&out_pos, &out_tris),
        closed_manifold(&out_tris),
        times[times.len() / 2],
        times[0],
    );
    Ok(())
}
