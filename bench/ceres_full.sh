#!/usr/bin/env bash
# The full-SLAM baseline (book Sec. 1.2.2.2): solve time and iterations.
#  1. Victoria Park (6969 poses, 151 trees; out/data/vicpark.rawlog, imported
#     on first use from ${VICPARK_TXT:-../shared/data/victoria_park/victoria_park.txt}) and
#     grid1225_large (configs/sim/grid1225_large.ini, the book's Table 5.1
#     scale: 18005 poses), each with the initialisations that reach the
#     optimum: re-solving every K steps from dead reckoning, and one batch
#     solve started from the EKF's estimate; also the plain batch solve from
#     dead reckoning, which stalls on both (reported, not hidden);
#  2. the EKF plugin on the same rawlog, side by side, as the competitor.
# Each row: medians over RUNS of the whole `esif run` process, the summed
# and final solve times, iterations, covariance time, chi2 / dof, converged.
#
# usage: bench/ceres_full.sh [RUNS] [DATASETS]   (default 3, "vicpark grid1225_large")
set -euo pipefail
cd "$(dirname "$0")/.."
runs=${1:-3}
datasets=${2:-"vicpark grid1225_large"}
esif=$(realpath build/bin/esif)
cache=out/bench; mkdir -p "$cache"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# Victoria Park is third-party data: neither it nor a rawlog made from it is
# committed, so import it here (importer defaults, as README.md "Real data").
# The importer writes atomically: an interrupted run leaves no partial file.
source bench/vicpark_data.sh
rawlog_for() {
  if [ "$1" = vicpark ]; then vicpark_rawlog; return; fi
  [ -f "$cache/$1.rawlog" ] || "$esif" simulate --config "configs/sim/$1.ini" --out "$cache/$1.rawlog" >&2
  echo "$cache/$1.rawlog"
}
ekf_config_for() { if [ "$1" = vicpark ]; then echo configs/vicpark/ekf.ini; else echo configs/ekf.ini; fi; }
resolve_steps_for() { if [ "$1" = vicpark ]; then echo 100; else echo 200; fi; }
now() { date +%s.%N; }
median() { sort -g | awk '{a[NR]=$1} END {print (NR%2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2)}'; }
stat() { python3 -c "import json,sys; v=json.load(open('$1/stats.json')).get('$2'); print('null' if v is None else v)"; }

# variant name -> INI text of the baseline's section
variant_ini() {  # dataset variant
  case $2 in
    batch) printf '[ceres_full]\n' ;;
    resolve) printf '[ceres_full]\nresolve_every_steps = %s\n' "$(resolve_steps_for "$1")" ;;
    from_ekf) printf '[ceres_full]\ninitial_run = %s\n' "$work/$1_ekf" ;;
  esac
}

printf '| data | run | whole process s | solve s (all) | final solve s | iterations | covariance s | chi2 / dof | converged | landmark RMSE m | ATE m |\n'
printf '|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n'
for data in $datasets; do
  log=$(rawlog_for "$data")
  for i in $(seq 1 "$runs"); do
    t0=$(now); "$esif" run -q --config "$(ekf_config_for "$data")" --rawlog "$log" --out "$work/${data}_ekf" >/dev/null; t1=$(now)
    awk -v a="$t0" -v b="$t1" 'BEGIN {print b - a}' >>"$work/${data}_ekf.total"
    for v in batch resolve from_ekf; do
      { printf '[esif]\nplugin = CeresFullSlam\n'; variant_ini "$data" "$v"; } >"$work/$v.ini"
      d="$work/${data}_$v"
      t0=$(now); "$esif" run -q --config "$work/$v.ini" --rawlog "$log" --out "$d" >/dev/null; t1=$(now)
      awk -v a="$t0" -v b="$t1" 'BEGIN {print b - a}' >>"$d.total"
      for k in plugin_solve_s plugin_final_solve_s plugin_iterations plugin_covariance_s; do stat "$d" $k >>"$d.$k"; done
    done
  done
  d="$work/${data}_ekf"
  printf '| %s | EKF | %.2f | - | - | - | - | - | - | %s | %s |\n' "$data" "$(median <"$d.total")" \
    "$(stat "$d" landmark_rmse_m)" "$(stat "$d" ate_rmse_m)"
  for v in batch resolve from_ekf; do
    d="$work/${data}_$v"
    label=$v; [ "$v" = resolve ] && label="re-solve every $(resolve_steps_for "$data")"
    printf '| %s | full SLAM, %s | %.2f | %.2f | %.2f | %.0f | %.2f | %.3f | %s | %s | %s |\n' "$data" "$label" \
      "$(median <"$d.total")" "$(median <"$d.plugin_solve_s")" "$(median <"$d.plugin_final_solve_s")" \
      "$(median <"$d.plugin_iterations")" "$(median <"$d.plugin_covariance_s")" \
      "$(awk -v a="$(stat "$d" plugin_chi2)" -v b="$(stat "$d" plugin_chi2_dof)" 'BEGIN {print a / b}')" \
      "$(stat "$d" plugin_converged)" "$(stat "$d" landmark_rmse_m)" "$(stat "$d" ate_rmse_m)"
  done
done
