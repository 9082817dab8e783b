#!/usr/bin/env bash
# The full-SLAM baseline (book Sec. 1.2.2.2): solve time and iterations.
#  1. Victoria Park (6969 poses, 151 trees; out/data/vicpark.rawlog, imported
#     on first use from ${VICPARK_TXT:-../shared/data/victoria_park/victoria_park.txt}) and
#     grid1225_large (configs/sim/grid1225_large.ini, the book's Table 5.1
#     scale: 18005 poses), each with four initialisations: the plugin's
#     default (the problem re-solved as it grows, new poses refined by their
#     measurements), re-solving every K steps with new poses from odometry
#     alone, one batch solve started from the EKF's estimate, and the plain
#     batch solve from dead reckoning, which stalls on both (reported, not
#     hidden); on Victoria Park also GTSAM's problem (every measurement kept,
#     one solve from the EKF's estimate, no covariances);
#  2. the EKF plugin on the same rawlog, side by side, as the competitor.
# Each row: medians over RUNS of the whole `esif run` process, the summed
# and final solve times, iterations, covariance time; chi2 / dof, converged
# and accuracy of the last run.
#
# With --update-docs the table is written to docs/results/ceres_full.md (the
# whole file, generated).
#
# usage: bench/ceres_full.sh [RUNS] [DATASETS] [--update-docs]   (default 3, "vicpark grid1225_large")
# Environment: ESIF (the binary), ESIF_BENCH_OUT, ESIF_RESULTS_DIR,
# VICPARK_RAWLOG, VICPARK_TXT (bench/common.sh, bench/vicpark_data.sh).
set -euo pipefail
source "$(dirname "$0")/common.sh"
runs=${1:-3}
datasets=${2:-"vicpark grid1225_large"}
cache=$bench_out; mkdir -p "$cache"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# Victoria Park is third-party data: neither it nor a rawlog made from it is
# committed, so bench/vicpark_data.sh imports it on first use.
source bench/vicpark_data.sh
rawlog_for() {
  if [ "$1" = vicpark ]; then vicpark_rawlog; return; fi
  [ -f "$cache/$1.rawlog" ] || "$esif" simulate --config "configs/sim/$1.ini" --out "$cache/$1.rawlog" >&2
  echo "$cache/$1.rawlog"
}
ekf_config_for() { if [ "$1" = vicpark ]; then echo configs/vicpark/ekf.ini; else echo configs/ekf.ini; fi; }
resolve_steps_for() { if [ "$1" = vicpark ]; then echo 100; else echo 200; fi; }

# variant name -> INI text of the baseline's config. On Victoria Park also
# the problem GTSAM's batch Levenberg-Marquardt solves from esif's g2o export
# seeded with the EKF's estimate (issue 42): every measurement kept, one
# solve from the EKF's estimate, no marginal covariances.
variants_for() {
  if [ "$1" = vicpark ]; then echo "growth every_k from_ekf batch from_ekf_all_kept"
  else echo "growth every_k from_ekf batch"; fi
}
variant_ini() {  # dataset variant
  printf '[esif]\nplugin = CeresFullSlam\n'
  case $2 in
    growth) printf '[ceres_full]\n' ;;
    every_k) printf '[ceres_full]\nresolve_growth = 0\nrefine_new_poses = false\nresolve_every_steps = %s\n' "$(resolve_steps_for "$1")" ;;
    from_ekf) printf 'initial_run = %s\n[ceres_full]\nresolve_growth = 0\n' "$work/$1_ekf" ;;
    batch) printf '[ceres_full]\nresolve_growth = 0\nrefine_new_poses = false\n' ;;
    from_ekf_all_kept) printf 'initial_run = %s\n[ceres_full]\nresolve_growth = 0\noutliers = keep\ncovariance = none\n' "$work/$1_ekf" ;;
  esac
}
variant_label() {  # dataset variant
  case $2 in
    growth) echo "re-solved as it grows (the default)" ;;
    every_k) echo "re-solve every $(resolve_steps_for "$1") steps from odometry" ;;
    from_ekf) echo "one solve from the EKF's estimate" ;;
    batch) echo "one solve from dead reckoning" ;;
    from_ekf_all_kept) echo "one solve from the EKF's estimate, every measurement kept, no covariances (GTSAM's problem)" ;;
  esac
}

table() {
  printf '| data | run | whole process s | solve s (all) | final solve s | iterations | covariance s | chi2 / dof | converged | landmark RMSE m | ATE m |\n'
  printf '|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n'
  for data in $datasets; do
    log=$(rawlog_for "$data")
    for i in $(seq 1 "$runs"); do
      t0=$(now); "$esif" run -q --config "$(ekf_config_for "$data")" --rawlog "$log" --out "$work/${data}_ekf" >/dev/null; t1=$(now)
      awk -v a="$t0" -v b="$t1" 'BEGIN {print b - a}' >>"$work/${data}_ekf.total"
      for v in $(variants_for "$data"); do
        variant_ini "$data" "$v" >"$work/$v.ini"
        d="$work/${data}_$v"
        t0=$(now); "$esif" run -q --config "$work/$v.ini" --rawlog "$log" --out "$d" >/dev/null; t1=$(now)
        awk -v a="$t0" -v b="$t1" 'BEGIN {print b - a}' >>"$d.total"
        for k in plugin_solve_s plugin_final_solve_s plugin_iterations plugin_covariance_s; do stat "$d" $k >>"$d.$k"; done
      done
    done
    d="$work/${data}_ekf"
    printf '| %s | EKF | %.2f | - | - | - | - | - | - | %s | %s |\n' "$data" "$(median <"$d.total")" \
      "$(num %.3f "$(stat "$d" landmark_rmse_m)")" "$(num %.3f "$(stat "$d" ate_rmse_m)")"
    for v in $(variants_for "$data"); do
      d="$work/${data}_$v"
      label=$(variant_label "$data" "$v")
      printf '| %s | full SLAM, %s | %.2f | %.2f | %.2f | %.0f | %.2f | %.3f | %s | %s | %s |\n' "$data" "$label" \
        "$(median <"$d.total")" "$(median <"$d.plugin_solve_s")" "$(median <"$d.plugin_final_solve_s")" \
        "$(median <"$d.plugin_iterations")" "$(median <"$d.plugin_covariance_s")" \
        "$(awk -v a="$(stat "$d" plugin_chi2)" -v b="$(stat "$d" plugin_chi2_dof)" 'BEGIN {print a / b}')" \
        "$(stat "$d" plugin_converged)" "$(num %.3f "$(stat "$d" landmark_rmse_m)")" "$(num %.3f "$(stat "$d" ate_rmse_m)")"
    done
  done
}

table | tee "$work/table.md"

if [ "$update_docs" = 1 ]; then
  data=""
  for d in $datasets; do
    if [ "$d" = vicpark ]; then data+="$(vicpark_description "$(vicpark_rawlog)"); "
    else data+="\`configs/sim/$d.ini\` simulated by \`esif simulate\`; "; fi
  done
  {
    cat <<'MD'
The full-SLAM baseline (`CeresFullSlam`, book Sec. 1.2.2.2) with each
initialisation ([plugins/ceres_full.md](../plugins/ceres_full.md)), beside
the EKF on the same rawlog: the plugin's default (re-solved whenever the
pose count has grown by `resolve_growth`, new poses refined by their
measurements), re-solving every K steps with new poses from odometry alone,
one solve started from the EKF's estimate (`initial_run`), and one solve from
dead reckoning (`resolve_growth = 0`, `refine_new_poses = false`). Apart
from those keys the full-SLAM rows use the plugin's defaults (so
`outliers = drop`, unlike `configs/vicpark/ceres_full.ini`). On Victoria
Park the last row is the problem GTSAM's batch Levenberg-Marquardt solves
from `esif export g2o --associations-from` an EKF run (issue 42): every
measurement kept (`outliers = keep`, the optimum's chi2 is 7930.1 for 6978
dof), one solve from the same EKF estimate (`initial_run`), and no marginal
covariances (`covariance = none`), which GTSAM's solve does not compute
either. The EKF row uses
`configs/vicpark/ekf.ini` on Victoria Park and `configs/ekf.ini` otherwise.
Medians over the runs of the whole `esif run` process, the summed and final
solve times, iterations and covariance time; chi2 / dof, convergence and
(with ground truth) accuracy of the last run.

MD
    cat "$work/table.md"
  } | results_page ceres_full "Full-SLAM baseline: solve time and initialisation" "${data%; }, $runs runs each"
fi
