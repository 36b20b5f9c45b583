#!/usr/bin/env bash
# Paired rounds of CPU time per step of `closed_form_step`'s variants (the lean harness of
# `callgrind.sh`), for the time columns of BENCHMARKS.md on a shared, loaded host. Each argument
# `REF:CAND:STEPS` is a pair of variants (turns of 720 steps); in every round each variant runs
# at STEPS and STEPS/10 steps, and its time per step is the difference of the two runs' CPU
# times (user + system, as GNU time reports them) over the difference of their steps, so the
# setup cancels. CPU time, not wall time: the time a run waits for a core another build holds
# is not counted (what is left is the contention of the core's caches and the other hyper-thread).
# The pair's two variants run one after the other in every round (each first in every other
# round), so load that comes and goes weighs on both; the ratio is taken per round. Prints every round, then per pair the median
# and range of the ratio CAND / REF and the medians of the two times.
#
#   benches/cputime.sh 11 hand:point:5000000 gear-lever-hand:gear-lever-point:5000000
#   benches/cputime.sh 7 class-four-hand:class-four-point:500000 series-point:ring-point:20000
#
# GNU time reports CPU time in hundredths of a second: choose STEPS so that a run takes at least
# half a second (about 5,000,000 closed-form steps, 500,000 class IV steps, 20,000 ring steps).
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
target="${CARGO_TARGET_DIR:-$root/target}"
bin="$target/release/closed_form_step"
[ -x /usr/bin/time ] || { echo "cputime.sh: needs GNU time (/usr/bin/time)" >&2; exit 1; }
[ "$#" -ge 2 ] || { echo "usage: cputime.sh ROUNDS REF:CAND:STEPS..." >&2; exit 1; }
rounds="$1"
shift
(cd "$root" && cargo build --quiet --release -p kinloop-bench --bin closed_form_step) >&2

# CPU seconds (user + system) of `closed_form_step VARIANT STEPS 720`.
cpu() {
  /usr/bin/time -f "%U %S" -o /dev/stdout "$bin" "$1" "$2" 720 | awk 'END { print $1 + $2 }'
}

# Nanoseconds per step of VARIANT from runs of STEPS and STEPS/10 steps.
per_step() {
  local hi="$2" lo=$(($2 / 10)) a b
  b="$(cpu "$1" "$hi")"
  a="$(cpu "$1" "$lo")"
  awk -v a="$a" -v b="$b" -v n="$((hi - lo))" 'BEGIN { printf "%.2f", (b - a) / n * 1e9 }'
}

median() {
  sort -g | awk '{ v[NR] = $1 } END { if (NR % 2) print v[(NR + 1) / 2]; else printf "%.4f\n", (v[NR / 2] + v[NR / 2 + 1]) / 2 }'
}

declare -A refs cands ratios
for r in $(seq 1 "$rounds"); do
  for p in "$@"; do
    IFS=: read -r ref cand steps <<<"$p"
    # Each of the two first in every other round: neither always runs after the other.
    if ((r % 2)); then
      tr="$(per_step "$ref" "$steps")"
      tc="$(per_step "$cand" "$steps")"
    else
      tc="$(per_step "$cand" "$steps")"
      tr="$(per_step "$ref" "$steps")"
    fi
    q="$(awk -v a="$tr" -v b="$tc" 'BEGIN { printf "%.4f", b / a }')"
    echo "round $r: $ref $tr ns, $cand $tc ns, ratio $q"
    refs[$p]+="$tr "
    cands[$p]+="$tc "
    ratios[$p]+="$q "
  done
done
echo "# closed_form_step CPU time per step, $rounds paired rounds, 720 steps a turn"
for p in "$@"; do
  IFS=: read -r ref cand _ <<<"$p"
  q="$(tr ' ' '\n' <<<"${ratios[$p]}" | grep . | sort -g)"
  echo "$cand / $ref: median $(median <<<"$q") (range $(head -1 <<<"$q")-$(tail -1 <<<"$q")); $ref $(tr ' ' '\n' <<<"${refs[$p]}" | grep . | median) ns, $cand $(tr ' ' '\n' <<<"${cands[$p]}" | grep . | median) ns"
done
