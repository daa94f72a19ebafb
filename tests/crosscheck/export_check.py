"""Reads every mesh file the command line exported with trimesh and checks it against
`bspcsg info --json` on the same file: the same triangle count, the same volume (relative
1e-6) and the same verdict on watertightness, which must be "watertight".

    .venv/bin/python tests/crosscheck/export_check.py DIR [--bspcsg target/release/bspcsg]
    .venv/bin/python tests/crosscheck/export_check.py DIR --volumes ours.json

DIR holds the exported .obj, .stl, .gltf and .glb files (companion .mtl and .bin files beside
them). Our figures come from running the binary on each file, or from a JSON file that maps
file names to `bspcsg info --json` objects. Prints a table; exits 1 on any mismatch and 2 when
there is nothing to check.
"""

import argparse
import json
import math
import subprocess
import sys
from pathlib import Path

import trimesh

EXTENSIONS = (".obj", ".stl", ".gltf", ".glb")
# STL and glTF store float32; both sides read the same float32 values and sum in float64,
# so they agree far closer than this. OBJ is f64 text on both sides.
VOLUME_RTOL = 1e-6


def ours_by_running(binary: Path, files: list[Path]) -> dict[str, dict]:
    out = {}
    for f in files:
        run = subprocess.run(
            [str(binary), "info", "--json", str(f)], capture_output=True, text=True
        )
        if run.returncode != 0:
            out[f.name] = {"error": run.stderr.strip() or f"exit {run.returncode}"}
        else:
            out[f.name] = json.loads(run.stdout)
    return out


def theirs(path: Path) -> trimesh.Trimesh:
    mesh = trimesh.load(str(path), force="mesh")
    # trimesh keeps vertices as stored, and the files repeat positions by design: glTF
    # vertices carry flat normals (one copy per face normal around a position) and each
    # material is its own primitive; trimesh loads OBJ `usemtl` groups as separate pieces.
    # Unmerged, every such seam looks open. Merge equal positions (trimesh's merge tolerance,
    # 1e-8) so that watertightness is judged on the geometry, as `bspcsg info` judges it.
    mesh.merge_vertices(merge_tex=True, merge_norm=True)
    return mesh


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("dir", type=Path, help="directory of exported mesh files")
    parser.add_argument(
        "--bspcsg",
        type=Path,
        default=Path("target/release/bspcsg"),
        help="the binary to run `info --json` with (default: %(default)s)",
    )
    parser.add_argument(
        "--volumes",
        type=Path,
        help="JSON object: file name -> `bspcsg info --json` output (instead of running it)",
    )
    args = parser.parse_args()

    files = sorted(p for p in args.dir.iterdir() if p.suffix.lower() in EXTENSIONS)
    if not files:
        print(f"export_check: no .obj/.stl/.gltf/.glb files in {args.dir}", file=sys.stderr)
        return 2
    if args.volumes:
        ours = json.loads(args.volumes.read_text())
    else:
        ours = ours_by_running(args.bspcsg, files)

    header = (
        f"{'file':<34} {'triangles':>9} {'our volume':>16} {'trimesh volume':>16} "
        f"{'rel diff':>9}  watertight  verdict"
    )
    print(header)
    print("-" * len(header))
    failures = 0
    for f in files:
        problems = []
        o = ours.get(f.name)
        if o is None or "error" in o:
            problems.append(f"bspcsg info failed: {o.get('error') if o else 'no entry'}")
            o = {}
        try:
            m = theirs(f)
            t_volume, t_tris = float(m.volume), len(m.faces)
            t_tight = bool(m.is_watertight and m.is_winding_consistent)
        except Exception as e:  # any failure to load is a failed check, reported in the table
            problems.append(f"trimesh cannot load it: {e}")
            t_volume, t_tris, t_tight = math.nan, -1, False
        o_volume = o.get("volume")
        o_tris = o.get("triangles")
        o_tight = o.get("watertight")
        if o_volume is None:
            rel = math.nan
        else:
            rel = abs(o_volume - t_volume) / max(abs(o_volume), 1e-300)
        if not rel <= VOLUME_RTOL:
            problems.append(f"volume differs by {rel:.2e} (> {VOLUME_RTOL:g})")
        if o_tris is not None and o_tris != t_tris:
            problems.append(f"triangles: ours {o_tris}, trimesh {t_tris}")
        if o_tight is not True or not t_tight:
            problems.append(f"watertight: ours {o_tight}, trimesh {t_tight}")
        verdict = "ok" if not problems else "FAIL"
        failures += bool(problems)
        vol = f"{o_volume:>16.9g}" if o_volume is not None else f"{'-':>16}"
        tight = f"{'yes' if o_tight else 'no'}/{'yes' if t_tight else 'no'}"
        print(
            f"{f.name:<34} {o_tris if o_tris is not None else '-':>9} {vol} "
            f"{t_volume:>16.9g} {rel:>9.1e}  {tight:<10}  {verdict}"
        )
        for p in problems:
            print(f"    {p}")
    print(f"export_check: {len(files) - failures} passed, {failures} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
