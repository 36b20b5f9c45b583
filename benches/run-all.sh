#!/usr/bin/env bash
# One run of every benchmark BENCHMARKS.md reports, on the code as it is checked out, each
# result in a file of OUTDIR (default `target/bench-run`), in the order that keeps the timings
# apart from the builds: first every build, then the instruction counts (which do not depend on
# the host's load), then the CPU times in paired rounds, then criterion. Nothing else should run
# on the host meanwhile: a build beside the paired rounds widens their ranges (the report then
# says which pairs were run again).
#
#   benches/run-all.sh                 # about 20 minutes on a 2-core host once built
#   benches/run-all.sh /tmp/run        # the files elsewhere
#
# The files: `commit` (what was measured), `callgrind.txt` (benches/callgrind.sh), `model.txt`
# (model/callgrind.sh), `breakdown.txt` (benches/breakdown.sh: instructions by source file),
# `cputime-*.txt` (benches/cputime.sh), `criterion-*.txt` (cargo bench's
# output; the medians are in the target directory's `criterion/`), `tables.md` (the report
# binary's tables from both), `drift.txt` (the sweeps' drift from the libm path).
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="${1:-$root/target/bench-run}"
mkdir -p "$out"
cd "$root"

git rev-parse HEAD >"$out/commit"
git status --porcelain | grep -q . && echo "run-all.sh: uncommitted changes: the run is of the working tree" >&2

echo "run-all.sh: building" >&2
cargo build --quiet --release -p kinloop-bench --bin closed_form_step --bin report --bin step_count
cargo bench --quiet --no-run -p kinloop-bench --bench step --bench expand
cargo bench --quiet --no-run -p kinloop-model --bench step
cargo test --quiet --no-run --test sweeps

echo "run-all.sh: instruction counts" >&2
benches/callgrind.sh >"$out/callgrind.txt"
model/callgrind.sh >"$out/model.txt"
benches/breakdown.sh sweep four-bar-sweep gear-lever-sweep point four-bar-point gear-lever-point \
  kernel-lane four-bar-kernel-lane gear-lever-kernel-lane four-bar-lane-sketch four-bar-lane-lean \
  four-bar-hand-sweep-checked hand four-bar-hand gear-lever-hand ring-point >"$out/breakdown.txt"

echo "run-all.sh: CPU time in paired rounds" >&2
benches/cputime.sh 15 hand:point:20000000 four-bar-hand:four-bar-point:20000000 \
  gear-lever-hand:gear-lever-point:20000000 >"$out/cputime-point.txt"
benches/cputime.sh 15 hand:sweep:20000000 four-bar-hand:four-bar-sweep:20000000 \
  gear-lever-hand:gear-lever-sweep:20000000 >"$out/cputime-sweep.txt"
benches/cputime.sh 9 hand:sweep-for:20000000 four-bar-hand:four-bar-sweep-for:20000000 \
  gear-lever-hand:gear-lever-sweep-for:20000000 >"$out/cputime-sweep-for.txt"
benches/cputime.sh 9 hand:hand-sweep-checked:20000000 four-bar-hand:four-bar-hand-sweep-checked:20000000 \
  gear-lever-hand:gear-lever-hand-sweep-checked:20000000 hand:kernel-lane:20000000 \
  four-bar-hand:four-bar-kernel-lane:20000000 gear-lever-hand:gear-lever-kernel-lane:20000000 \
  four-bar-hand:four-bar-lane-sketch:20000000 four-bar-hand:four-bar-lane-lean:20000000 >"$out/cputime-lanes.txt"
benches/cputime.sh 7 class-four-hand:class-four-point:1000000 class-four-hand-near:class-four-point:1000000 \
  series-point:ring-point:100000 >"$out/cputime-newton.txt"

echo "run-all.sh: criterion" >&2
cargo bench --quiet -p kinloop-bench --bench step -- 'closed_form_|ring_720|sensitivities_four_bar' \
  >"$out/criterion-step.txt" 2>&1
cargo bench --quiet -p kinloop-model --bench step >"$out/criterion-model.txt" 2>&1
cargo bench --quiet -p kinloop-bench --bench expand >"$out/criterion-expand.txt" 2>&1

echo "run-all.sh: drift and tables" >&2
cargo test --quiet --test sweeps drift -- --include-ignored --nocapture >"$out/drift.txt" 2>&1
cargo run --quiet --release -p kinloop-bench --bin report -- --callgrind "$out/callgrind.txt" >"$out/tables.md"
echo "run-all.sh: done, in $out" >&2
