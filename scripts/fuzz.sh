#!/usr/bin/env bash
# Fuzzes the readers of untrusted input with libFuzzer (clang): the rawlog,
# INI, local-map, g2o and ground-truth (side-file) readers, and the Victoria
# Park and MRCLAM importers:
#   bash scripts/fuzz.sh [seconds per target, default 60]
#   bash scripts/fuzz.sh --smoke    (CI: a fixed seed and a fixed number of
#                                    inputs, so a run is repeatable)
# Builds build-fuzz/ (only the fuzz targets), runs every kept regression input
# once, then fuzzes each target from its seed corpus with a 1 GiB memory
# limit. Exit non-zero on any finding; findings are written to
# build-fuzz/findings/ (add each to tests/fuzz/regressions/ once fixed), the
# logs to build-fuzz/logs/ (bash scripts/fuzz_report.sh makes
# docs/results/fuzz.md of them).
set -euo pipefail
cd "$(dirname "$0")/.."
# Each target is fuzz_<name>_reader or fuzz_<name>_importer; its seeds and
# regressions are under tests/fuzz/{seeds,regressions}/<name>.
targets=(rawlog ini localmap g2o ground_truth vicpark mrclam)
declare -A binary=([rawlog]=reader [ini]=reader [localmap]=reader [g2o]=reader [ground_truth]=reader
                   [vicpark]=importer [mrclam]=importer)
declare -A budget
if [ "${1:-}" = "--smoke" ]; then
  # About a minute for the rawlog target (it forks a sandboxed reader per
  # input), seconds to tens of seconds for the in-process text readers; the
  # importers write a rawlog per input they accept.
  budget=([rawlog]="-seed=1 -runs=2000" [ini]="-seed=1 -runs=100000" [localmap]="-seed=1 -runs=50000"
          [g2o]="-seed=1 -runs=50000" [ground_truth]="-seed=1 -runs=50000" [vicpark]="-seed=1 -runs=20000"
          [mrclam]="-seed=1 -runs=20000")
else
  seconds="${1:-60}"
  for t in "${targets[@]}"; do budget[$t]="-max_total_time=$seconds"; done
fi

if ! command -v clang++ >/dev/null; then
  sudo=""; [ "$(id -u)" -ne 0 ] && sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends clang libclang-rt-14-dev >/dev/null
fi
CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DESIF_FUZZ=ON -DBUILD_TESTING=OFF >/dev/null
fuzzers=()
for t in "${targets[@]}"; do fuzzers+=("fuzz_${t}_${binary[$t]}"); done
cmake --build build-fuzz --target "${fuzzers[@]}"

mkdir -p build-fuzz/findings
for target in "${targets[@]}"; do
  mkdir -p build-fuzz/corpus/"$target"
  if [ -d tests/fuzz/seeds/"$target" ]; then cp tests/fuzz/seeds/"$target"/* build-fuzz/corpus/"$target"/; fi
done
for f in configs/*.ini configs/*/*.ini; do cp "$f" build-fuzz/corpus/ini/"${f//\//_}"; done

rm -rf build-fuzz/logs
mkdir -p build-fuzz/logs
{
  echo "commit:  $(git rev-parse --short HEAD 2>/dev/null || echo unknown)$(git diff --quiet HEAD 2>/dev/null || echo ' (with uncommitted changes)')"
  echo "started: $(date -u '+%Y-%m-%d %H:%M UTC')"
  echo "command: bash scripts/fuzz.sh $*"
} > build-fuzz/logs/campaign.txt
for target in "${targets[@]}"; do
  bin="build-fuzz/bin/fuzz_${target}_${binary[$target]}"
  regressions=(tests/fuzz/regressions/"$target"/*)
  if [ -e "${regressions[0]}" ]; then
    echo "esif fuzz: ${#regressions[@]} kept ${target} regression inputs"
    "$bin" -rss_limit_mb=1024 "${regressions[@]}" 2>&1 | tail -n 2
  fi
  echo "esif fuzz: ${target} ${binary[$target]} (${budget[$target]})"
  # The rawlog reader's sandboxed child may use up to 60 s of CPU on a
  # corrupt entry before it is stopped (RawlogReader.cpp): its timeout is
  # above that, so an input the reader bounds by design is no finding.
  timeout=30; [ "$target" = rawlog ] && timeout=120
  # The whole log is kept for scripts/fuzz_report.sh, which ends each with libFuzzer's exit status.
  log=build-fuzz/logs/"$target".log
  status=0
  # shellcheck disable=SC2086  # the budget is several options
  "$bin" ${budget[$target]} -rss_limit_mb=1024 -max_len=65536 -timeout=$timeout \
    -artifact_prefix=build-fuzz/findings/"$target"- -print_final_stats=1 \
    build-fuzz/corpus/"$target" >"$log" 2>&1 || status=$?
  echo "exit $status" >>"$log"
  grep -E '^(#[0-9]+ *DONE|stat::number_of_executed_units|stat::peak_rss_mb|==|SUMMARY|ERROR)' "$log" || true
  # libFuzzer exits non-zero on a finding; pipefail is bypassed above so say it here.
  if ls build-fuzz/findings/"$target"-* >/dev/null 2>&1; then
    echo "esif fuzz: findings for the ${target} reader in build-fuzz/findings/" >&2
    exit 1
  fi
done
echo "esif fuzz: no finding"
