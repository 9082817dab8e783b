#!/usr/bin/env bash
# Victoria Park report (book Sec. 3.6.2, 4.7, 5.6): every plugin's
# configs/vicpark/*.ini run on the dataset beside the full-SLAM optimum
# (configs/vicpark/ceres_full.ini, the yardstick when there is no ground
# truth). Prints, per filter, the RMS and largest landmark and trajectory
# difference from the optimum, the best-fit rotation of its map onto the
# optimum's and the RMS left after it (a map that is only rotated, an EKF
# heading error, against one that is distorted), and the share of landmarks
# whose optimal position lies inside the filter's own 95% ellipse (a
# consistency test without ground truth: about 95% for a consistent filter).
# The optimum's chi-square is printed beside (GTSAM's batch optimum of the
# problem under the rawlog's own noise, configs/calibration/vicpark_reference.ini: 7930).
#
# Writes out/bench/vicpark_report/ (one folder per run, comparison.md/.csv,
# maps_overlay.png: every map over the optimum's).
#
# The dataset is third-party, never committed: out/data/vicpark.rawlog is
# imported on first use from ${VICPARK_TXT:-../shared/data/victoria_park/victoria_park.txt}.
#
# With --update-docs the report is written to docs/results/vicpark.md (the
# whole file, generated, never edited by hand).
#
# usage: bench/vicpark_report.sh [RAWLOG] [--update-docs]
#   RAWLOG: a Victoria Park rawlog (default: out/data/vicpark.rawlog, imported
#   on first use), e.g. one imported with other noise settings.
# Environment: ESIF (the binary), ESIF_BENCH_OUT, ESIF_RESULTS_DIR,
# VICPARK_RAWLOG, VICPARK_TXT (bench/common.sh, bench/vicpark_data.sh).
set -euo pipefail
source "$(dirname "$0")/common.sh"
source bench/vicpark_data.sh
out=$bench_out/vicpark_report
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

log=""
for arg in "$@"; do
  case "$arg" in
    -*) echo "bench/vicpark_report.sh: unknown option $arg (usage: [RAWLOG] [--update-docs])" >&2; exit 2 ;;
    *) [ -z "$log" ] || { echo "bench/vicpark_report.sh: one RAWLOG only" >&2; exit 2; }
       [ -f "$arg" ] || { echo "bench/vicpark_report.sh: $arg: no such rawlog" >&2; exit 2; }
       log=$arg ;;
  esac
done
[ -n "$log" ] || log=$(vicpark_rawlog)
configs=$(ls configs/vicpark/*.ini | grep -v ceres_full | grep -v _jcbb | tr '\n' ',')configs/vicpark/ceres_full.ini
set +e
"$esif" compare --configs "$configs" --rawlog "$log" --out "$out" >/dev/null
status=$?
set -e
[ -f "$out/comparison.csv" ] || { echo "bench/vicpark_report.sh: compare wrote no table (exit $status)" >&2; exit 1; }

python3 - "$out" <<'PY' | tee "$work/report.md"
import csv, json, os, sys
out = sys.argv[1]
rows = list(csv.DictReader(open(os.path.join(out, "comparison.csv"))))
def cell(row, key, fmt):
    v = row.get(key, "")
    try:
        return fmt.format(float(v))
    except ValueError:
        return v if v else "-"
cols = [("landmarks", "ref_landmarks_matched", "{:.0f}"),
        ("landmark RMS [m]", "ref_landmark_rms_m", "{:.2f}"), ("landmark max [m]", "ref_landmark_max_m", "{:.2f}"),
        ("path RMS [m]", "ref_traj_rms_m", "{:.2f}"), ("path max [m]", "ref_traj_max_m", "{:.2f}"),
        ("rotation [deg]", "ref_rotation_deg", "{:.2f}"), ("RMS after it [m]", "ref_landmark_rms_aligned_m", "{:.2f}"),
        ("inside own 95%", "ref_landmarks_in_own95", "{:.1%}"), ("wall [s]", "wall_s", "{:.1f}")]
print("| run | " + " | ".join(c[0] for c in cols) + " |")
print("|---" * (len(cols) + 1) + "|")
for r in rows:
    print("| " + r.get("label", "?") + " | " + " | ".join(cell(r, k, f) for _, k, f in cols) + " |")
for name in sorted(os.listdir(out)):  # run folders are named after their configs
    stats = os.path.join(out, name, "stats.json")
    if os.path.exists(stats):
        s = json.load(open(stats))
        if "plugin_chi2" in s:
            print(f"\noptimum '{s.get('label', name)}': chi2 {s['plugin_chi2']:.1f} for {s.get('plugin_chi2_dof', 'n/a')} dof,"
                  f" plausible {s.get('plugin_optimum_plausible', 'n/a')} (calibrated noise; GTSAM's optimum of the rawlog's own noise, configs/calibration/vicpark_reference.ini: 7930)")
PY
echo "figure: $out/maps_overlay.png"

if [ "$update_docs" = 1 ]; then
  {
    cat <<'MD'
Every filter of `configs/vicpark/` beside the full-SLAM optimum
(`configs/vicpark/ceres_full.ini`, the yardstick when there is no ground
truth), from `esif compare`'s `ref_*` rows
([outputs.md](../outputs.md#rows-of-comparisonmd)): landmark and path
difference from the optimum (RMS and largest; no alignment fitted), the
best-fit rotation of the filter's map onto the optimum's and the landmark
RMS left after it, the share of landmarks whose optimal position is inside
the filter's own 95% ellipse (about 95% for a consistent filter), and the
replay time. The optimum's own row is zero.

MD
    cat "$work/report.md"
    if [ "$status" -ne 0 ]; then printf '\n`esif compare` exited with %s: a run failed (see its row).\n' "$status"; fi
  } | results_page vicpark "Victoria Park: every filter against the full-SLAM optimum" "$(vicpark_description "$log")"
fi
exit $status
