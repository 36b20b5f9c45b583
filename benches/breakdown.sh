#!/usr/bin/env bash
# Where a step's instructions go, by source file: the breakdown tables of BENCHMARKS.md.
# Builds `closed_form_step` in release mode with line tables (into target/line-tables, apart
# from the plain build whose counts `callgrind.sh` reports), runs each variant under callgrind at
# two step counts, and prints, per variant, each source file's instructions per step (the
# difference of the file's totals over the difference of the steps: the setup cancels), largest
# first; libm's files are summed as `libm`. The step counts are `callgrind.sh`'s (whole turns:
# 3 and 6 of 720 steps, 1 and 2 of 20,000).
#
#   benches/breakdown.sh sweep four-bar-sweep gear-lever-sweep
#   benches/breakdown.sh point@20000
#
# Line tables move a few instructions (a total here is within a few of `callgrind.sh`'s for
# the same code); the tables say so where they stand.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
target="$root/target/line-tables"
bin="$target/release/closed_form_step"
[ "$#" -gt 0 ] || { echo "usage: benches/breakdown.sh VARIANT[@TURN]..." >&2; exit 2; }
command -v valgrind >/dev/null || { echo "breakdown.sh: valgrind is not installed" >&2; exit 1; }
(cd "$root" && CARGO_TARGET_DIR="$target" CARGO_PROFILE_RELEASE_DEBUG=line-tables-only \
  cargo build --quiet --release -p kinloop-bench --bin closed_form_step) >&2

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

# Self instructions per source file of `closed_form_step VARIANT STEPS TURN`, one
# `COUNT FILE` line each.
per_file() {
  valgrind --tool=callgrind --dump-instr=no --dump-line=yes --callgrind-out-file="$work/cg.out" \
    "$bin" "$1" "$2" "$3" >/dev/null 2>&1 || { echo "breakdown.sh: closed_form_step $1 $2 $3 failed" >&2; return 1; }
  callgrind_annotate --auto=no --inclusive=no --threshold=100 "$work/cg.out" | python3 -c '
import re, sys
root = sys.argv[1].rstrip("/") + "/"
totals = {}
for line in sys.stdin:
    # `COUNT (PERCENT)  FILE:FUNCTION [OBJECT]`; a file name has no colon, a function may.
    m = re.match(r"\s*([\d,]+)\s+(?:\([^)]*\)\s+)?([^:\s][^:]*):(.*?)\s*(\[[^\]]*\])?\s*$", line)
    if not m:
        continue
    count, file, obj = int(m.group(1).replace(",", "")), m.group(2), m.group(4) or ""
    if file == "???":
        file = "libm" if "libm" in obj else (obj.strip("[]").rsplit("/", 1)[-1] or "???")
    elif file.startswith("./math/"):
        file = "libm"
    elif file.startswith("./"):
        file = "libc: " + file.rsplit("/", 1)[-1]
    elif "/library/" in file:
        file = "std: " + file.split("/library/", 1)[1]
    elif file.startswith(root):
        file = file[len(root):]
    totals[file] = totals.get(file, 0) + count
for file, count in totals.items():
    print(count, file)
' "$root"
}

for spec in "$@"; do
  variant="${spec%@*}"
  turn=720
  [ "$spec" != "$variant" ] && turn="${spec#*@}"
  # The step counts of `callgrind.sh`: whole turns of at least 2000 steps and twice that up to
  # 20,000 steps a turn, otherwise 2000 and 4000 steps; the ring and its series 200 and 400.
  low=2000 high=4000
  if [ "$turn" -le 20000 ]; then low=$(((2000 + turn - 1) / turn * turn)) high=$((2 * low)); fi
  case "$variant" in ring-* | series-*) low=200 high=400 ;; esac
  per_file "$variant" "$low" "$turn" >"$work/low"
  per_file "$variant" "$high" "$turn" >"$work/high"
  echo "== $spec (instructions a step, by source file)"
  python3 - "$work/low" "$work/high" "$((high - low))" <<'EOF'
import sys
def read(path):
    out = {}
    for line in open(path):
        count, file = line.rstrip("\n").split(" ", 1)
        out[file] = out.get(file, 0) + int(count)
    return out
low, high, steps = read(sys.argv[1]), read(sys.argv[2]), int(sys.argv[3])
rows = {f: (high.get(f, 0) - low.get(f, 0)) / steps for f in set(low) | set(high)}
total = sum(rows.values())
for f, v in sorted(rows.items(), key=lambda r: -r[1]):
    if abs(v) >= 0.5:
        print(f"{v:8.1f}  {f}")
print(f"{total:8.1f}  total")
EOF
done
