#!/usr/bin/env bash
# An `esif montecarlo --emit-jobs` list run by GNU parallel with the line of
# docs/user-guide.md, collected, equals the same campaign run by esif itself.
#   bash tests/engines/gnu_parallel.sh ESIF_BINARY SOURCE_DIR
# Skips (exit 77) without GNU parallel (scripts/setup.sh installs it).
set -euo pipefail
ESIF=$1
SOURCE_DIR=$2
# shellcheck source-path=SCRIPTDIR
source "$(dirname "$0")/common.sh"

command -v parallel > /dev/null || skip "GNU parallel not installed (Debian package parallel; scripts/setup.sh installs it)"
parallel --version 2> /dev/null | grep -q "GNU parallel" ||
  skip "'parallel' is not GNU parallel ($(command -v parallel); moreutils' parallel takes other options)"

engine_tmpdir
trap engine_cleanup EXIT
line=$(doc_line "GNU parallel")
engine_prepare
echo "running in the job list's folder: $line"
(cd "$T/engine" && bash -c "$line") || fail "'$line' failed (exit $?)"
engine_collect_and_compare
