#!/usr/bin/env bash
# Fuzzes the two readers of untrusted input with libFuzzer (clang):
#   bash scripts/fuzz.sh [seconds per target, default 60]
#   bash scripts/fuzz.sh --smoke    (CI: a fixed seed and a fixed number of
#                                    inputs, so a run is repeatable)
# Builds build-fuzz/ (only the two targets), runs every kept regression input
# once, then fuzzes each target from its seed corpus with a 1 GiB memory
# limit. Exit non-zero on any finding; findings are written to
# build-fuzz/findings/ (add each to tests/fuzz/regressions/ once fixed).
set -euo pipefail
cd "$(dirname "$0")/.."
if [ "${1:-}" = "--smoke" ]; then
  # About a minute each: the rawlog target forks a sandboxed reader per input.
  declare -A budget=([rawlog]="-seed=1 -runs=2000" [ini]="-seed=1 -runs=100000")
else
  seconds="${1:-60}"
  declare -A budget=([rawlog]="-max_total_time=$seconds" [ini]="-max_total_time=$seconds")
fi

if ! command -v clang++ >/dev/null; then
  sudo=""; [ "$(id -u)" -ne 0 ] && sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends clang libclang-rt-14-dev >/dev/null
fi
CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DESIF_FUZZ=ON -DBUILD_TESTING=OFF >/dev/null
cmake --build build-fuzz --target fuzz_rawlog_reader fuzz_ini_reader

mkdir -p build-fuzz/findings build-fuzz/corpus/rawlog build-fuzz/corpus/ini
cp tests/fuzz/seeds/rawlog/* build-fuzz/corpus/rawlog/
for f in configs/*.ini configs/*/*.ini; do cp "$f" build-fuzz/corpus/ini/"${f//\//_}"; done

for target in rawlog ini; do
  bin="build-fuzz/bin/fuzz_${target}_reader"
  regressions=(tests/fuzz/regressions/"$target"/*)
  if [ -e "${regressions[0]}" ]; then
    echo "esif fuzz: ${#regressions[@]} kept ${target} regression inputs"
    "$bin" -rss_limit_mb=1024 "${regressions[@]}" 2>&1 | tail -n 2
  fi
  echo "esif fuzz: ${target} reader (${budget[$target]})"
  # shellcheck disable=SC2086  # the budget is several options
  "$bin" ${budget[$target]} -rss_limit_mb=1024 -max_len=65536 -timeout=30 \
    -artifact_prefix=build-fuzz/findings/"$target"- -print_final_stats=1 \
    build-fuzz/corpus/"$target" 2>&1 | grep -E '^(#[0-9]+ *DONE|stat::number_of_executed_units|stat::peak_rss_mb|==|SUMMARY|ERROR)' || true
  # libFuzzer exits non-zero on a finding; pipefail is bypassed above so say it here.
  if ls build-fuzz/findings/"$target"-* >/dev/null 2>&1; then
    echo "esif fuzz: findings for the ${target} reader in build-fuzz/findings/" >&2
    exit 1
  fi
done
echo "esif fuzz: no finding"
