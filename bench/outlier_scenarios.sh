#!/usr/bin/env bash
# Every plugin config on the outlier scenarios of configs/sim/ (issue:
# filters that survive outliers): misread IDs, clutter, landmarks in pairs
# 0.2 m apart, long stretches without landmarks. Each scenario is simulated
# (with the seed in its file), then `esif compare` runs every config beside the full-SLAM
# baseline; the table gives, per run, its status, landmark RMSE, ATE, share
# of landmarks inside their 95% ellipse, wrong and rejected associations
# (scored against the simulator's true measurement IDs), the map's
# duplicated and spurious landmarks, association precision and recall, the
# landmark OSPA, JCBB fallbacks and wall time. Runs are whole `esif` processes; a run that fails is a row,
# never a stop.
#
# Writes out/bench/outliers/ (the simulated rawlogs, one compare folder per
# scenario). With --update-docs the tables are written to
# docs/results/outlier_scenarios.md (the whole file, generated).
#
# usage: bench/outlier_scenarios.sh [SCENARIOS] [CONFIGS] [--update-docs]
#   SCENARIOS default "wrong_ids clutter clusters long_gap"
#   CONFIGS   default: every configs/*.ini (comma-separated)
# Environment: ESIF (the binary), ESIF_BENCH_OUT, ESIF_RESULTS_DIR (bench/common.sh).
set -euo pipefail
source "$(dirname "$0")/common.sh"
scenarios=${1:-"wrong_ids clutter clusters long_gap"}
configs=${2:-$(ls configs/*.ini | tr '\n' ',' | sed 's/,$//')}
out=$bench_out/outliers; mkdir -p "$out"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

tables() {
  for s in $scenarios; do
    log="$out/$s.rawlog"
    [ -f "$log" ] || "$esif" simulate --config "configs/sim/$s.ini" --out "$log" >&2
    set +e
    "$esif" compare --configs "$configs" --rawlog "$log" --out "$out/$s" >/dev/null 2>"$out/$s.stderr"
    status=$?
    set -e
    echo "## $s (compare exit $status)"
    echo
    python3 - "$out/$s/comparison.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
cols = [("status", "status", "{}"), ("landmark RMSE [m]", "landmark_rmse_m", "{:.3f}"), ("ATE [m]", "ate_rmse_m", "{:.3f}"),
        ("in 95%", "landmark_consistent_fraction", "{:.1%}"), ("da_wrong", "da_wrong", "{:.0f}"),
        ("da_rejected", "da_rejected", "{:.0f}"), ("duplicated", "landmarks_duplicated", "{:.0f}"),
        ("spurious", "landmarks_spurious", "{:.0f}"), ("precision", "da_precision", "{:.3f}"),
        ("recall", "da_recall", "{:.3f}"), ("OSPA [m]", "landmark_ospa_m", "{:.3f}"),
        ("JCBB fallbacks", "plugin_jcbb_fallbacks", "{:.0f}"),
        ("wall [s]", "wall_s", "{:.1f}"), ("error", "error", "{}")]
def cell(r, k, f):
    v = r.get(k, "")
    if v == "": return "-"
    try: return f.format(float(v)) if f != "{}" else v
    except ValueError: return v
print("| run | " + " | ".join(c[0] for c in cols) + " |")
print("|---" * (len(cols) + 1) + "|")
for r in rows:
    print("| " + r.get("label", "?") + " | " + " | ".join(cell(r, k, f) for _, k, f in cols) + " |")
PY
    echo
  done
}

tables | tee "$work/tables.md"

if [ "$update_docs" = 1 ]; then
  {
    cat <<'MD'
Every config on the outlier scenarios of `configs/sim/` (one draw each,
the seed in its file: see [consistency.md](consistency.md) for Monte Carlo figures),
side by side in one `esif compare` per scenario. `status` is `-` when
every run succeeded and none is suspect, else `ok`, `suspect` or `failed`
(with the first error line); `in 95%` is the share of landmarks inside
their 95% ellipse; `da_wrong`, the duplicated and spurious landmarks,
precision and recall are scored against the simulator's true measurement
IDs, and the OSPA (p = 2, c = `ospa_c_m`) needs none
([outputs.md](../outputs.md#scoring-without-ids)).

MD
    cat "$work/tables.md"
  } | results_page outlier_scenarios "Outlier scenarios: every config, one draw each" \
        "$(printf '`configs/sim/%s.ini` ' $scenarios | sed 's/ $//; s/ /, /g') simulated by \`esif simulate\` (the seed in each file), with the configs \`${configs//,/\`, \`}\`"
fi
