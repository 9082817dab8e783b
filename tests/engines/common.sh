# shellcheck shell=bash
# Sourced by the engine tests (tests/engines/*.sh; registered in
# tests/CMakeLists.txt): a small Monte Carlo campaign run by `esif
# montecarlo` on its own and as an --emit-jobs list run by an engine with
# the command line docs/user-guide.md shows, then collected; the two must
# give the same tables.
#
# The caller sets ESIF (the esif binary) and SOURCE_DIR (the repository) and
# calls engine_tmpdir first. Exit codes: 0 passed, 1 failed, 77 skipped
# (ctest SKIP_RETURN_CODE); with ESIF_REQUIRE_ENGINES=1 (set by .ci/run) a
# skip is a failure, so CI cannot pass by skipping.

# The campaign: configs/sim/small.ini (200 steps, 16 features) with the EKF
# and D-SLAM, 3 noise draws: 6 jobs of under a second each.
ENGINE_RUNS=3
ENGINE_CONFIGS=2
engine_campaign_args() {
  printf '%s\n' --scenario "$SOURCE_DIR/configs/sim/small.ini" \
    --configs "$SOURCE_DIR/configs/ekf.ini,$SOURCE_DIR/configs/dslam.ini" --runs "$ENGINE_RUNS"
}

skip() {
  if [ "${ESIF_REQUIRE_ENGINES:-0}" = 1 ]; then
    echo "FAILED (skip not allowed, ESIF_REQUIRE_ENGINES=1): $*" >&2
    exit 1
  fi
  echo "SKIPPED: $*"
  exit 77
}

fail() {
  echo "FAILED: $*" >&2
  exit 1
}

# A fresh temporary folder in $T; every file the test writes goes under it
# (TMPDIR and GNU parallel's PARALLEL_HOME included). Removed on exit by
# engine_cleanup, which a test's own EXIT trap must call last.
engine_tmpdir() {
  T=$(mktemp -d "${TMPDIR:-/tmp}/esif_engine.XXXXXX")
  mkdir -p "$T/tmp"
  export TMPDIR="$T/tmp" PARALLEL_HOME="$T/parallel_home"
}
engine_cleanup() {
  [ -n "${T:-}" ] && rm -rf "$T"
}

# The command line docs/user-guide.md gives for an engine: its one line that
# ends in "# TAG" (literally), without that comment.
doc_line() {
  local tag="# $1" lines
  lines=$(awk -v tag="$tag" '{
      i = index($0, tag)
      if (i > 1 && substr($0, i) == tag) { s = substr($0, 1, i - 1); sub(/[ \t]+$/, "", s); print s }
    }' "$SOURCE_DIR/docs/user-guide.md")
  if [ -z "$lines" ] || [ "$(printf '%s\n' "$lines" | wc -l)" -ne 1 ]; then
    fail "docs/user-guide.md: expected exactly one command line ending in '$tag', found: '$lines'"
  fi
  printf '%s\n' "$lines"
}

# The campaign run by esif itself in $T/direct, and its job list written to
# $T/engine/jobs.txt for the campaign folder $T/engine/mc.
engine_prepare() {
  local args
  mapfile -t args < <(engine_campaign_args)
  "$ESIF" montecarlo "${args[@]}" --out "$T/direct" --jobs 2 > "$T/direct.log" 2>&1 ||
    { cat "$T/direct.log" >&2; fail "the direct campaign failed"; }
  mkdir -p "$T/engine"
  (cd "$T/engine" && "$ESIF" montecarlo "${args[@]}" --out "$T/engine/mc" --emit-jobs jobs.txt) ||
    fail "--emit-jobs failed"
  local n
  n=$(wc -l < "$T/engine/jobs.txt")
  [ "$n" -eq $((ENGINE_RUNS * ENGINE_CONFIGS)) ] ||
    fail "jobs.txt has $n lines, expected $((ENGINE_RUNS * ENGINE_CONFIGS))"
}

# A CSV without its columns named wall_s* (the runs' times, which differ
# from one execution to the next; every other cell is a function of the
# seeds and configs alone).
without_times() {
  awk -F, '
    NR == 1 { for (i = 1; i <= NF; i++) keep[i] = ($i !~ /^wall_s/) }
    { out = ""; first = 1
      for (i = 1; i <= NF; i++) if (keep[i]) { out = out (first ? "" : ",") $i; first = 0 }
      print out }' "$1"
}

# --collect on what the engine ran, then the same tables as the direct run:
# exactly, since each run is the same esif process on the same inputs
# (simulation seed included) and the aggregation reads the runs in a fixed
# order whatever the order they finished in (tests/integration/
# test_MonteCarlo.cpp asserts the same of xargs).
engine_collect_and_compare() {
  local total=$((ENGINE_RUNS * ENGINE_CONFIGS)) out
  out=$("$ESIF" montecarlo --collect "$T/engine/mc" 2>&1) || { echo "$out" >&2; fail "--collect failed"; }
  echo "$out" | tail -n 1
  [[ "$out" == *"$total of $total runs finished (0 suspect), 0 failed, 0 not finished"* ]] ||
    { echo "$out" >&2; fail "--collect did not find all $total runs finished"; }
  # Every config's row aggregates all the runs (a guard against comparing two empty tables).
  local runs_col rows
  runs_col=$(head -n 1 "$T/engine/mc/summary.csv" | tr , '\n' | grep -nx runs | cut -d: -f1)
  [ -n "$runs_col" ] || fail "summary.csv has no 'runs' column"
  rows=$(awk -F, -v c="$runs_col" -v n="$ENGINE_RUNS" 'NR > 1 && $c == n' "$T/engine/mc/summary.csv" | wc -l)
  [ "$rows" -eq "$ENGINE_CONFIGS" ] || fail "summary.csv: $rows rows with runs = $ENGINE_RUNS, expected $ENGINE_CONFIGS"
  diff <(without_times "$T/direct/summary.csv") <(without_times "$T/engine/mc/summary.csv") >&2 ||
    fail "summary.csv differs from the direct campaign's (wall times aside)"
  local f
  for f in per_step.csv landmarks.csv; do
    cmp "$T/direct/$f" "$T/engine/mc/$f" || fail "$f differs from the direct campaign's"
  done
  echo "summary.csv (wall times aside), per_step.csv and landmarks.csv equal the direct campaign's"
}
