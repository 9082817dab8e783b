# Sourced by the bench scripts (from the repository root, with $esif set):
# vicpark_rawlog prints the path of out/data/vicpark.rawlog, importing it on
# first use from ${VICPARK_TXT:-../shared/data/victoria_park/victoria_park.txt}
# (third-party data, never committed), or exits naming the missing dataset.
vicpark_rawlog() {
  local out=out/data/vicpark.rawlog txt=${VICPARK_TXT:-../shared/data/victoria_park/victoria_park.txt}
  if [ ! -f "$out" ]; then
    [ -f "$txt" ] || { echo "bench/$(basename "$0"): $(realpath -m "$txt") not present (the Victoria Park dataset; set VICPARK_TXT)" >&2; exit 1; }
    mkdir -p out/data
    "$esif" import victoria-park --in "$txt" --out "$out" >&2
  fi
  echo "$out"
}
