#!/usr/bin/env bash
# Side by side: the esif EKF plugin against MRPT's EKF SLAM on one rawlog,
# with the same noise (odometry covariance from the rawlog's actions; range
# and bearing noise given here, passed to both), known data association.
#  1. whole process: `esif run` vs MRPT's `kf-slam` app (CRangeBearingKFSLAM2D,
#     logging to a scratch folder, no 3-D window), alternated A B A B ...;
#  2. filter only: esif's replay time (stats.json wall_s) vs the bare
#     CRangeBearingKFSLAM2D loop without the app's logging (mrpt_kf_replay);
#  3. agreement: RMS and max difference of the final landmark means, by ID.
# Medians over RUNS runs after one warm-up.
#
# usage: bench/ekf_vs_kfslam.sh RAWLOG STD_RANGE_M STD_BEARING_DEG [RUNS] [--update-docs]
#   RAWLOG "vicpark": out/data/vicpark.rawlog, imported on first use from
#   ${VICPARK_TXT:-../shared/data/victoria_park/victoria_park.txt}.
#   e.g. bench/ekf_vs_kfslam.sh rawlogs/grid196.rawlog 0.1 1 7
#        bench/ekf_vs_kfslam.sh /usr/share/mrpt/datasets/kf-slam_demo.rawlog 0.01 0.1 7
#        bench/ekf_vs_kfslam.sh vicpark 0.5 2 7
#   --update-docs writes the table to docs/results/ekf_vs_kfslam_NAME.md (NAME:
#   the rawlog's file name without .rawlog; the whole file, generated).
# Environment: ESIF (the binary; mrpt_kf_replay is taken from beside it),
# ESIF_RESULTS_DIR, VICPARK_RAWLOG, VICPARK_TXT (bench/common.sh,
# bench/vicpark_data.sh). MRPT's kf-slam must be on the PATH.
set -euo pipefail
source "$(dirname "$0")/common.sh"
[ $# -ge 3 ] || { sed -n '2,22p' "bench/$bench_script"; exit 2; }
replay=$bin_dir/mrpt_kf_replay
[ -x "$replay" ] || { echo "bench/ekf_vs_kfslam.sh: $replay: not built (it is built beside esif)" >&2; exit 1; }
command -v kf-slam >/dev/null || { echo "bench/ekf_vs_kfslam.sh: MRPT's kf-slam is not on the PATH" >&2; exit 1; }
# Victoria Park is third-party data: neither it nor a rawlog made from it is
# committed, so bench/vicpark_data.sh imports it on first use.
source bench/vicpark_data.sh
if [ "$1" = vicpark ]; then
  set -- "$(vicpark_rawlog)" "${@:2}"
  name=vicpark data=$(vicpark_description "$1")
else
  name=$(basename "$1" .rawlog) data="\`$1\`"
fi
rawlog=$(realpath "$1"); std_r=$2; std_b=$3; runs=${4:-7}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

cat >"$work/esif.ini" <<INI
[esif]
plugin = EkfSlam
label = esif_ekf
sensor_std_range_m = $std_r
sensor_std_bearing_deg = $std_b
[ekf]
association = known_ids
INI
sed -e "s/^std_sensor_range *=.*/std_sensor_range = $std_r/" \
    -e "s/^std_sensor_yaw_deg *=.*/std_sensor_yaw_deg = $std_b/" bench/kf-slam.ini >"$work/kf-slam.ini"

for i in $(seq 0 "$runs"); do   # run 0 is a warm-up
  t0=$(now); "$esif" run -q --config "$work/esif.ini" --rawlog "$rawlog" --out "$work/esif" >/dev/null; t1=$(now)
  (cd "$work" && kf-slam "$work/kf-slam.ini" "$rawlog" </dev/null >/dev/null 2>&1); t2=$(now)
  "$replay" "$rawlog" "$std_r" "$work/mrpt_landmarks.txt" "$std_b" | awk '{print $6}' >>"$work/mf.t"
  [ "$i" -eq 0 ] && { : >"$work/mf.t"; continue; }
  awk -F'[:,]' '/"wall_s"/ {print $2}' "$work/esif/stats.json" >>"$work/ef.t"
  awk -v t0="$t0" -v t1="$t1" -v t2="$t2" -v d="$work" 'BEGIN {
    a = t1 - t0; b = t2 - t1
    print a >>(d "/esif.t"); print b >>(d "/kf.t"); print a / b >>(d "/ratio.t") }'
done

report() {
  printf 'Noise %s m / %s deg, %d runs each, medians.\n\n' "$std_r" "$std_b" "$runs"
  printf '| measure | esif | MRPT | ratio esif / MRPT |\n|---|---:|---:|---:|\n'
  printf '| whole process: `esif run` vs `kf-slam` [s] | %.3f | %.3f | %.3f |\n' \
    "$(median <"$work/esif.t")" "$(median <"$work/kf.t")" "$(median <"$work/ratio.t")"
  ef=$(median <"$work/ef.t"); mf=$(median <"$work/mf.t")
  printf '| filter only: EkfSlam vs CRangeBearingKFSLAM2D [s] | %.4f | %.4f | %.3f |\n\n' "$ef" "$mf" \
    "$(awk -v a="$ef" -v b="$mf" 'BEGIN {print a / b}')"
  # MRPT's filter skips the prediction while its map is empty (odometry before
  # the first landmark is dropped), so on logs whose first scans are empty the
  # two maps differ by a rigid motion: also report the difference after the
  # least-squares SE(2) alignment of MRPT's map onto esif's.
  awk 'NR == FNR { if ($1 !~ /^#/) { x[$1] = $2; y[$1] = $3 }; next }
       ($1 in x) { n++; ax[n] = x[$1]; ay[n] = y[$1]; bx[n] = $2; by[n] = $3
                   d = sqrt(($2 - x[$1])^2 + ($3 - y[$1])^2); s += d * d; if (d > m) m = d }
       END {
         for (i = 1; i <= n; i++) { cax += ax[i] / n; cay += ay[i] / n; cbx += bx[i] / n; cby += by[i] / n }
         for (i = 1; i <= n; i++) {
           px = bx[i] - cbx; py = by[i] - cby; qx = ax[i] - cax; qy = ay[i] - cay
           dot += px * qx + py * qy; crs += px * qy - py * qx }
         th = atan2(crs, dot); c = cos(th); sn = sin(th)
         for (i = 1; i <= n; i++) {
           px = bx[i] - cbx; py = by[i] - cby
           ex = cax + c * px - sn * py - ax[i]; ey = cay + sn * px + c * py - ay[i]
           d = sqrt(ex * ex + ey * ey); s2 += d * d; if (d > m2) m2 = d }
         printf "- landmarks: %d matched by ID, RMS difference %.3g m, max %.3g m\n", n, sqrt(s / n), m
         printf "- after SE(2) alignment (rotation %.3g deg): RMS %.3g m, max %.3g m\n", th * 57.29578, sqrt(s2 / n), m2 }' \
    "$work/esif/landmarks.txt" "$work/mrpt_landmarks.txt"
}

report | tee "$work/report.md"

if [ "$update_docs" = 1 ]; then
  {
    cat <<'MD'
The EKF plugin (`EkfSlam`, known data association) beside MRPT's EKF SLAM
(`CRangeBearingKFSLAM2D`) with the same noise
([plugins/ekf.md](../plugins/ekf.md)): the whole process of `esif run`
against MRPT's `kf-slam` application, the filter alone (esif's replay time
against the bare MRPT filter loop `mrpt_kf_replay`), and how far the two
final maps are apart.

MD
    cat "$work/report.md"
  } | results_page "ekf_vs_kfslam_$name" "EKF plugin against MRPT's kf-slam ($name)" "$data"
fi
