#!/usr/bin/env python3
"""Cross-check bspcsg's sketches (2D booleans, extrusions, revolutions) against manifold3d's
CrossSection, on the corpus that tools/crosscheck_sketch_corpus.rs writes.

usage: crosscheck_sketch.py CORPUS_DIR

  cargo run --release --example crosscheck_sketch_corpus -- DIR
  .venv/bin/python tests/crosscheck/crosscheck_sketch.py DIR      (.ci/extra-checks does this)

For every case the two operands' rings, exactly as our sketches held them, become manifold3d
CrossSections (non-zero fill: outer rings counter-clockwise, holes clockwise), the same boolean
runs there (`+`, `^`, `-`), and its result is extruded and revolved by manifold3d with the same
parameters ours used. Checks, each must hold:

  valid     our result passes Sketch::report (no crossings, zero-length edges, stray holes,
            collinear runs) and our extrusion and revolution are closed 2-manifolds
  area      |ours - ref| <= 1e-6 * (A_a + A_b)   (manifold3d's Clipper2 rounds coordinates to
            its precision, so the error scales with the inputs, not with a result that may be
            tiny or empty)
  extrude   |ours - ref| <= 1e-6 * max(ref, (A_a + A_b) * h), manifold3d's extrude of its own
            result with the same height and (uniform) top scale
  revolve   the same tolerance, manifold3d's revolve of its own result moved by the same shift,
            with as many steps over the angle as ours took (manifold3d spreads
            circular_segments over the swept angle; ours takes a full turn's share)

Prints one line per case and a summary; exits 1 on any mismatch.
"""
import json
import os
import sys

import manifold3d as m3
import numpy as np

REL = 1e-6


def section(rings):
    return m3.CrossSection([np.array(r, dtype=np.float64) for r in rings], m3.FillRule.NonZero)


def check(case):
    a, b = section(case["a"]), section(case["b"])
    ref = {"union": lambda: a + b, "intersection": lambda: a ^ b,
           "difference": lambda: a - b}[case["op"]]()
    ours = case["ours"]
    scale = a.area() + b.area()
    fails = []
    if not ours["valid"]:
        fails.append(f"invalid sketch {ours['report']}")
    d_area = abs(ours["area"] - ref.area())
    if d_area > REL * scale:
        fails.append(f"area {ours['area']:.12g} vs {ref.area():.12g}")
    d_ext = d_rev = 0.0
    if "extrude" in case:
        e = case["extrude"]
        top = e["scale_top"]
        v = m3.Manifold.extrude(ref, e["height"], 0, 0.0, (top, top)).volume()
        d_ext = abs(e["volume"] - v)
        if not e["closed"]:
            fails.append("extrusion not closed")
        if d_ext > REL * max(v, scale * e["height"]):
            fails.append(f"extrude volume {e['volume']:.12g} vs {v:.12g}")
        r = case["revolve"]
        moved = ref.translate((r["shift"], 0.0))
        v = m3.Manifold.revolve(moved, r["steps"], r["angle"]).volume()
        d_rev = abs(r["volume"] - v)
        if not r["closed"]:
            fails.append("revolution not closed")
        if d_rev > REL * max(v, 1.0):
            fails.append(f"revolve volume {r['volume']:.12g} vs {v:.12g}")
    return fails, d_area / scale, d_ext, d_rev


def main(argv):
    if len(argv) != 2:
        print(__doc__)
        return 2
    with open(os.path.join(argv[1], "manifest.json")) as src:
        manifest = json.load(src)
    print(f"corpus: {manifest['generator']}")
    cases = manifest["cases"]
    failed = 0
    worst = [0.0, 0.0, 0.0]
    extrusions = 0
    for case in cases:
        fails, da, de, dr = check(case)
        worst = [max(w, x) for w, x in zip(worst, (da, de, dr))]
        extrusions += "extrude" in case
        status = "FAIL " + "; ".join(fails) if fails else "ok"
        print(f"{case['id']:<52} area {case['ours']['area']:>10.6f}  dA/A {da:.1e}  "
              f"dV {de:.1e} / {dr:.1e}  {status}")
        failed += bool(fails)
    print(f"\n== sketch cross-check: {len(cases)} booleans ({extrusions} with extrusion and "
          f"revolution), {len(cases) - failed} pass, {failed} fail; worst relative area "
          f"{worst[0]:.1e}, worst volume differences {worst[1]:.1e} (extrude), "
          f"{worst[2]:.1e} (revolve)")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
