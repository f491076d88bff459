# Sourced by the full-disk tests: what a run leaves in a folder must be whole.
#   check_whole DIR WHAT    fails (via fail, which the sourcing script defines) on a PNG that
#                           does not end with its IEND chunk, a JSON file that does not parse,
#                           or a temporary file ("*.tmp.*", host_tools/common/atomic_file.hpp)
check_whole() {
  local dir=$1 what=$2 f
  while IFS= read -r -d '' f; do
    [[ $(tail -c 12 "$f" | od -An -tx1 | tr -d ' \n') == 0000000049454e44ae426082 ]] ||
      fail "$what: $f is a truncated PNG"
  done < <(find "$dir" -name '*.png' -print0)
  while IFS= read -r -d '' f; do
    python3 -c 'import json,sys; json.load(open(sys.argv[1]))' "$f" 2> /dev/null ||
      fail "$what: $f is not whole JSON"
  done < <(find "$dir" -name '*.json' -print0)
  [[ -z $(find "$dir" -name '*.tmp.*') ]] || fail "$what: temporary files left: $(find "$dir" -name '*.tmp.*')"
}
