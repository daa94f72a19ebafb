#!/usr/bin/env bash
# The speed comparison in one command: builds bspcsg's `bench_obj` and `write_bench_inputs`,
# writes the inputs (with BSPCSG_MODELS set, the real-model cases too), makes the Python venv
# with manifold3d if there is none, and prints the markdown table of bspcsg (boolean + closed
# mesh) against manifold3d on the same files, interleaved (see tools/speed_table.py).
#
# usage: tools/speed_table.sh [--large] [--rounds R] [--only SUBSTRING]
#   --large  adds the 1M-triangle case (two 1024×512 spheres) with peak memory
#   inputs go to target/speed-inputs (SPEED_INPUTS overrides)
set -euo pipefail
cd "$(dirname "$0")/.."
inputs="${SPEED_INPUTS:-target/speed-inputs}"
large=()
for a in "$@"; do [[ "$a" == --large ]] && large=(--large); done
cargo build --release --quiet --example bench_obj --example write_bench_inputs
target/release/examples/write_bench_inputs "$inputs" "${large[@]}"
if [[ ! -x .venv/bin/python ]]; then
    python3 -m venv .venv
    .venv/bin/pip install --quiet -r tests/crosscheck/requirements.txt
fi
exec .venv/bin/python tools/speed_table.py "$inputs" "$@"
