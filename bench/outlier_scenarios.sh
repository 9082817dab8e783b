#!/usr/bin/env bash
# Every plugin config on the outlier scenarios of configs/sim/ (issue:
# filters that survive outliers): misread IDs, clutter, landmarks in pairs
# 0.2 m apart, long stretches without landmarks. Each scenario is simulated
# (seed 1), then `esif compare` runs every config beside the full-SLAM
# baseline; the table gives, per run, its status, landmark RMSE, ATE, share
# of landmarks inside their 95% ellipse, wrong and rejected associations
# (scored against the simulator's true measurement IDs), JCBB fallbacks and
# wall time. Runs are whole `esif` processes; a run that fails or exceeds
# TIMEOUT seconds is a row, never a stop.
#
# usage: bench/outlier_scenarios.sh [SCENARIOS] [CONFIGS]
#   SCENARIOS default "wrong_ids clutter clusters long_gap"
#   CONFIGS   default: every configs/*.ini
set -euo pipefail
cd "$(dirname "$0")/.."
scenarios=${1:-"wrong_ids clutter clusters long_gap"}
configs=${2:-$(ls configs/*.ini | tr '\n' ',' | sed 's/,$//')}
esif=$(realpath build/bin/esif)
out=out/bench/outliers; mkdir -p "$out"

for s in $scenarios; do
  log="$out/$s.rawlog"
  [ -f "$log" ] || "$esif" simulate --config "configs/sim/$s.ini" --out "$log" >&2
  set +e
  "$esif" compare --configs "$configs" --rawlog "$log" --out "$out/$s" >/dev/null 2>"$out/$s.stderr"
  status=$?
  set -e
  echo "## $s (compare exit $status)"
  python3 - "$out/$s/comparison.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
cols = [("status", "status", "{}"), ("landmark RMSE [m]", "landmark_rmse_m", "{:.3f}"), ("ATE [m]", "ate_rmse_m", "{:.3f}"),
        ("in 95%", "landmark_consistent_fraction", "{:.1%}"), ("da_wrong", "da_wrong", "{:.0f}"),
        ("da_rejected", "da_rejected", "{:.0f}"), ("JCBB fallbacks", "plugin_jcbb_fallbacks", "{:.0f}"),
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
