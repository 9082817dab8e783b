#!/usr/bin/env bash
# D-SLAM against the EKF plugin (book Sec. 3.5, 3.7, Fig. 3.20):
#  1. grid1225 (configs/sim/grid1225.ini, ~7900 steps), both plugins side by
#     side, alternated A B A B ... after a warm-up: whole-process time of
#     `esif run`, replay time (stats.json wall_s) and per-step times; medians;
#  2. growth with the map: D-SLAM alone on grid196, grid1225 and grid5000
#     (configs/sim/grid5000.ini): features, time per step, information-matrix
#     and factor non-zeros, full reorderings (the book: 44,692 non-zeros at
#     1225 features with a 6 m range; 73 reorderings in 7876 steps).
# Scenario rawlogs are simulated once into out/bench/ (deterministic seeds).
# With --update-docs the tables are written to docs/results/dslam_vs_ekf.md
# (the whole file, generated).
#
# usage: bench/dslam_vs_ekf.sh [RUNS] [--update-docs]     (default 5)
# Environment: ESIF (the binary), ESIF_BENCH_OUT, ESIF_RESULTS_DIR (bench/common.sh).
set -euo pipefail
source "$(dirname "$0")/common.sh"
runs=${1:-5}
cache=$bench_out; mkdir -p "$cache"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

rawlog_for() {  # scenario name -> rawlog path (simulated on first use)
  local name=$1
  if [ "$name" = grid196 ]; then echo rawlogs/grid196.rawlog; return; fi
  [ -f "$cache/$name.rawlog" ] || "$esif" simulate --config "configs/sim/$name.ini" --out "$cache/$name.rawlog" >&2
  echo "$cache/$name.rawlog"
}

tables() {
  # ---- 1. side by side on grid1225
  grid1225=$(rawlog_for grid1225)
  for i in $(seq 0 "$runs"); do   # run 0 is a warm-up
    for cfg in ekf dslam; do
      t0=$(now); "$esif" run -q --config "configs/$cfg.ini" --rawlog "$grid1225" --out "$work/$cfg" >/dev/null; t1=$(now)
      [ "$i" -eq 0 ] && continue
      awk -v a="$t0" -v b="$t1" 'BEGIN {print b - a}' >>"$work/$cfg.total"
      stat "$work/$cfg" wall_s >>"$work/$cfg.replay"
      stat "$work/$cfg" step_us_p50 >>"$work/$cfg.p50"
      stat "$work/$cfg" step_us_mean >>"$work/$cfg.mean"
    done
  done
  printf 'grid1225 (configs/sim/grid1225.ini), %d runs each, medians\n\n' "$runs"
  printf '| plugin | whole process s | replay s | step us mean | step us p50 | landmarks | landmark RMSE m | ATE m |\n|---|---:|---:|---:|---:|---:|---:|---:|\n'
  for cfg in ekf dslam; do
    printf '| %s | %.3f | %.3f | %.0f | %.0f | %s | %.3f | %.3f |\n' "$cfg" "$(median <"$work/$cfg.total")" \
      "$(median <"$work/$cfg.replay")" "$(median <"$work/$cfg.mean")" "$(median <"$work/$cfg.p50")" \
      "$(stat "$work/$cfg" landmarks)" "$(stat "$work/$cfg" landmark_rmse_m)" "$(stat "$work/$cfg" ate_rmse_m)"
  done
  printf '\nratio D-SLAM / EKF: whole process %.3f, replay %.3f\n\n' \
    "$(awk -v a="$(median <"$work/dslam.total")" -v b="$(median <"$work/ekf.total")" 'BEGIN {print a / b}')" \
    "$(awk -v a="$(median <"$work/dslam.replay")" -v b="$(median <"$work/ekf.replay")" 'BEGIN {print a / b}')"

  # ---- 2. growth with the number of features (D-SLAM alone)
  printf '| scenario | steps | features | replay s | step us mean | step us p50 | us per step per 1000 features | info nnz | factor nnz | full reorders |\n'
  printf '|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n'
  for name in grid196 grid1225 grid5000; do
    [ -f "configs/sim/$name.ini" ] || continue
    log=$(rawlog_for "$name")
    for i in $(seq 1 "$runs"); do
      "$esif" run -q --config configs/dslam.ini --rawlog "$log" --out "$work/g_$name" >/dev/null
      stat "$work/g_$name" wall_s >>"$work/g_$name.replay"
      stat "$work/g_$name" step_us_mean >>"$work/g_$name.mean"
      stat "$work/g_$name" step_us_p50 >>"$work/g_$name.p50"
    done
    d="$work/g_$name"; n=$(stat "$d" landmarks); mean=$(median <"$d.mean")
    printf '| %s | %s | %s | %.3f | %.0f | %.0f | %.0f | %s | %.0f | %.0f |\n' "$name" "$(stat "$d" steps)" "$n" \
      "$(median <"$d.replay")" "$mean" "$(median <"$d.p50")" "$(awk -v m="$mean" -v n="$n" 'BEGIN {print 1000 * m / n}')" \
      "$(stat "$d" info_nnz)" "$(stat "$d" plugin_sparse_factor_nnz)" "$(stat "$d" plugin_sparse_full_reorders)"
  done
}

tables | tee "$work/tables.md"

if [ "$update_docs" = 1 ]; then
  {
    cat <<'MD'
D-SLAM (`configs/dslam.ini`) beside the EKF (`configs/ekf.ini`), book
Sec. 3.5, 3.7 and Fig. 3.20. First table: both on grid1225, alternated after
a warm-up; whole `esif run` process, replay time (`wall_s`) and time per
step, medians over the runs. Second table: D-SLAM alone as the map grows
(the book: 44,692 information non-zeros at 1225 features with a 6 m range;
73 reorderings in 7876 steps).

MD
    cat "$work/tables.md"
  } | results_page dslam_vs_ekf "D-SLAM against the EKF, and D-SLAM's growth" \
        "the simulated scenarios \`configs/sim/grid196.ini\` (the committed \`rawlogs/grid196.rawlog\`), \`grid1225.ini\` and \`grid5000.ini\`, $runs runs each"
fi
