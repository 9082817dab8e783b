#!/usr/bin/env bash
# The D-SLAM local map joining filter (book Ch. 4) against the book's figures,
# side by side with D-SLAM, SLSJF and the full-SLAM baseline; whole
# `esif` processes, medians over RUNS:
#  join      grid1225_large (Sec. 4.6.2, Table 5.1) in local maps of 45 steps
#            that hold two features of the previous map (Sec. 4.4.4): the
#            401 maps fused with their IDs (built once with `esif localmaps
#            build` into out/bench/grid1225_large_lmj_maps), and the whole run
#            with the IDs hidden (association computed, Sec. 4.4.2): fusion
#            time in all and per map, of which association, time per map /
#            state dimension as Fig. 4.14-4.15
#            (out/bench/lmj_join_*_localmap_times.png); information non-zeros
#            beside D-SLAM's and SLSJF's on the same run (the book: 54,296 /
#            69,244 / 143,414, ratio LMJ / D-SLAM 1.28); accuracy and
#            consistency against the ground truth;
#  fig49     out/bench/feature_std.png: Fig. 4.9 on grid196;
#  vicpark   Victoria Park (out/data/vicpark.rawlog, imported on first use from
#            ${VICPARK_TXT:-../shared/data/victoria_park/victoria_park.txt}):
#            LMJ and SLSJF against the full-SLAM optimum.
#
# With --update-docs the tables are written to docs/results/dslam_lmj.md (the
# whole file, generated).
#
# usage: bench/dslam_lmj.sh [RUNS] [PARTS] [--update-docs]   (default 5, "join fig49 vicpark")
# Environment: ESIF (the binary; feature_std is taken from beside it),
# ESIF_BENCH_OUT, ESIF_RESULTS_DIR, VICPARK_RAWLOG, VICPARK_TXT
# (bench/common.sh, bench/vicpark_data.sh).
set -euo pipefail
source "$(dirname "$0")/common.sh"
runs=${1:-5}
parts=${2:-"join fig49 vicpark"}
cache=$bench_out; mkdir -p "$cache"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# Sum of the per-map fusion times in a run's stats (the host's join_us, or the plugin's own costs).
fusion_sum() { python3 -c "import json; s=json.load(open('$1/stats.json')); print(s['join_us_mean'] * s['local_maps'] * 1e-6)"; }

grid1225_rawlog() {
  [ -f "$cache/grid1225_large.rawlog" ] || "$esif" simulate --config configs/sim/grid1225_large.ini --out "$cache/grid1225_large.rawlog" >&2
  echo "$cache/grid1225_large.rawlog"
}
source bench/vicpark_data.sh

join_part() {
  local log maps=$cache/grid1225_large_lmj_maps
  log=$(grid1225_rawlog)
  printf '[esif]\nplugin = DslamLocalMapJoining\nlabel = lmj_ids\n[dslam_lmj]\nassociation = known_ids\nlocal_map_steps = 45\nlocal_min_range_m = 0.3\n' >"$work/ids.ini"
  printf '[esif]\nplugin = DslamLocalMapJoining\nlabel = lmj_jcbb\nhide_landmark_ids = true\n[dslam_lmj]\nassociation = jcbb\nlocal_association = jcbb\nlocal_map_steps = 45\nlocal_min_range_m = 0.3\n' >"$work/jcbb.ini"
  [ -d "$maps" ] || "$esif" localmaps build -q --config "$work/ids.ini" --rawlog "$log" --out "$maps" >&2
  printf '### grid1225_large in 401 local maps (book: D-SLAM 54,296, LMJ 69,244, SLSJF 143,414 non-zeros)\n\n'
  printf '| run | fusion s (sum) | per map ms (median) | of which association s | whole process s | state dim | non-zeros | wrong | landmark RMSE m | consistent |\n'
  printf '|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n'
  for i in $(seq 1 "$runs"); do
    timed "$work/ids.total" run -q --config "$work/ids.ini" --local-maps "$maps" --out "$work/ids"
    fusion_sum "$work/ids" >>"$work/ids.sum"; stat "$work/ids" join_us_p50 >>"$work/ids.p50"
    timed "$work/jcbb.total" run -q --config "$work/jcbb.ini" --rawlog "$log" --out "$work/jcbb"
    fusion_sum "$work/jcbb" >>"$work/jcbb.sum"; stat "$work/jcbb" join_us_p50 >>"$work/jcbb.p50"
    stat "$work/jcbb" plugin_association_s >>"$work/jcbb.assoc"
  done
  echo 0 >"$work/ids.assoc"
  for r in ids jcbb; do
    cp "$work/$r/localmap_times.png" "$cache/lmj_join_${r}_localmap_times.png"
    printf '| %s | %.3f | %.2f | %.3f | %.2f | %s | %s | %s | %s | %s |\n' "$r" "$(median <"$work/$r.sum")" \
      "$(awk '{print $1 / 1000}' "$work/$r.p50" | median)" "$(median <"$work/$r.assoc")" "$(median <"$work/$r.total")" \
      "$(stat "$work/$r" state_dim)" "$(stat "$work/$r" info_nnz)" "$(stat "$work/$r" da_wrong)" \
      "$(num %.3f "$(stat "$work/$r" landmark_rmse_m)")" "$(pct "$(stat "$work/$r" landmark_consistent_fraction)")"
  done
  # The three filters' non-zeros on the same run (Table 5.1 layout).
  printf '[esif]\nplugin = Slsjf\nlabel = slsjf\n[slsjf]\nlocal_map_steps = 45\nlocal_min_range_m = 0.3\n' >"$work/slsjf.ini"
  "$esif" compare --configs "configs/dslam.ini,$work/ids.ini,$work/slsjf.ini" --rawlog "$log" --out "$work/table" >/dev/null 2>&1
  echo
  sed -n '/^## Table 5.1/,$p' "$work/table/comparison.md" | sed 's/^## /### /'
}

fig49_part() {
  "$bin_dir/feature_std" rawlogs/grid196.rawlog "$cache/feature_std.png"
  echo "Fig. 4.9 drawn into ${cache#"$root"/}/feature_std.png."
}

vicpark_part() {
  local log; log=$(vicpark_rawlog)
  printf '### Victoria Park: LMJ and SLSJF against the full-SLAM optimum (no ground truth)\n\n'
  for i in $(seq 1 "$runs"); do
    timed "$work/vp_lmj.total" run -q --config configs/vicpark/dslam_lmj.ini --rawlog "$log" --out "$work/vp_lmj"
  done
  "$esif" compare --configs configs/vicpark/dslam_lmj.ini,configs/vicpark/slsjf.ini,configs/vicpark/ceres_full.ini \
    --rawlog "$log" --out "$work/vp_cmp" >/dev/null 2>&1
  printf '| run | replay s | trajectory RMS from optimum m | landmark RMS from optimum m | landmark max m |\n'
  printf '|---|---:|---:|---:|---:|\n'
  python3 - "$work/vp_cmp/comparison.csv" <<'PY'
import csv, sys
def f(v):
    try: return "%.2f" % float(v)
    except ValueError: return v or "-"
for row in csv.DictReader(open(sys.argv[1])):
    print("| %s | %s | %s | %s | %s |" % (row["label"], f(row["wall_s"]), f(row["ref_traj_rms_m"]),
                                          f(row["ref_landmark_rms_m"]), f(row["ref_landmark_max_m"])))
PY
  printf '\nLMJ whole process s (median of %s): %.2f\n' "$runs" "$(median <"$work/vp_lmj.total")"
}

for p in $parts; do "${p}_part"; echo; done | tee "$work/tables.md"

if [ "$update_docs" = 1 ]; then
  data=""
  for p in $parts; do
    case $p in
      join) data+="\`configs/sim/grid1225_large.ini\` simulated by \`esif simulate\` and its local maps built by \`esif localmaps build\`; " ;;
      fig49) data+="\`rawlogs/grid196.rawlog\`; " ;;
      vicpark) data+="$(vicpark_description "$(vicpark_rawlog)"); " ;;
    esac
  done
  {
    cat <<'MD'
The D-SLAM local map joining filter (`DslamLocalMapJoining`, book Ch. 4;
[plugins/dslam_lmj.md](../plugins/dslam_lmj.md)) against the book's
figures; whole `esif` processes, medians over the runs. `join`:
grid1225_large's 401 local maps fused with their IDs, and the whole run with
the IDs hidden, associating itself (fusion time, of which association;
`consistent`: landmarks inside their 95% ellipse); then the information
non-zeros beside D-SLAM's and SLSJF's in the book's Table 5.1 layout.
`vicpark`: map joining and SLSJF against the full-SLAM optimum (no ground
truth). `fig49` draws the book's Fig. 4.9 into a PNG only.

MD
    cat "$work/tables.md"
  } | results_page dslam_lmj "D-SLAM local map joining: joining cost, Table 5.1, Victoria Park" "${data%; }, $runs runs"
fi
