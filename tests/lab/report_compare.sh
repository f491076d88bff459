# Sourced by the curio-lab CLI tests: same_report A B fails (exit 1, naming the file) unless
# the two output folders hold the same report, file for file: byte for byte except the wall
# times (summary.json's wall_seconds and seconds_per_run lines, summary.md's line 3), the
# folders' names in plot scripts (a copied folder's scripts name the original), and records/ (each record keeps its run's own timings).
same_report() {
  local a=$1 b=$2 f
  local fa fb
  fa=$(cd "$a" && find . -path ./records -prune -o -type f -print | sort)
  fb=$(cd "$b" && find . -path ./records -prune -o -type f -print | sort)
  [[ $fa == "$fb" ]] || { echo "FAIL: $a and $b hold different files:"; diff <(echo "$fa") <(echo "$fb"); exit 1; }
  for f in $fa; do
    case $f in
      ./summary.json)
        cmp -s <(grep -v -e '"wall_seconds"' -e '"seconds_per_run"' "$a/$f") \
               <(grep -v -e '"wall_seconds"' -e '"seconds_per_run"' "$b/$f") ;;
      ./summary.md) cmp -s <(sed 3d "$a/$f") <(sed 3d "$b/$f") ;;
      *.gp) cmp -s <(sed -e "s|$a/|OUT/|g" -e "s|$b/|OUT/|g" "$a/$f") \
                   <(sed -e "s|$a/|OUT/|g" -e "s|$b/|OUT/|g" "$b/$f") ;;
      *) cmp -s "$a/$f" "$b/$f" ;;
    esac || { echo "FAIL: $f differs between $a and $b"; exit 1; }
  done
  [[ $(ls "$a/records" | wc -l) == $(ls "$b/records" | wc -l) ]] ||
    { echo "FAIL: $a and $b hold different numbers of records"; exit 1; }
}

# Fails unless the folder holds no temporary file (a writer killed mid-way leaves *.tmp.*).
no_temp_files() {
  local left
  left=$(find "$1" -name '*.tmp.*')
  [[ -z $left ]] || { echo "FAIL: temporary files left in $1: $left"; exit 1; }
}
