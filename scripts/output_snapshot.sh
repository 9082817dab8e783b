#!/usr/bin/env bash
# Runs every config in configs/ on its data and keeps what a refactoring must
# not change: landmarks.txt, trajectory.tum, associations.txt, the simulated
# rawlogs and stats.json without its timings. Two snapshots, taken before and
# after a change, are compared with `diff -r BEFORE AFTER`.
#
#   bash scripts/output_snapshot.sh SNAPSHOT_DIR [ESIF_BINARY]
#
# Ground truth beside a rawlog is found by esif itself. Third-party data is
# read from ../shared/data (or ESIF_DATA); configs whose data is missing are
# skipped with a message naming the path. Paths of the temporary work folder
# are written as WORK.
#
# One known difference that is not a change: Ceres' covariance (SPARSE_QR:
# the full-SLAM baseline's landmark covariances and the NEES from them)
# varies in its last bits from run to run of one binary (about 1e-13
# relative); everything else is byte for byte.
set -euo pipefail
cd "$(dirname "$0")/.."
snapshot=${1:?usage: output_snapshot.sh SNAPSHOT_DIR [ESIF_BINARY]}
esif=${2:-build/bin/esif}
data=${ESIF_DATA:-../shared/data}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$snapshot"

# stats.json without the keys that measure time or memory, one key per line.
strip_timings() {
  /usr/bin/python3 - "$1" <<'EOF'
import json, re, sys
timing = re.compile(r'(wall|cpu|time|seconds|_ms$|_us$|_us_|_s$|rss|memory|peak)', re.I)
def clean(v):
    if isinstance(v, dict):
        return {k: clean(x) for k, x in v.items() if not timing.search(k)}
    if isinstance(v, list):
        return [clean(x) for x in v]
    return v
print(json.dumps(clean(json.load(open(sys.argv[1]))), indent=1, sort_keys=True))
EOF
}

keep_run() {  # keep_run RUN_DIR NAME
  local dst="$snapshot/$2"
  mkdir -p "$dst"
  for f in landmarks.txt trajectory.tum associations.txt; do
    [[ -f "$1/$f" ]] && sed "s|$work|WORK|g" "$1/$f" > "$dst/$f"
  done
  [[ -f "$1/stats.json" ]] && strip_timings "$1/stats.json" | sed "s|$work|WORK|g" > "$dst/stats.json"
  return 0
}

run_config() {  # run_config CONFIG NAME ARGS...
  local config=$1 name=$2
  shift 2
  if "$esif" run --config "$config" "$@" --out "$work/$name" > "$work/$name.log" 2>&1; then
    keep_run "$work/$name" "$name"
  else
    mkdir -p "$snapshot/$name"
    tail -1 "$work/$name.log" | sed "s|$work|WORK|g" > "$snapshot/$name/failed.txt"
  fi
  echo "ran $name"
}

for c in configs/sim/*.ini; do
  n=$(basename "$c" .ini)
  "$esif" simulate --config "$c" --out "$work/sim_$n.rawlog" > /dev/null
  mkdir -p "$snapshot/sim"
  sha256sum < "$work/sim_$n.rawlog" | cut -d' ' -f1 > "$snapshot/sim/$n.sha256"
  echo "simulated $n"
done

for c in configs/*.ini; do
  run_config "$c" "grid196_$(basename "$c" .ini)" --rawlog rawlogs/grid196.rawlog
done

localmaps=$data/localmaps/vicpark_200
if [[ -d $localmaps ]]; then
  for c in configs/localmaps/*.ini; do
    run_config "$c" "vp200_$(basename "$c" .ini)" --local-maps "$localmaps" \
      --reference-result "$localmaps/linear_slam_result"
  done
else
  echo "skipped configs/localmaps: $localmaps not found"
fi

if [[ -f $data/victoria_park/victoria_park.txt ]]; then
  "$esif" import victoria-park --in "$data/victoria_park/victoria_park.txt" --out "$work/vicpark.rawlog" > /dev/null
  sha256sum < "$work/vicpark.rawlog" | cut -d' ' -f1 > "$snapshot/vicpark.rawlog.sha256"
  for c in configs/vicpark/*.ini; do
    run_config "$c" "vicpark_$(basename "$c" .ini)" --rawlog "$work/vicpark.rawlog"
  done
else
  echo "skipped configs/vicpark: $data/victoria_park/victoria_park.txt not found"
fi

if [[ -d $data/mrclam/MRCLAM_Dataset6 ]]; then
  "$esif" import mrclam --dataset "$data/mrclam/MRCLAM_Dataset6" --robot 1 --out "$work/mrclam6_r1.rawlog" > /dev/null
  sha256sum < "$work/mrclam6_r1.rawlog" | cut -d' ' -f1 > "$snapshot/mrclam6_r1.rawlog.sha256"
  for c in configs/mrclam/*.ini; do
    run_config "$c" "mrclam_$(basename "$c" .ini)" --rawlog "$work/mrclam6_r1.rawlog"
  done
else
  echo "skipped configs/mrclam: $data/mrclam/MRCLAM_Dataset6 not found"
fi
echo "snapshot in $snapshot"
