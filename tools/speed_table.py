#!/usr/bin/env python3
"""bspcsg against manifold3d on the same OBJ files, interleaved in one session.

usage: speed_table.py INPUT_DIR [--rounds R] [--only SUBSTRING] [--large] [--bench-obj PATH]
                     [--boolmesh PATH]
       speed_table.py --manifold union|intersection|difference A.obj B.obj [--runs N]

Run it through tools/speed_table.sh, which builds the tools and writes the inputs. For each case
it starts, R times and alternating which goes first, one process of bspcsg's `bench_obj` (boolean
and boolean + `to_mesh`, the closed mesh a user gets) and one of this script in `--manifold`
mode (manifold3d's boolean with evaluation forced; its result is already a mesh). Each process
loads its inputs outside the timed region, warms up once and times a few runs; the table pools
every timed run of every round. Peak memory is each process's maximum resident set (from
wait4), input loading included; the manifold3d process also holds the Python interpreter and
numpy (about 40 MB before any mesh is read).

With `--boolmesh PATH` (tools/boolmesh_bench, which speed_table.sh builds when it can), a third
process per round times boolmesh, the Rust port of manifold's boolean, on the same files (its
result is a mesh too; taking out its flat position and index arrays is inside the timing), and
the table gains its columns; the three take turns going first.

Prints a markdown table: medians, the spread (min–max) and the ratio of our closed mesh to
manifold3d, output triangle counts and volumes of both.
"""
import json
import os
import statistics
import sys
import time

# label, op, files, timed runs per process (large cases fewer)
CASES = [
    ("UV sphere 64×32 ∪ copy moved 0.5", "union", ["sphere64_a", "sphere64_b"], 5),
    ("sphere 128×64 ∪ moved", "union", ["sphere128_a", "sphere128_b"], 5),
    ("sphere 256×128 ∪ moved", "union", ["sphere256_a", "sphere256_b"], 3),
    ("sphere 512×256 ∪ moved", "union", ["sphere512_a", "sphere512_b"], 2),
    ("sphere 128×64 ∩ moved", "intersection", ["sphere128_a", "sphere128_b"], 5),
    ("cube(2) − sphere 128×64", "difference", ["cube2", "sphere128_a"], 5),
    ("block − 10×10 cylinders (32 segments)", "difference", ["block", "holes"], 5),
    ("Menger sponge depth 3 (cube − union of its bars)", "difference", ["menger_cube", "menger_bars3"], 5),
    ("spot ∪ spot moved (0.3, 0.1, 0.2)", "union", ["spot_a", "spot_b"], 5),
    ("fandisk − fandisk moved (0.5, 0.5, 0.25)", "difference", ["fandisk_a", "fandisk_b"], 5),
    ("rocker-arm ∪ rocker-arm moved (0.05, 0.02, 0.01)", "union", ["rocker-arm_a", "rocker-arm_b"], 5),
]
LARGE = ("1M triangles: sphere 1024×512 ∪ moved", "union", ["sphere1024_a", "sphere1024_b"], 1)


def read_obj(path):
    import numpy as np

    verts, tris = [], []
    with open(path) as src:
        for line in src:
            parts = line.split()
            if not parts:
                continue
            if parts[0] == "v":
                verts.append([float(x) for x in parts[1:4]])
            elif parts[0] == "f":
                idx = [int(t.split("/")[0]) for t in parts[1:]]
                idx = [i - 1 if i > 0 else len(verts) + i for i in idx]
                tris += [[idx[0], idx[k], idx[k + 1]] for k in range(1, len(idx) - 1)]
    return np.array(verts, dtype=np.float32), np.array(tris, dtype=np.uint32)


def manifold_mode(argv):
    """Times manifold3d as ../shared/bench/manifold_reference.py does, printing every run."""
    import manifold3d as m3

    runs = 5
    if "--runs" in argv:
        i = argv.index("--runs")
        runs = int(argv[i + 1])
        argv = argv[:i] + argv[i + 2:]
    op, paths = argv[0], argv[1:]
    solids = []
    for p in paths:
        v, f = read_obj(p)
        m = m3.Manifold(m3.Mesh(vert_properties=v, tri_verts=f))
        if m.status() != m3.Error.NoError:
            print(f"manifold3d refuses {p}: {m.status()}", file=sys.stderr)
            return 1
        solids.append(m)
    combine = {"union": lambda a, b: a + b, "difference": lambda a, b: a - b,
               "intersection": lambda a, b: a ^ b}[op]
    times, out = [], None
    for _ in range(runs + 1):  # the first run warms up and is not counted
        t0 = time.perf_counter()
        out = solids[0]
        for s in solids[1:]:
            out = combine(out, s)
        out.num_tri()  # forces evaluation: manifold3d is lazy
        times.append((time.perf_counter() - t0) * 1e3)
    print(json.dumps(dict(output_triangles=out.num_tri(), volume=out.volume(), ms=times[1:])))
    return 0


def run_measured(cmd):
    """Runs a command to its end; returns its last JSON line and its peak resident set in MB."""
    pid = os.posix_spawn(cmd[0], cmd, os.environ, file_actions=[
        (os.POSIX_SPAWN_OPEN, 1, OUT_PATH, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o644),
    ])
    _, status, usage = os.wait4(pid, 0)
    with open(OUT_PATH) as f:
        text = f.read()
    if os.waitstatus_to_exitcode(status) != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed: {text}")
    line = [ln for ln in text.splitlines() if ln.startswith("{")][-1]
    return json.loads(line), usage.ru_maxrss / 1024.0


OUT_PATH = None


def fmt_ms(v):
    return f"{v:.1f}" if v >= 10 else f"{v:.2f}"


def spread(v):
    return f"{fmt_ms(min(v))}–{fmt_ms(max(v))}"


def main(argv):
    global OUT_PATH
    if argv and argv[0] == "--manifold":
        return manifold_mode(argv[1:])
    if not argv or argv[0].startswith("--"):
        print(__doc__, file=sys.stderr)
        return 2
    dir_ = argv[0]
    rounds, only, large, boolmesh = 3, None, False, None
    # speed_table.sh builds it with the `fast` profile (one codegen unit, fat LTO).
    bench_obj = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "target", "fast",
                             "examples", "bench_obj")
    i = 1
    while i < len(argv):
        if argv[i] == "--rounds":
            rounds, i = int(argv[i + 1]), i + 2
        elif argv[i] == "--only":
            only, i = argv[i + 1], i + 2
        elif argv[i] == "--bench-obj":
            bench_obj, i = argv[i + 1], i + 2
        elif argv[i] == "--boolmesh":
            boolmesh, i = argv[i + 1], i + 2
        elif argv[i] == "--large":
            large, i = True, i + 1
        else:
            print(f"unknown argument {argv[i]}", file=sys.stderr)
            return 2
    OUT_PATH = os.path.join(dir_, ".speed_table_out.json")
    cases = CASES + ([LARGE] if large else [])
    if only:
        cases = [c for c in cases if only.lower() in c[0].lower()]
    rows = []
    for label, op, names, runs in cases:
        files = [os.path.join(dir_, n + ".obj") for n in names]
        missing = [f for f in files if not os.path.exists(f)]
        if missing:
            print(f"skipped {label}: missing {', '.join(missing)}", file=sys.stderr)
            continue
        ours_cmd = [bench_obj, op, *files, "--runs", str(runs)]
        theirs_cmd = [sys.executable, os.path.abspath(__file__), "--manifold", op, *files, "--runs", str(runs)]
        boolean, closed, m3, bm = [], [], [], []
        ours_mem, m3_mem, bm_mem = 0.0, 0.0, 0.0
        ours_last = m3_last = bm_last = None
        for r in range(rounds):
            order = [("ours", ours_cmd), ("m3", theirs_cmd)]
            if boolmesh:
                order.append(("bm", [boolmesh, op, *files, "--runs", str(runs)]))
                order = order[r % 3:] + order[:r % 3]
            elif r % 2:
                order.reverse()
            for who, cmd in order:
                out, mem = run_measured(cmd)
                if who == "ours":
                    boolean += out["boolean_ms"]
                    closed += out["with_mesh_ms"]
                    ours_mem, ours_last = max(ours_mem, mem), out
                elif who == "bm":
                    bm += out["ms"]
                    bm_mem, bm_last = max(bm_mem, mem), out
                else:
                    m3 += out["ms"]
                    m3_mem, m3_last = max(m3_mem, mem), out
        row = dict(label=label, input_triangles=ours_last["input_triangles"],
                   boolean=statistics.median(boolean), closed=statistics.median(closed),
                   closed_spread=spread(closed), m3=statistics.median(m3), m3_spread=spread(m3),
                   ours_tris=ours_last["output_triangles"], m3_tris=m3_last["output_triangles"],
                   ours_volume=ours_last["volume"], m3_volume=m3_last["volume"],
                   closed_manifold=ours_last["closed_manifold"], ours_mb=ours_mem, m3_mb=m3_mem,
                   samples=len(closed))
        if boolmesh:
            row.update(bm=statistics.median(bm), bm_spread=spread(bm), bm_mb=bm_mem,
                       bm_tris=bm_last["output_triangles"], bm_volume=bm_last["volume"],
                       bm_closed=bm_last["closed_manifold"])
        rows.append(row)
        print(f"{label}: ours {fmt_ms(row['closed'])} ms, manifold3d {fmt_ms(row['m3'])} ms, "
              f"{row['closed'] / row['m3']:.2f}×"
              + (f", boolmesh {fmt_ms(row['bm'])} ms" if boolmesh else ""), file=sys.stderr, flush=True)
    print("| case | triangles in | ours, boolean | ours, closed mesh (spread) | manifold3d (spread) "
          "| ratio (closed) | triangles out, ours / manifold3d | volume, ours / manifold3d | peak MB, ours / manifold3d |"
          + (" boolmesh (spread) | ratio to boolmesh | boolmesh: triangles out, volume, peak MB |" if boolmesh else ""))
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|" + ("---:|---:|---:|" if boolmesh else ""))
    for r in rows:
        closed_note = "" if r["closed_manifold"] else " (not closed!)"
        print(f"| {r['label']} | {r['input_triangles']:,} | {fmt_ms(r['boolean'])} | "
              f"{fmt_ms(r['closed'])} ({r['closed_spread']}){closed_note} | {fmt_ms(r['m3'])} ({r['m3_spread']}) | "
              f"{r['closed'] / r['m3']:.2f}× | {r['ours_tris']:,} / {r['m3_tris']:,} | "
              f"{r['ours_volume']:.6g} / {r['m3_volume']:.6g} | {r['ours_mb']:.0f} / {r['m3_mb']:.0f} |"
              + (f" {fmt_ms(r['bm'])} ({r['bm_spread']}){'' if r['bm_closed'] else ' (not closed!)'} | "
                 f"{r['closed'] / r['bm']:.2f}× | {r['bm_tris']:,}, {r['bm_volume']:.6g}, {r['bm_mb']:.0f} |"
                 if boolmesh else ""))
    print(f"\nTimes in ms: medians over {rounds} interleaved rounds of each side's timed runs "
          "(after one warm-up run per process); spread is min–max."
          + (" Ratio to boolmesh: our closed mesh over boolmesh's." if boolmesh else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
