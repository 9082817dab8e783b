#!/usr/bin/env bash
# Calibrates the noise models shipped with the dataset configs (esif
# calibrate, docs/user-guide.md#calibrate):
#   configs/calibration/vicpark.ini  Victoria Park against its full-SLAM
#       optimum under the rawlog's own noise (configs/calibration/
#       vicpark_reference.ini): the dataset has no ground truth;
#   configs/calibration/mrclam.ini   the five robots of MRCLAM dataset 6
#       jointly, against the Vicon ground truth, with the sensor noise
#       inflated for sums of up to $MRCLAM_SENSOR_HORIZON (default 16)
#       consecutive sightings of one cylinder (the camera's error is largely
#       each cylinder's own: the report's last table).
# The datasets are third-party (never committed): the rawlogs are imported
# into out/data/ on first use from ../shared/data (VICPARK_TXT, MRCLAM_DIR).
#
# usage: bench/calibrate_datasets.sh [vicpark] [mrclam]   (default both)
set -euo pipefail
source "$(dirname "$0")/common.sh"
source bench/vicpark_data.sh
datasets=("$@")
[ ${#datasets[@]} -gt 0 ] || datasets=(vicpark mrclam)

# esif calibrate writes into out/bench/calibration/ (its own files there);
# the committed copy in configs/calibration/ is replaced by this script,
# git holding the previous one.
install_calibration() { cp "$bench_out/calibration/$1.ini" "configs/calibration/$1.ini"; echo "bench/$bench_script: wrote configs/calibration/$1.ini" >&2; }

calibrate_vicpark() {
  local log
  log=$(vicpark_rawlog)
  # Relative to the repository root, so that the file's report names no machine path.
  local optimum
  optimum=$(realpath -m --relative-to="$root" "$bench_out/calibration/vicpark_optimum_rawlog_noise")
  mkdir -p "$(dirname "$optimum")"
  "$esif" run -q --no-figures --config configs/calibration/vicpark_reference.ini --rawlog "$log" --out "$optimum"
  "$esif" calibrate -r "$log" --reference-run "$optimum" -o "$bench_out/calibration/vicpark.ini"
  install_calibration vicpark
}

calibrate_mrclam() {
  local dir=${MRCLAM_DIR:-../shared/data/mrclam/MRCLAM_Dataset6} args=() r log
  [ -d "$dir" ] || { echo "bench/$bench_script: $(realpath -m "$dir") not present (MRCLAM dataset 6; set MRCLAM_DIR)" >&2; exit 1; }
  for r in 1 2 3 4 5; do
    log=out/data/mrclam6_r$r.rawlog
    [ -f "$log" ] || "$esif" import mrclam --dataset "$dir" --robot "$r" --out "$log" >&2
    args+=(-r "$log")
  done
  mkdir -p "$bench_out/calibration"
  "$esif" calibrate "${args[@]}" --sensor-horizon "${MRCLAM_SENSOR_HORIZON:-16}" -o "$bench_out/calibration/mrclam.ini"
  install_calibration mrclam
}

for d in "${datasets[@]}"; do
  case $d in
    vicpark) calibrate_vicpark ;;
    mrclam) calibrate_mrclam ;;
    *) echo "bench/$bench_script: unknown dataset $d (vicpark, mrclam)" >&2; exit 2 ;;
  esac
done
