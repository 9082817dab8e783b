#!/usr/bin/env bash
# Side-by-side timing of the esif EKF plugin and MRPT's kf-slam app
# (CRangeBearingKFSLAM2D, full EKF, known data association) on one rawlog,
# with equivalent noise: both take odometry covariance from the rawlog's
# actions and use range 0.1 m / bearing 1 deg sensor noise (bench/kf-slam.ini).
# Whole-process wall times, runs alternated A B A B ..., medians reported.
#
# usage: bench/ekf_vs_kfslam.sh [RAWLOG] [RUNS]     (defaults: rawlogs/grid196.rawlog 7)
set -euo pipefail
cd "$(dirname "$0")/.."
rawlog=$(realpath "${1:-rawlogs/grid196.rawlog}")
runs=${2:-7}
esif=$(realpath build/bin/esif)
ini=$(realpath bench/kf-slam.ini)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

now() { date +%s.%N; }
median() { sort -g | awk '{a[NR]=$1} END {print (NR%2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2)}'; }

: >"$work/esif.t"; : >"$work/kf.t"; : >"$work/ratio.t"
for i in $(seq 0 "$runs"); do   # run 0 is a warm-up, not counted
  t0=$(now); "$esif" run -q --config configs/ekf.ini --rawlog "$rawlog" --out "$work/esif" >/dev/null; t1=$(now)
  (cd "$work" && kf-slam "$ini" "$rawlog" </dev/null >/dev/null 2>&1); t2=$(now)
  [ "$i" -eq 0 ] && continue
  awk -v t0="$t0" -v t1="$t1" -v t2="$t2" -v d="$work" 'BEGIN {
    a = t1 - t0; b = t2 - t1
    print a >>(d "/esif.t"); print b >>(d "/kf.t"); print a / b >>(d "/ratio.t") }'
done
printf 'rawlog: %s, %d runs each (medians, whole process)\n' "$rawlog" "$runs"
printf 'esif run (EkfSlam):        %.3f s\n' "$(median <"$work/esif.t")"
printf 'kf-slam (CRangeBearingKFSLAM2D): %.3f s\n' "$(median <"$work/kf.t")"
printf 'ratio esif / kf-slam:      %.3f\n' "$(median <"$work/ratio.t")"

# Filter only: esif's replay time (stats.json wall_s) against the bare MRPT
# filter without the app's logging (bench/mrpt_kf_replay.cpp).
: >"$work/ef.t"; : >"$work/mf.t"
replay=$(realpath build/bin/mrpt_kf_replay)
for i in $(seq 1 "$runs"); do
  "$esif" run -q --config configs/ekf.ini --rawlog "$rawlog" --out "$work/esif" >/dev/null
  awk -F'[:,]' '/"wall_s"/ {print $2}' "$work/esif/stats.json" >>"$work/ef.t"
  "$replay" "$rawlog" 0.1 | awk '{print $6}' >>"$work/mf.t"
done
ef=$(median <"$work/ef.t"); mf=$(median <"$work/mf.t")
printf 'filter only: esif EkfSlam %.3f s, MRPT CRangeBearingKFSLAM2D %.3f s, ratio %.3f\n' "$ef" "$mf" \
  "$(awk -v a="$ef" -v b="$mf" 'BEGIN {print a / b}')"
