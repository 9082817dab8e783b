#!/usr/bin/env bash
# What a run costs as a user waits for it: the whole esif process beside the
# filter's own time (stats.json wall_s: every step and finish()), the
# difference (start-up, reading, evaluation, output files) and the peak
# memory, medians of RUNS (default 5), measured with /usr/bin/time.
#
#   bash bench/end_to_end.sh [RUNS] [--campaign] [--update-docs]
#
# Rows: `esif --help` and `esif plugins` (start-up alone), `esif run --help`
# (start-up with the host and MRPT loaded), the EKF on rawlogs/grid196.rawlog
# with and without its figures, SLSJF smoothing every 50 maps on Victoria Park
# (configs/vicpark/slsjf_smoothed.ini; skipped without the dataset) and SLSJF
# on the simulated grid1225_large (configs/slsjf.ini). --campaign adds
# `esif montecarlo` on grid196 with the EKF, D-SLAM, SLSJF and D-SLAM map
# joining, 50 runs: its whole time and the time per run beside the filters'
# mean wall_s. --update-docs writes docs/results/end_to_end.md.
source "$(dirname "$0")/common.sh"
source "$(dirname "$0")/vicpark_data.sh"
runs=5
campaign=0
for arg in "$@"; do
  case $arg in
    --campaign) campaign=1 ;;
    *[!0-9]* | "") echo "usage: bench/end_to_end.sh [RUNS] [--campaign] [--update-docs]" >&2; exit 2 ;;
    *) runs=$arg ;;
  esac
done
[ -x /usr/bin/time ] || { echo "bench/end_to_end.sh: /usr/bin/time not found (Debian package time)" >&2; exit 1; }
work=$bench_out/end_to_end
mkdir -p "$work"

# measure NAME ARGS...: runs `esif ARGS` RUNS times (after one warm-up) and
# prints a table row: whole process, wall_s, overhead, peak memory (medians).
# When ARGS hold `--out DIR`, wall_s is read from DIR/stats.json.
measure() {
  local name=$1 out="" prev="" a
  shift
  for a in "$@"; do [ "$prev" = --out ] && out=$a; prev=$a; done
  local whole=$work/whole.txt rss=$work/rss.txt filter=$work/filter.txt
  : >"$whole"; : >"$rss"; : >"$filter"
  for i in $(seq 0 "$runs"); do
    /usr/bin/time -f "%e %M" -o "$work/time.txt" "$esif" "$@" >/dev/null 2>"$work/stderr.txt" ||
      { echo "bench/end_to_end.sh: $name failed: $(tail -1 "$work/stderr.txt")" >&2; exit 1; }
    [ "$i" -eq 0 ] && continue  # the warm-up: page cache, dynamic loader
    read -r seconds kib <"$work/time.txt"
    echo "$seconds" >>"$whole"
    echo "$kib" >>"$rss"
    if [ -n "$out" ]; then
      stat "$out" wall_s >>"$filter"
      cp "$out/stats.json" "$work/stats_$i.json"
      echo "$seconds" >"$work/whole_$i.txt"
    fi
  done
  if [ -n "$out" ]; then breakdown "$name" >>"$work/breakdown.md"; fi
  local w f m
  w=$(median <"$whole")
  m=$(awk '{print $1 / 1024}' "$rss" | median)
  if [ -n "$out" ]; then
    f=$(median <"$filter")
    printf '| %s | %.2f s | %.2f s | %.2f s | %.0f MiB |\n' "$name" "$w" "$f" "$(awk -v a="$w" -v b="$f" 'BEGIN {print a - b}')" "$m"
  else
    # /usr/bin/time counts in hundredths: a start-up below that reads 0.
    local shown
    shown=$(awk -v a="$w" 'BEGIN { if (a < 0.01) print "< 0.01 s"; else printf "%.2f s", a }')
    printf '| %s | %s | - | %s | %.0f MiB |\n' "$name" "$shown" "$shown" "$m"
  fi
}

# breakdown NAME: one row of where the run's time goes (medians over the
# runs' stats.json): start-up, exit and the output folder's commit (whole
# process - total_wall_s - state NEES), reading, the filter, evaluation, the
# output files (with the three slowest) and the whole-state NEES.
breakdown() {
  python3 - "$1" "$work" "$runs" <<'PY'
import json, statistics, sys
name, work, runs = sys.argv[1], sys.argv[2], int(sys.argv[3])
stats = [json.load(open(f"{work}/stats_{i}.json")) for i in range(1, runs + 1)]
whole = [float(open(f"{work}/whole_{i}.txt").read()) for i in range(1, runs + 1)]
def med(key): return statistics.median(s.get(key) or 0.0 for s in stats)
phases = sorted({k[5:-2] for s in stats for k in s if k.startswith("time_") and k.endswith("_s")})
outputs = [p for p in phases if p not in ("read", "evaluate", "state_nees")]
rest = statistics.median(w - s["total_wall_s"] - (s.get("time_state_nees_s") or 0) for w, s in zip(whole, stats))
files = sorted(((med(f"time_{p}_s"), p) for p in outputs), reverse=True)
def file_name(phase): return phase[::-1].replace("_", ".", 1)[::-1]  # map_png -> map.png
slowest = ", ".join(f"{file_name(p)} {t:.3f}" for t, p in files[:3])
print(f"| {name} | {rest:.3f} | {med('time_read_s'):.3f} | {med('wall_s'):.3f} | {med('time_evaluate_s'):.3f} | "
      f"{sum(t for t, _ in files):.3f} ({slowest}) | {med('time_state_nees_s'):.3f} |")
PY
}

grid1225=$bench_out/grid1225_large.rawlog
[ -f "$grid1225" ] || "$esif" simulate --config configs/sim/grid1225_large.ini --out "$grid1225" >/dev/null

table() {
  : >"$work/breakdown.md"
  echo "| command | whole process | the filter (\`wall_s\`) | overhead | peak memory |"
  echo "|---|---:|---:|---:|---:|"
  measure '`esif --help`' --help
  measure '`esif plugins`' plugins
  # Any other command loads the host and, through it, MRPT; Debian's MRPT 2.5
  # links OpenCV and GDAL, so this is the floor under every run.
  local libs
  libs=$(ldd "$bin_dir/../lib/libesif_app.so" | wc -l)
  measure "\`esif run --help\` (loads the host and MRPT: $libs shared libraries)" run --help
  measure 'EKF, `rawlogs/grid196.rawlog` (3,000 steps)' run --config configs/ekf.ini --rawlog rawlogs/grid196.rawlog --out "$work/ekf_grid196"
  measure 'EKF, `rawlogs/grid196.rawlog`, `--no-figures`' run --no-figures --config configs/ekf.ini --rawlog rawlogs/grid196.rawlog --out "$work/ekf_grid196_no_figures"
  if vp=$(vicpark_rawlog 2>/dev/null); then
    measure 'SLSJF smoothing every 50 maps, Victoria Park (6,969 steps)' run --config configs/vicpark/slsjf_smoothed.ini --rawlog "$vp" --out "$work/slsjf_vicpark"
  else
    echo "| SLSJF, Victoria Park | skipped: dataset not present | | | |"
  fi
  measure 'SLSJF, `grid1225_large` (simulated)' run --config configs/slsjf.ini --rawlog "$grid1225" --out "$work/slsjf_grid1225_large"
  echo
  echo "Medians of $runs runs after one warm-up; whole process and peak memory by \`/usr/bin/time\`; overhead = whole process - \`wall_s\`."
  echo
  echo "Where each run's time goes [s], medians of the runs' \`stats.json\` (\`time_*_s\`):"
  echo
  echo "| run | start-up, exit, folder commit | read input | filter (\`wall_s\`) | evaluate | output files, summed (slowest three) | whole-state NEES |"
  echo "|---|---:|---:|---:|---:|---|---:|"
  cat "$work/breakdown.md"
  echo
  echo "Output files are written side by side (each figure is a gnuplot process on a thread of its own), so their summed times exceed the wall time they take."
}

campaign_table() {
  local dir=$work/campaign t0 t1 total per_run mean_wall
  rm -rf "$dir"
  t0=$(now)
  "$esif" montecarlo --scenario configs/sim/grid196.ini \
    --configs configs/ekf.ini,configs/dslam.ini,configs/slsjf.ini,configs/dslam_lmj.ini \
    --runs 50 --jobs "$(nproc)" --out "$dir" >/dev/null
  t1=$(now)
  total=$(awk -v a="$t0" -v b="$t1" 'BEGIN {print b - a}')
  per_run=$(awk -v t="$total" -v j="$(nproc)" 'BEGIN {print t * j / 200}')
  mean_wall=$(find "$dir/runs" -name stats.json -exec dirname {} \; | while read -r d; do stat "$d" wall_s; done |
    awk '{s += $1; n++} END {print s / n}')
  echo
  echo "\`esif montecarlo\` on grid196 (EKF, D-SLAM, SLSJF, D-SLAM map joining; 50 runs each, $(nproc) jobs):"
  echo
  echo "| whole campaign | per run (whole x jobs / 200) | the filters' mean \`wall_s\` | ratio |"
  echo "|---:|---:|---:|---:|"
  printf '| %.1f s | %.2f s | %.2f s | %.2f |\n' "$total" "$per_run" "$mean_wall" "$(awk -v a="$per_run" -v b="$mean_wall" 'BEGIN {print a / b}')"
}

output=$(
  table
  if [ "$campaign" -eq 1 ]; then campaign_table; fi
)
echo "$output"
if [ "$update_docs" -eq 1 ]; then
  echo "$output" | results_page end_to_end "End to end: whole process against the filter's own time" \
    'the committed `rawlogs/grid196.rawlog`, Victoria Park (third-party, `../shared/data/victoria_park/`) and the simulated `configs/sim/grid1225_large.ini`'
fi
