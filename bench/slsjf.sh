#!/usr/bin/env bash
# SLSJF (book Ch. 5) against the book's figures and side by side with its
# competitors, whole `esif` processes, medians over RUNS:
#  join      the 401 local maps of grid1225_large (Sec. 5.5; built once with
#            `esif localmaps build` into out/bench/grid1225_large_maps), fused
#            with their IDs and with the IDs hidden (JCBB, Sec. 5.4.1): total
#            fusion time (the book: 120 s and 459 s in MATLAB), per map, and
#            out/bench/slsjf_join*_localmap_times.png (Fig. 5.7-5.8);
#  grid1225  end to end on grid1225_large (build + join): SLSJF plain and
#            relinearised, the EKF and the re-solving full-SLAM baseline
#            (these two once: minutes each), accuracy ratios and Table 5.1;
#  vicpark   Victoria Park (out/data/vicpark.rawlog, imported on first use
#            from ${VICPARK_TXT:-../shared/data/victoria_park/victoria_park.txt}):
#            SLSJF plain and relinearised against the full-SLAM optimum.
#
# With --update-docs the tables are written to docs/results/slsjf.md (the
# whole file, generated).
#
# usage: bench/slsjf.sh [RUNS] [PARTS] [--update-docs]   (default 5, "join grid1225 vicpark")
# Environment: ESIF (the binary), ESIF_BENCH_OUT, ESIF_RESULTS_DIR,
# VICPARK_RAWLOG, VICPARK_TXT (bench/common.sh, bench/vicpark_data.sh).
set -euo pipefail
source "$(dirname "$0")/common.sh"
runs=${1:-5}
parts=${2:-"join grid1225 vicpark"}
cache=$bench_out; mkdir -p "$cache"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

grid1225_rawlog() {
  [ -f "$cache/grid1225_large.rawlog" ] || "$esif" simulate --config configs/sim/grid1225_large.ini --out "$cache/grid1225_large.rawlog" >&2
  echo "$cache/grid1225_large.rawlog"
}
source bench/vicpark_data.sh

join_part() {
  local maps=$cache/grid1225_large_maps
  [ -d "$maps" ] || "$esif" localmaps build -q --config configs/slsjf.ini --rawlog "$(grid1225_rawlog)" --out "$maps" >&2
  printf '[esif]\nplugin = Slsjf\n[slsjf]\nassociation = known_ids\n' >"$work/ids.ini"
  printf '[esif]\nplugin = Slsjf\nhide_landmark_ids = true\n[slsjf]\nassociation = jcbb\n' >"$work/jcbb.ini"
  printf '### Joining the 401 local maps of grid1225_large (book: 120 s with association given, 459 s computing it)\n\n'
  printf '| association | maps | fusion s (sum) | per map ms (median) | of which association s | finish s | whole process s | state dim | non-zeros | wrong | landmark RMSE m |\n'
  printf '|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n'
  for a in ids jcbb; do
    local d=$work/join_$a
    for i in $(seq 1 "$runs"); do
      timed "$d.total" run -q --config "$work/$a.ini" --local-maps "$maps" --out "$d"
      python3 -c "import json; s=json.load(open('$d/stats.json')); print(s['join_us_mean'] * s['local_maps'] * 1e-6)" >>"$d.sum"
      stat "$d" join_us_p50 >>"$d.p50"; stat "$d" plugin_association_s >>"$d.assoc"; stat "$d" finish_us >>"$d.finish"
    done
    cp "$d/localmap_times.png" "$cache/slsjf_join_${a}_localmap_times.png"
    printf '| %s | %s | %.3f | %.2f | %.3f | %.3f | %.2f | %s | %s | %s | %s |\n' "$a" "$(stat "$d" local_maps)" \
      "$(median <"$d.sum")" "$(awk '{print $1 / 1000}' "$d.p50" | median)" "$(median <"$d.assoc")" \
      "$(awk '{print $1 / 1e6}' "$d.finish" | median)" "$(median <"$d.total")" "$(stat "$d" state_dim)" \
      "$(stat "$d" info_nnz)" "$(stat "$d" da_wrong)" "$(num %.4f "$(stat "$d" landmark_rmse_m)")"
  done
}

# config, runs -> one table row
end_to_end_row() {
  local data=$1 config=$2 n=$3 log=$4 d=$work/$1_$(basename "$2" .ini)
  for i in $(seq 1 "$n"); do timed "$d.total" run -q --config "$config" --rawlog "$log" --out "$d"; done
  printf '| %s | %s | %.2f | %s | %s | %s | %s | %s | %s | %s |\n' "$data" "$(stat "$d" label)" "$(median <"$d.total")" \
    "$(num %.3f "$(stat "$d" landmark_rmse_m)")" "$(num %.3f "$(stat "$d" ate_rmse_m)")" "$(pct "$(stat "$d" landmark_consistent_fraction)")" \
    "$(num %s "$(stat "$d" info_nnz)")" "$(stat "$d" landmarks)" "$(stat "$d" poses_in_state)" "$(stat "$d" state_dim)"
}

grid1225_part() {
  local log; log=$(grid1225_rawlog)
  printf '### End to end on grid1225_large (book Table 5.1: SLSJF 143,414 non-zeros, 876 features, 400 poses, dimension 2,952)\n\n'
  printf '| data | run | whole process s | landmark RMSE m | ATE m | consistent | non-zeros | features | poses | state dim |\n'
  printf '|---|---|---:|---:|---:|---:|---:|---:|---:|---:|\n'
  end_to_end_row grid1225 configs/slsjf.ini "$runs" "$log"
  end_to_end_row grid1225 configs/slsjf_smoothed.ini "$runs" "$log"
  end_to_end_row grid1225 configs/ekf.ini 1 "$log"
  end_to_end_row grid1225 configs/ceres_full_incremental.ini 1 "$log"
}

vicpark_part() {
  local log; log=$(vicpark_rawlog)
  # The shipped config whole, [esif] included: its calibration file (named
  # relative to the config, so made absolute here) sets the noise that the
  # ID gates and the smoothing weigh with.
  sed -e 's/^label *=.*/label = vicpark_slsjf_smoothed/' -e "s#^calibration = \.\./#calibration = $PWD/configs/#" \
    -e '/^\[slsjf\]/a smoothing = final' configs/vicpark/slsjf.ini >"$work/vp_smoothed.ini"
  # The same with maps of 10 steps: how much of the relinearised maps'
  # distance from the optimum is the local EKF's own linearisation.
  sed -e 's/label = vicpark_slsjf_smoothed/label = vicpark_slsjf_smoothed_10/' -e 's/^local_map_steps = .*/local_map_steps = 10/' \
    "$work/vp_smoothed.ini" >"$work/vp_smoothed_10.ini"
  printf '### Victoria Park: SLSJF against the full-SLAM optimum (no ground truth)\n\n'
  for i in $(seq 1 "$runs"); do
    timed "$work/vp_slsjf.total" run -q --config configs/vicpark/slsjf.ini --rawlog "$log" --out "$work/vp_slsjf"
    timed "$work/vp_smoothed.total" run -q --config "$work/vp_smoothed.ini" --rawlog "$log" --out "$work/vp_smoothed"
    timed "$work/vp_smoothed_10.total" run -q --config "$work/vp_smoothed_10.ini" --rawlog "$log" --out "$work/vp_smoothed_10"
  done
  "$esif" compare --configs "configs/vicpark/slsjf.ini,$work/vp_smoothed.ini,$work/vp_smoothed_10.ini,configs/vicpark/ceres_full.ini" \
    --rawlog "$log" --out "$work/vp_cmp" >/dev/null 2>&1
  printf '| run | whole process s (median) | trajectory RMS from optimum m | landmark RMS from optimum m | landmark max m |\n'
  printf '|---|---:|---:|---:|---:|\n'
  for pair in vicpark_slsjf:vp_slsjf vicpark_slsjf_smoothed:vp_smoothed vicpark_slsjf_smoothed_10:vp_smoothed_10; do  # label : timing file
    python3 - "$work/vp_cmp/comparison.csv" "${pair%%:*}" "$(median <"$work/${pair##*:}.total")" <<'PY'
import csv, sys
def f(v):
    try: return "%.2f" % float(v)
    except ValueError: return v or "-"
for row in csv.DictReader(open(sys.argv[1])):
    if row["label"] == sys.argv[2]:
        print("| %s | %.2f | %s | %s | %s |" % (row["label"], float(sys.argv[3]), f(row["ref_traj_rms_m"]),
                                               f(row["ref_landmark_rms_m"]), f(row["ref_landmark_max_m"])))
PY
  done
}

for p in $parts; do "${p}_part"; echo; done | tee "$work/tables.md"

if [ "$update_docs" = 1 ]; then
  data=""
  for p in $parts; do
    case $p in
      join) data+="\`configs/sim/grid1225_large.ini\` simulated by \`esif simulate\` and its local maps built by \`esif localmaps build\`; " ;;
      grid1225) data+="\`configs/sim/grid1225_large.ini\` simulated by \`esif simulate\`; " ;;
      vicpark) data+="$(vicpark_description "$(vicpark_rawlog)"); " ;;
    esac
  done
  {
    cat <<'MD'
SLSJF (`Slsjf`, book Ch. 5; [plugins/slsjf.md](../plugins/slsjf.md)) against
the book's figures and beside its competitors; whole `esif` processes,
medians over the runs. `join`: grid1225_large's 401 local maps fused with
their IDs and with the IDs hidden (JCBB, Sec. 5.4.1). `grid1225`: end to
end on grid1225_large, SLSJF plain and relinearised beside the EKF and the
full-SLAM baseline (these two run once). `vicpark`: SLSJF plain and
relinearised (35- and 10-step maps) against the full-SLAM optimum (no
ground truth).

MD
    cat "$work/tables.md"
  } | results_page slsjf "SLSJF: joining cost, end to end, Victoria Park" "${data%; }, $runs runs"
fi
