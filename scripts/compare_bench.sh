#!/usr/bin/env bash
# usage: scripts/compare_bench.sh OLD_REV [SECTION[:PART]...] [--quick] [--threads LIST]
# Before/after speed comparison against an old commit, measured in the same session: makes a
# git worktree of OLD_REV in a temporary folder, builds its huygens-bench there (Release,
# benchmarks only: no tests, no viewer), builds this tree's huygens-bench (HUYGENS_BUILD_DIR,
# default build/), then runs old and new alternately for HUYGENS_COMPARE_ROUNDS rounds (default
# 3; the order flips every round so that a drift of the machine's load hits both alike), prints
# every output, and ends with a side-by-side table: for each timing or ratio column of each table
# both builds print, the median over the rounds of old and new and new / old
# (scripts/compare_bench.py). Arguments after OLD_REV go to both benches unchanged.
# HUYGENS_COMPARE_DIR=DIR keeps the worktree and its build in DIR (reused by the next run);
# HUYGENS_COMPARE_CSV=DIR keeps every run's CSV there (old-ROUND.csv, new-ROUND.csv).
set -euo pipefail
[ $# -ge 1 ] || {
  sed -n '2,13p' "$0" | sed 's/^# \{0,1\}//'
  exit 2
}
root=$(cd "$(dirname "$0")/.." && pwd)
old_rev=$1
shift
new_build=${HUYGENS_BUILD_DIR:-$root/build}
rounds=${HUYGENS_COMPARE_ROUNDS:-3}
jobs=$(nproc)
out=$(mktemp -d)
work=${HUYGENS_COMPARE_DIR:-$out/old}
cleanup() {
  if [ -z "${HUYGENS_COMPARE_DIR:-}" ]; then
    git -C "$root" worktree remove --force "$work" 2>/dev/null || true
  fi
  rm -rf "$out"
}
trap cleanup EXIT

sha=$(git -C "$root" rev-parse --verify "$old_rev^{commit}")
if [ ! -d "$work/.git" ] && [ ! -f "$work/.git" ]; then
  echo "== compare_bench: worktree of $old_rev ($sha) in $work"
  git -C "$root" worktree add --detach "$work" "$sha" >/dev/null
else
  git -C "$work" checkout --detach -q "$sha"
fi
echo "== compare_bench: building the old huygens-bench ($old_rev)"
cmake -S "$work" -B "$work/build" -DCMAKE_BUILD_TYPE=Release -DHUYGENS_BUILD_TESTS=OFF -DHUYGENS_BUILD_VIZ=OFF \
  >"$out/old-configure.log" 2>&1 || { cat "$out/old-configure.log"; exit 1; }
cmake --build "$work/build" -j "$jobs" --target huygens-bench >"$out/old-build.log" 2>&1 || {
  tail -50 "$out/old-build.log"
  exit 1
}
echo "== compare_bench: building the new huygens-bench ($new_build)"
[ -f "$new_build/CMakeCache.txt" ] || cmake -S "$root" -B "$new_build" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$new_build" -j "$jobs" --target huygens-bench >"$out/new-build.log" 2>&1 || {
  tail -50 "$out/new-build.log"
  exit 1
}

run() {  # run NAME ROUND BINARY
  echo
  echo "==================== $1 ($([ "$1" = old ] && echo "$old_rev" || echo "working tree")), round $2 ===================="
  "$3" "${@:4}" --csv "$out/$1-$2.csv" | tee "$out/$1-$2.txt" || echo "(exit $? from the $1 bench)"
}
for r in $(seq 1 "$rounds"); do
  if [ $((r % 2)) = 1 ]; then
    run old "$r" "$work/build/benchmarks/huygens-bench" "$@"
    run new "$r" "$new_build/benchmarks/huygens-bench" "$@"
  else
    run new "$r" "$new_build/benchmarks/huygens-bench" "$@"
    run old "$r" "$work/build/benchmarks/huygens-bench" "$@"
  fi
done
echo
python3 "$root/scripts/compare_bench.py" --old "$out"/old-*.csv --new "$out"/new-*.csv
if [ -n "${HUYGENS_COMPARE_CSV:-}" ]; then
  mkdir -p "$HUYGENS_COMPARE_CSV"
  cp "$out"/*.csv "$HUYGENS_COMPARE_CSV"/
fi
