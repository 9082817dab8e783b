#!/usr/bin/env bash
# The D-SLAM local map joining filter (book Ch. 4) against the book's figures,
# side by side with D-SLAM, SLSJF, the EKF and the full-SLAM baseline; whole
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
# usage: bench/dslam_lmj.sh [RUNS] [PARTS]   (default 5, "join fig49 vicpark")
set -euo pipefail
cd "$(dirname "$0")/.."
runs=${1:-5}
parts=${2:-"join fig49 vicpark"}
esif=$(realpath build/bin/esif)
cache=out/bench; mkdir -p "$cache"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

now() { date +%s.%N; }
median() { sort -g | awk '{a[NR]=$1} END {print (NR%2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2)}'; }
stat() { python3 -c "import json; v=json.load(open('$1/stats.json')).get('$2'); print('null' if v is None else v)"; }
timed() { local file=$1; shift; local t0 t1; t0=$(now); "$esif" "$@" >/dev/null; t1=$(now); awk -v a="$t0" -v b="$t1" 'BEGIN {print b - a}' >>"$file"; }
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
  echo "### grid1225_large in 401 local maps (book: D-SLAM 54,296, LMJ 69,244, SLSJF 143,414 non-zeros)"
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
      "$(stat "$work/$r" landmark_rmse_m)" "$(stat "$work/$r" landmark_consistent_fraction)"
  done
  # The three filters' non-zeros on the same run (Table 5.1 layout).
  printf '[esif]\nplugin = Slsjf\nlabel = slsjf\n[slsjf]\nlocal_map_steps = 45\nlocal_min_range_m = 0.3\n' >"$work/slsjf.ini"
  "$esif" compare --configs "configs/dslam.ini,$work/ids.ini,$work/slsjf.ini" --rawlog "$log" --out "$work/table" 2>/dev/null |
    sed -n '/Table 5.1/,$p'
}

fig49_part() {
  build/bin/feature_std rawlogs/grid196.rawlog "$cache/feature_std.png"
}

vicpark_part() {
  local log; log=$(vicpark_rawlog)
  echo "### Victoria Park: LMJ and SLSJF against the full-SLAM optimum (no ground truth)"
  for i in $(seq 1 "$runs"); do
    timed "$work/vp_lmj.total" run -q --config configs/vicpark/dslam_lmj.ini --rawlog "$log" --out "$work/vp_lmj"
  done
  "$esif" compare --configs configs/vicpark/dslam_lmj.ini,configs/vicpark/slsjf.ini,configs/vicpark/ceres_full.ini \
    --rawlog "$log" --out "$work/vp_cmp" >/dev/null 2>&1
  printf '| run | replay s | trajectory RMS from optimum m | landmark RMS from optimum m | landmark max m |\n'
  printf '|---|---:|---:|---:|---:|\n'
  python3 - "$work/vp_cmp/comparison.csv" <<'PY'
import csv, sys
for row in csv.DictReader(open(sys.argv[1])):
    print("| %s | %s | %s | %s | %s |" % (row["label"], row["wall_s"], row["ref_traj_rms_m"], row["ref_landmark_rms_m"],
                                          row["ref_landmark_max_m"]))
PY
  echo "LMJ whole process s (median of $runs): $(median <"$work/vp_lmj.total")"
}

for p in $parts; do "${p}_part"; echo; done
