#!/usr/bin/env bash
# The speed comparison in one command: builds bspcsg's `bench_obj` (profile `fast`) and
# `write_bench_inputs`, writes the inputs (with BSPCSG_MODELS set, the real-model cases too),
# makes the Python venv with manifold3d if there is none, and prints the markdown table of
# bspcsg (boolean + closed mesh) against manifold3d on the same files, interleaved (see
# tools/speed_table.py).
#
# usage: tools/speed_table.sh [--large] [--rounds R] [--only SUBSTRING] [--no-boolmesh]
#   --large  adds the 1M-triangle case (two 1024×512 spheres) with peak memory
#   --no-boolmesh  leaves out the boolmesh column. Otherwise tools/boolmesh_bench (a project of
#            its own; boolmesh is never a dependency of the library) is built offline into
#            target/boolmesh-bench, and the column is left out, with the build's error, when
#            that fails (`cargo fetch --manifest-path tools/boolmesh_bench/Cargo.toml` fetches
#            its crates once)
#   inputs go to target/speed-inputs (SPEED_INPUTS overrides)
set -euo pipefail
cd "$(dirname "$0")/.."
inputs="${SPEED_INPUTS:-target/speed-inputs}"
large=()
args=()
boolmesh=1
for a in "$@"; do
    case "$a" in
        --large) large=(--large); args+=("$a") ;;
        --no-boolmesh) boolmesh=0 ;;
        *) args+=("$a") ;;
    esac
done
if ((boolmesh)); then
    if log=$(cargo build --offline --release --quiet --manifest-path tools/boolmesh_bench/Cargo.toml \
        --target-dir target/boolmesh-bench 2>&1); then
        args+=(--boolmesh target/boolmesh-bench/release/boolmesh_bench)
    else
        echo "the boolmesh column is left out: its offline build failed:" >&2
        echo "$log" | tail -n 5 >&2
    fi
fi
# The table times the `fast` profile (Cargo.toml: one codegen unit, fat LTO), the tool's fastest
# build (`cargo install --path . --profile fast`). The inputs' writer is not timed: `release`,
# which the test command has usually built already.
cargo build --profile fast --quiet --example bench_obj
cargo build --release --quiet --example write_bench_inputs
target/release/examples/write_bench_inputs "$inputs" "${large[@]}"
if [[ ! -x .venv/bin/python ]]; then
    python3 -m venv .venv
    .venv/bin/pip install --quiet -r tests/crosscheck/requirements.txt
fi
exec .venv/bin/python tools/speed_table.py "$inputs" "${args[@]}"
