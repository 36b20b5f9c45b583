#!/usr/bin/env bash
# Instructions per kinematic step, compiled against read at run time, under callgrind: runs
# `step_count VARIANT N` at N = 4000 and N = 8000 steps and prints, per variant,
# `VARIANT INSTRUCTIONS_PER_STEP` = (total at 8000 - total at 4000) / 4000 (the setup, reading
# and planning included, cancels: up to about 60,000 instructions from one run to the next,
# the hash tables' random seeds, which is 15 a step at this difference; the ring, whose steps
# are large, at 400 and 800).
#
#   model/callgrind.sh                       # every variant
#   model/callgrind.sh rhombic-runtime       # only these
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
target="${CARGO_TARGET_DIR:-$root/target}"
bin="$target/release/examples/step_count"
if [ "$#" -gt 0 ]; then
  variants=("$@")
else
  variants=(rhombic-compiled rhombic-runtime four-bar-compiled four-bar-runtime class-four-compiled class-four-runtime ring-compiled ring-runtime)
fi
command -v valgrind >/dev/null || { echo "callgrind.sh: valgrind is not installed" >&2; exit 1; }
(cd "$root" && cargo build --quiet --release -p kinloop-model --example step_count) >&2

total() {
  valgrind --tool=callgrind --callgrind-out-file=/dev/null "$bin" "$1" "$2" 2>&1 |
    sed -n 's/.*Collected : *\([0-9][0-9]*\).*/\1/p'
}

echo "# step_count instructions per step: (total at 8000 - total at 4000) / 4000 (the ring: 800 and 400), $(valgrind --version)"
for v in "${variants[@]}"; do
  n=4000
  case "$v" in ring-*) n=400 ;; esac
  a="$(total "$v" "$n")"
  b="$(total "$v" "$((2 * n))")"
  echo "$v $(( (b - a) / n ))"
done
