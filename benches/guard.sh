#!/usr/bin/env bash
# The instruction-count targets of BENCHMARKS.md that kinloop meets, held: each a ratio of two
# callgrind counts of the same harness (`benches/callgrind.sh`, `model/callgrind.sh`), which
# repeat to the instruction from run to run on any load (a count, not a time). Fails, naming the
# row, where a ratio exceeds its target; prints every ratio. CI runs it: a change that costs a
# met target its margin (the run-time model's rhombic drive went from 2.98x to 3.03x unnoticed
# through two changes) fails there, not in the next benchmark run.
#
#   benches/guard.sh
#
# The missed targets (the `Sweep` sample at 0.6x, the rhombic drive's point step at 1.3x in
# instructions) are not held here: they are reported in BENCHMARKS.md. One missed target is held
# at its measured ratio instead, so that it does not slip further unnoticed: the run-time
# rhombic drive against the compiled one (3x; 3.67x since the second crank arm's sine and cosine
# come by angle addition with `gamma`'s computed once: the compiled step fell from 1033 to 763
# instructions, the run-time one by as much, from 3083 to 2799, which raises the ratio). Needs
# valgrind.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
command -v valgrind >/dev/null || { echo "guard.sh: valgrind is not installed" >&2; exit 1; }

counts="$(bash "$root/benches/callgrind.sh" four-bar-hand four-bar-point gear-lever-hand gear-lever-point \
    class-four-hand class-four-point series-point ring-point four-bar-sens-point four-bar-sens)
$(bash "$root/model/callgrind.sh" rhombic-compiled rhombic-runtime four-bar-compiled four-bar-runtime \
    class-four-compiled class-four-runtime)"

failed=0
# hold ROW CANDIDATE REFERENCE TARGET: CANDIDATE's count over REFERENCE's at most TARGET.
hold() {
    local row=$1 candidate reference
    candidate=$(printf '%s\n' "$counts" | awk -v v="$2" '$1 == v { print $2 }')
    reference=$(printf '%s\n' "$counts" | awk -v v="$3" '$1 == v { print $2 }')
    if [ -z "$candidate" ] || [ -z "$reference" ]; then
        echo "guard.sh: no count for $2 or $3" >&2
        failed=1
        return
    fi
    if awk -v c="$candidate" -v r="$reference" -v t="$4" 'BEGIN { exit !(c <= t * r) }'; then
        verdict=held
    else
        verdict=EXCEEDED
        failed=1
    fi
    awk -v row="$row" -v c="$candidate" -v r="$reference" -v t="$4" -v v="$verdict" \
        'BEGIN { printf "%-58s %8d / %8d = %5.2fx (target %sx) %s\n", row, c, r, c / r, t, v }'
}

hold "four-bar point step against its hand closed form" four-bar-point four-bar-hand 1.3
hold "gear-lever point step against its hand closed form" gear-lever-point gear-lever-hand 1.3
hold "class IV point step against its hand Newton" class-four-point class-four-hand 1.3
hold "ring of 64 loops against the same loops in series" ring-point series-point 5
hold "four-bar sensitivity solve against its kinematic step" four-bar-sens four-bar-sens-point 3
hold "run-time rhombic drive against the compiled one (3x missed)" rhombic-runtime rhombic-compiled 3.7
hold "run-time four-bar against the compiled one" four-bar-runtime four-bar-compiled 3
hold "run-time class IV block against the compiled one" class-four-runtime class-four-compiled 3

exit "$failed"
