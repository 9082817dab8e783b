# Sourced by the bench scripts after bench/common.sh (from the repository
# root, with $esif set). The Victoria Park dataset is third-party data: neither
# it nor a rawlog made from it is committed (../shared/data/victoria_park/README.md
# says where it comes from).
#
# vicpark_rawlog prints the path of the imported rawlog, ${VICPARK_RAWLOG:-out/data/vicpark.rawlog},
# importing it on first use with the importer's defaults (range 0.5 m,
# bearing 2 deg, as the README's "Running a real dataset") from
# ${VICPARK_TXT:-../shared/data/victoria_park/victoria_park.txt}, or exits
# naming the missing dataset. The importer writes atomically: an interrupted
# run leaves no partial file.
vicpark_default_rawlog() { echo "${VICPARK_RAWLOG:-out/data/vicpark.rawlog}"; }

vicpark_rawlog() {
  local out txt=${VICPARK_TXT:-../shared/data/victoria_park/victoria_park.txt}
  out=$(vicpark_default_rawlog)
  if [ ! -f "$out" ]; then
    [ -f "$txt" ] || { echo "bench/$(basename "$0"): $(realpath -m "$txt") not present (the Victoria Park dataset; set VICPARK_TXT)" >&2; exit 1; }
    mkdir -p "$(dirname "$out")"
    "$esif" import victoria-park --in "$txt" --out "$out" >&2
  fi
  echo "$out"
}

# vicpark_description RAWLOG: what RAWLOG is, for the header of a results page.
vicpark_description() {
  local txt=${VICPARK_TXT:-../shared/data/victoria_park/victoria_park.txt}
  if [ "$(realpath -m "$1")" = "$(realpath -m "$(vicpark_default_rawlog)")" ]; then
    printf 'Victoria Park, imported by `esif import victoria-park` with its defaults from `%s` (third-party data, see `../shared/data/victoria_park/README.md`)' \
      "$(realpath -m --relative-to="$root" "$txt")"
  else
    printf 'the Victoria Park rawlog `%s`' "$1"
  fi
}
