#!/usr/bin/env bash
# Instructions per step of the closed-form rows under callgrind, for `report --callgrind FILE`:
# runs `closed_form_step VARIANT N [TURN]` (turns of 720 steps unless `VARIANT@TURN` says
# another) under valgrind at two step counts and prints, per variant, one line
# `VARIANT INSTRUCTIONS_PER_STEP` = (total at high - total at low) / (high - low): the setup
# cancels. The two counts differ by whole turns (the cost of libm's functions depends on the
# angle, so a part of a turn would weigh some angles more than others): 3 and 6 turns of 720
# steps, 1 and 2 turns of 20,000; the turns of 10^6 steps are sampled over their first 2000
# steps (2000 and 4000), and the ring of 64 loops and its series, whose steps are large, over
# 200 and 400.
#
#   benches/callgrind.sh > callgrind.txt            # every variant of the report's tables
#   benches/callgrind.sh four-bar-hand point@1000000  # only these
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
  variants=(hand hand-libm-sum point sweep hand-sweep hand-sweep-checked
    four-bar-hand four-bar-point four-bar-sweep four-bar-hand-sweep four-bar-hand-sweep-checked
    gear-lever-hand gear-lever-point gear-lever-sweep gear-lever-hand-sweep gear-lever-hand-sweep-checked
    hand@20000 point@20000 sweep@20000 hand-sweep@20000 hand-sweep-checked@20000
    four-bar-hand@20000 four-bar-point@20000 four-bar-sweep@20000 four-bar-hand-sweep@20000
    four-bar-hand-sweep-checked@20000
    gear-lever-hand@20000 gear-lever-point@20000 gear-lever-sweep@20000
    gear-lever-hand-sweep@20000 gear-lever-hand-sweep-checked@20000
    kernel-lane four-bar-kernel-lane gear-lever-kernel-lane
    kernel-lane@20000 four-bar-kernel-lane@20000 gear-lever-kernel-lane@20000
    four-bar-lane-sketch four-bar-lane-sketch@20000 four-bar-lane-lean four-bar-lane-lean@20000
    sweep-for four-bar-sweep-for gear-lever-sweep-for
    class-four-hand class-four-hand-near class-four-point
    class-four-hand-taylor class-four-point-taylor class-four-sweep
    class-four-hand@1000000 class-four-point@1000000
    class-four-hand-taylor@1000000 class-four-point-taylor@1000000
    hand@1000000 point@1000000
    newton newton-sweep
    series-point ring-point
    four-bar-sens-point four-bar-sens four-bar-scan four-bar-sweep@99)
fi

command -v valgrind >/dev/null || { echo "callgrind.sh: valgrind is not installed" >&2; exit 1; }
(cd "$root" && cargo build --quiet --release -p kinloop-bench --bin closed_form_step) >&2

# Total instructions of `closed_form_step VARIANT STEPS TURN`, from callgrind's summary line.
total() {
  local out
  out="$(valgrind --tool=callgrind --callgrind-out-file=/dev/null "$bin" "$1" "$2" "$3" 2>&1)" || {
    echo "callgrind.sh: closed_form_step $1 $2 $3 failed:" >&2
    echo "$out" >&2
    return 1
  }
  echo "$out" | sed -n 's/.*Collected : *\([0-9][0-9]*\).*/\1/p'
}

# Warns when a hand closed form calls libm's `sin` or `cos` on its own: a split `f64::sin_cos`
# (LLVM merges the pair into `sincos` only within one basic block) costs the reference about 45
# instructions an angle and flatters every ratio against it (see BENCHMARKS.md, "The harness").
check_lean_reference() {
  local file
  file="$(mktemp)"
  valgrind --tool=callgrind --callgrind-out-file="$file" "$bin" "$1" "$low" "$2" >/dev/null 2>&1 || true
  if grep -Eq '^c?fn=.*__(sin|cos)_fma' "$file"; then
    echo "callgrind.sh: WARNING: $1 calls sin or cos on its own (a split sin_cos): its count is not the lean reference's" >&2
  fi
  rm -f "$file"
}

echo "# closed_form_step instructions per step: difference of the totals of two runs over the difference of their steps (whole turns up to 20,000 steps a turn; otherwise $low and $high steps, ring and series 200 and 400), 720 steps a turn unless VARIANT@TURN, $(valgrind --version)"
for v in "${variants[@]}"; do
  name="${v%@*}"
  turn=720
  [ "$name" != "$v" ] && turn="${v#*@}"
  lo=$low
  hi=$high
  if [ "$turn" -le 20000 ]; then
    # Whole turns: the smallest number of turns of at least `low` steps, and twice that.
    lo=$(((low + turn - 1) / turn * turn))
    hi=$((2 * lo))
  fi
  case "$name" in ring-* | series-*) lo=200 hi=400 ;; esac
  case "$name" in hand | hand-libm-sum | four-bar-hand | gear-lever-hand) check_lean_reference "$name" "$turn" ;; esac
  a="$(total "$name" "$lo" "$turn")"
  b="$(total "$name" "$hi" "$turn")"
  if [ -z "$a" ] || [ -z "$b" ]; then
    echo "callgrind.sh: no instruction count for $v" >&2
    exit 1
  fi
  awk -v v="$v" -v a="$a" -v b="$b" -v n="$((hi - lo))" 'BEGIN { printf "%s %.0f\n", v, (b - a) / n }'
done
