#!/usr/bin/env bash
# The README's quick start on a fresh Debian 12, timed as a newcomer meets it:
# a new root file system (`debootstrap --variant=minbase bookworm`: not even a
# compiler, so it installs more than a fresh machine needs), a clone of HEAD
# in it, then `bash scripts/demo.sh` and, with --tests, `bash scripts/test.sh`
# after it. Each is timed whole and split by its own output into package
# installation, build and run. Nothing is cached: no ccache, no packages,
# no build folder.
#
# Needs root, debootstrap (Debian package) and Debian's mirror; about 7 min,
# plus about 15 with --tests. The root file system is made under
# $ESIF_BENCH_OUT (default out/bench) and removed afterwards; its mounts live
# in a mount namespace of their own, so none outlives the script.
#
# usage: bench/fresh_machine.sh [--tests] [--update-docs]
set -euo pipefail
source "$(dirname "$0")/common.sh"
with_tests=0
for a in "${bench_args[@]}"; do
  case $a in
    --tests) with_tests=1 ;;
    *) echo "usage: bench/fresh_machine.sh [--tests] [--update-docs]" >&2; exit 2 ;;
  esac
done
[ "$(id -u)" -eq 0 ] || { echo "bench/fresh_machine.sh: needs root (debootstrap, chroot)" >&2; exit 1; }
command -v debootstrap >/dev/null || { echo "bench/fresh_machine.sh: debootstrap not found (apt-get install debootstrap)" >&2; exit 1; }

mkdir -p "$bench_out"
fresh=$(mktemp -d "$bench_out/fresh_root.XXXXXX")
trap 'rm -rf --one-file-system "$fresh"' EXIT
mirror=${DEBIAN_MIRROR:-http://deb.debian.org/debian}
debootstrap --variant=minbase bookworm "$fresh" "$mirror" >"$bench_out/fresh_debootstrap.log" 2>&1 ||
  { echo "bench/fresh_machine.sh: debootstrap failed, see $bench_out/fresh_debootstrap.log" >&2; exit 1; }
printf 'deb %s bookworm main\ndeb %s bookworm-updates main\ndeb http://deb.debian.org/debian-security bookworm-security main\n' \
  "$mirror" "$mirror" >"$fresh/etc/apt/sources.list"
cp /etc/resolv.conf "$fresh/etc/resolv.conf"
git clone -q "$root" "$fresh/root/esif"

# timed SCRIPT LOG: runs `bash scripts/SCRIPT` in the new root, each output
# line stamped with bash's $EPOCHREALTIME; the last line is its exit status.
timed() {
  local script=$1 log=$2
  # shellcheck disable=SC2016  # expanded by the bash in the new root
  printf '%s\n' 'cd /root/esif' 'echo "$EPOCHREALTIME start"' \
    "{ bash scripts/$script 2>&1; echo \"exit \$?\"; } | while IFS= read -r line; do echo \"\$EPOCHREALTIME \$line\"; done" \
    >"$fresh/root/timed.sh"
  # shellcheck disable=SC2016  # $1 is the inner bash's argument
  unshare --mount --propagation private bash -c '
    mount -t proc proc "$1/proc" && mount --rbind /dev "$1/dev" && mount --rbind /sys "$1/sys" &&
      chroot "$1" /usr/bin/env -i HOME=/root PATH=/usr/sbin:/usr/bin:/sbin:/bin DEBIAN_FRONTEND=noninteractive \
        bash /root/timed.sh' _ "$fresh" >"$log" 2>&1 || true
}

# phases LOG NAME: one table row from a stamped log: installation until the
# build's first progress line ("[1/N]"), the build until its last, then the run.
phases() {
  python3 - "$1" "$2" <<'PY'
import re, sys
log, name = sys.argv[1], sys.argv[2]
rows = []
for line in open(log, errors="replace"):
    m = re.match(r"([0-9]+\.[0-9]+) (.*)", line.rstrip("\n"))
    if m: rows.append((float(m.group(1)), m.group(2)))
if len(rows) < 2 or rows[0][1] != "start" or not rows[-1][1].startswith("exit "):
    sys.exit(f"bench/fresh_machine.sh: {name}: no start or exit status in {log}")
rows = [(t - rows[0][0], text) for t, text in rows]
status, end = rows[-1][1].split()[1], rows[-1][0]
build = [t for t, text in rows if re.match(r"\[\d+/\d+\]", text)]
installed = build[0] if build else 0.0
built = build[-1] if build else installed
installs = next((text for _, text in rows if text.startswith("esif setup: installing")), "")
packages = len(installs.split()) - 3 if installs else 0
print(f"| `bash scripts/{name}` | {'ok' if status == '0' else 'exit ' + status} | {end / 60:.1f} min | "
      f"{installed / 60:.1f} min ({packages} packages and their dependencies) | {(built - installed) / 60:.1f} min | {(end - built) / 60:.1f} min |")
PY
}

timed demo.sh "$bench_out/fresh_demo.log"
rows=$(phases "$bench_out/fresh_demo.log" demo.sh)
if [ "$with_tests" -eq 1 ]; then
  timed test.sh "$bench_out/fresh_test.log"
  rows+=$'\n'$(phases "$bench_out/fresh_test.log" test.sh)
fi
output=$(
  echo "| command | result | whole | package installation | build | run |"
  echo "|---|---|---:|---:|---:|---:|"
  echo "$rows"
  echo
  tests_note=""
  [ "$with_tests" -eq 0 ] || tests_note=" \`test.sh\` runs after \`demo.sh\`, the quick start's order, so it builds only the tests."
  echo "One run each on $(nproc) cores in a fresh \`debootstrap --variant=minbase bookworm\` root: no packages (not even a compiler), no ccache, no build folder.$tests_note Logs: \`${bench_out#"$root"/}/fresh_*.log\`."
)
echo "$output"
if [ "$update_docs" -eq 1 ]; then
  echo "$output" | results_page fresh_machine "The quick start on a fresh Debian 12" \
    "a fresh Debian 12 root file system (debootstrap minbase) and a clone of the checked-out commit"
fi
