#!/bin/sh
# One run of the literature's path-synthesis cases by kinloop and its two peers, on this machine,
# one after the other (BENCHMARKS.md, "Synthesis: the literature's cases beside pylinkage and
# four-bar"). PYTHON: a Python with pylinkage 1.3.0 installed (a virtual environment outside
# the repository). Run from the repository root.
set -e
PYTHON=${PYTHON:-python3}
nproc
cargo build --release -p kinloop-bench --bin literature
cargo build --release --manifest-path benches/peers/four-bar/Cargo.toml --target-dir target
target/release/literature "${KINLOOP_STARTS:-1024}" 1
target/release/four-bar-peer "${FOUR_BAR_RUNS:-5}"
"$PYTHON" benches/peers/pylinkage/cases.py
