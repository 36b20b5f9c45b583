#!/usr/bin/env bash
# Instructions per kinematic step, compiled against read at run time, under callgrind: runs
# `step_count VARIANT N` (N = 4000 steps; the ring, whose steps are large, 400) counting only the
# instructions inside its harness functions (`compiled`, `runtime`: the steps and the harness's
# own accumulation, the same for both), and prints, per variant,
# `VARIANT INSTRUCTIONS_PER_STEP` = that count / N. Reading and planning a model are outside the
# count (their instructions differ by up to about 60,000 from one run to the next, with the hash
# tables' random seeds, which a difference of two runs would spread over the steps).
#
#   model/callgrind.sh                       # every variant
#   model/callgrind.sh rhombic-runtime       # only these
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
target="${CARGO_TARGET_DIR:-$root/target}"
bin="$target/release/step_count"
if [ "$#" -gt 0 ]; then
  variants=("$@")
else
  variants=(rhombic-compiled rhombic-runtime four-bar-compiled four-bar-runtime class-four-compiled class-four-runtime ring-compiled ring-runtime)
fi
command -v valgrind >/dev/null || { echo "callgrind.sh: valgrind is not installed" >&2; exit 1; }
(cd "$root" && cargo build --quiet --release -p kinloop-bench --bin step_count) >&2

total() {
  valgrind --tool=callgrind --callgrind-out-file=/dev/null \
    "--toggle-collect=*step_count::compiled*" "--toggle-collect=*step_count::runtime*" \
    "$bin" "$1" "$2" 2>&1 |
    sed -n 's/.*Collected : *\([0-9][0-9]*\).*/\1/p'
}

echo "# step_count instructions per step: the harness functions' count over N steps (N = 4000, the ring 400), $(valgrind --version)"
for v in "${variants[@]}"; do
  n=4000
  case "$v" in ring-*) n=400 ;; esac
  echo "$v $(( $(total "$v" "$n") / n ))"
done
