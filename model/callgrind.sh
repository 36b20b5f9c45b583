#!/usr/bin/env bash
# Instructions per kinematic step, compiled against read at run time, under callgrind: runs
# `step_count VARIANT N` at N = 2000 and N = 4000 steps and prints, per variant,
# `VARIANT INSTRUCTIONS_PER_STEP` = (total at 4000 - total at 2000) / 2000 (the setup, reading
# and planning included, cancels).
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

echo "# step_count instructions per step: (total at 4000 - total at 2000) / 2000, $(valgrind --version)"
for v in "${variants[@]}"; do
  a="$(total "$v" 2000)"
  b="$(total "$v" 4000)"
  echo "$v $(( (b - a) / 2000 ))"
done
