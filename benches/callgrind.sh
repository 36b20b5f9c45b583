#!/usr/bin/env bash
# Instructions per step of the closed-form rows under callgrind, for `report --callgrind FILE`:
# runs `closed_form_step VARIANT N` (turns of 720 steps, warm start = previous position) under
# valgrind at N = 2000 and N = 4000 steps and prints, per variant, one line
# `VARIANT INSTRUCTIONS_PER_STEP` = (total at 4000 - total at 2000) / 2000 (the setup cancels).
#
#   benches/callgrind.sh > callgrind.txt            # every variant of the report's table
#   benches/callgrind.sh four-bar-hand four-bar-point  # only these
#   cargo run --release -p kinloop-bench --bin report -- --callgrind callgrind.txt
#
# Needs valgrind (3.19 measured the figures of BENCHMARKS.md). Run it from anywhere; it builds
# the harness in release mode first, into $CARGO_TARGET_DIR or the workspace's target/.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
target="${CARGO_TARGET_DIR:-$root/target}"
bin="$target/release/closed_form_step"
low=2000
high=4000

if [ "$#" -gt 0 ]; then
  variants=("$@")
else
  variants=(hand point sweep
    four-bar-hand four-bar-point four-bar-sweep
    gear-lever-hand gear-lever-point gear-lever-sweep
    class-four-hand class-four-point)
fi

command -v valgrind >/dev/null || { echo "callgrind.sh: valgrind is not installed" >&2; exit 1; }
(cd "$root" && cargo build --quiet --release -p kinloop-bench --bin closed_form_step) >&2

# Total instructions of `closed_form_step VARIANT STEPS`, from callgrind's summary line.
total() {
  local out
  out="$(valgrind --tool=callgrind --callgrind-out-file=/dev/null "$bin" "$1" "$2" 2>&1)" || {
    echo "callgrind.sh: closed_form_step $1 $2 failed:" >&2
    echo "$out" >&2
    return 1
  }
  echo "$out" | sed -n 's/.*Collected : *\([0-9][0-9]*\).*/\1/p'
}

echo "# closed_form_step instructions per step: (total at $high - total at $low) / $((high - low)), 720 steps a turn, $(valgrind --version)"
for v in "${variants[@]}"; do
  a="$(total "$v" "$low")"
  b="$(total "$v" "$high")"
  if [ -z "$a" ] || [ -z "$b" ]; then
    echo "callgrind.sh: no instruction count for $v" >&2
    exit 1
  fi
  awk -v v="$v" -v a="$a" -v b="$b" -v n="$((high - low))" 'BEGIN { printf "%s %.0f\n", v, (b - a) / n }'
done
