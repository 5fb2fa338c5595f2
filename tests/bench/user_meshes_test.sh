#!/usr/bin/env bash
# vkcollide_bench on the user's own meshes, then frontier.sh on its CSV (docs/results.md,
# "Your own meshes"). Two small generated meshes in a temporary folder:
#   user_meshes_test.sh bench VKCOLLIDE_BENCH FRONTIER_SH   the CSV's rows and recall column, no
#       file but the one asked for, a chart when gnuplot is installed, and the readers' errors
#       (missing file, no triangle, a NaN vertex) named with the file
#   user_meshes_test.sh frontier FRONTIER_SH                an empty CSV: exit 1, the file named
set -euo pipefail
mode="$1"
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
# Runs a command that must fail; its stderr must hold every later argument.
expectError() {
  local cmd="$1"; shift
  if eval "$cmd" > "$dir/out.txt" 2> "$dir/err.txt"; then fail "$cmd succeeded"; fi
  for want in "$@"; do grep -qF -- "$want" "$dir/err.txt" || { cat "$dir/err.txt" >&2; fail "$cmd: stderr lacks '$want'"; }; done
  echo "ok: $cmd -> $(head -1 "$dir/err.txt")"
}

if [ "$mode" = frontier ]; then
  frontier="$2"
  : > "$dir/empty.csv"
  expectError "bash '$frontier' '$dir/chart.png' '$dir/empty.csv'" "$dir/empty.csv" "is empty"
  echo "device,set,scene,variant,frame" > "$dir/header.csv"
  expectError "bash '$frontier' '$dir/chart.png' '$dir/header.csv'" "$dir/header.csv" "lacks the column(s) total_ms"
  [ ! -e "$dir/chart.png" ] || fail "a chart was written from an empty CSV"
  exit 0
fi

bench="$2"; frontier="$3"
# A unit cube (OFF) and a slab of 4 x 4 x 1 (OBJ, its large faces subdivided) moved so that
# its lower face cuts through the cube.
cat > "$dir/cube.off" <<'MESH'
OFF
8 6 0
0 0 0
1 0 0
1 1 0
0 1 0
0 0 1
1 0 1
1 1 1
0 1 1
4 0 3 2 1
4 4 5 6 7
4 0 1 5 4
4 1 2 6 5
4 2 3 7 6
4 3 0 4 7
MESH
{
  n=4  # quads per edge of each face
  echo "o slab"
  for k in 0 1; do for j in $(seq 0 $n); do for i in $(seq 0 $n); do echo "v $i $j $k"; done; done; done
  # the slab's large faces (z = 0, z = 1) as grids, then its four sides as single quads
  for k in 0 1; do for j in $(seq 0 $((n - 1))); do for i in $(seq 0 $((n - 1))); do
    a=$((k * (n + 1) * (n + 1) + j * (n + 1) + i + 1)); b=$((a + 1)); c=$((a + n + 2)); d=$((a + n + 1))
    if [ "$k" -eq 0 ]; then echo "f $a $d $c $b"; else echo "f $a $b $c $d"; fi
  done; done; done
  top=$(((n + 1) * (n + 1)))
  c00=1; c10=$((n + 1)); c11=$top; c01=$((top - n))
  echo "f $c00 $c10 $((c10 + top)) $((c00 + top))"; echo "f $c10 $c11 $((c11 + top)) $((c10 + top))"
  echo "f $c11 $c01 $((c01 + top)) $((c11 + top))"; echo "f $c01 $c00 $((c00 + top)) $((c01 + top))"
} > "$dir/slab.obj"

mkdir "$dir/run"
cd "$dir/run"
"$bench" --mesh "$dir/cube.off" --mesh "$dir/slab.obj:-1.5,-1.5,0.5" --frames 1 --resolutions 64 \
  --variants default,peeling,res-64 --csv "$dir/mine.csv" > "$dir/bench.txt" 2>&1 || { cat "$dir/bench.txt" >&2; fail "vkcollide_bench"; }
cat "$dir/bench.txt"
[ -z "$(ls -A "$dir/run")" ] || fail "vkcollide_bench wrote files it was not asked for: $(ls -A "$dir/run")"
# One row per variant (1 frame), scene named after the files, set "user", a recall per row,
# and the reliable method (default) finds every exact pair.
awk -F, '
  NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i
            if (!("recall" in c) || !("reference_pairs" in c)) { print "no recall or reference_pairs column"; bad = 1; exit } next }
  { ++rows; v[$c["variant"]] = 1
    if ($c["scene"] != "cube+slab" || $c["set"] != "user") { print "row " NR ": scene " $c["scene"] ", set " $c["set"]; bad = 1 }
    if ($c["recall"] !~ /^[0-9.]+$/) { print "row " NR ": recall " $c["recall"]; bad = 1 }
    if ($c["reference_pairs"] + 0 == 0) { print "row " NR ": the meshes do not cross"; bad = 1 }
    if ($c["variant"] == "default" && $c["recall"] + 0 != 1) { print "default recall " $c["recall"]; bad = 1 } }
  END { if (bad) exit 1
        if (rows != 3 || !("default" in v) || !("peeling" in v) || !("res-64" in v)) { print rows " rows, expected default, peeling, res-64"; exit 1 } }
' "$dir/mine.csv" || { cat "$dir/mine.csv" >&2; fail "the CSV"; }
echo "ok: $dir/mine.csv has default, peeling and res-64 with their recall"

if command -v gnuplot > /dev/null; then
  bash "$frontier" "$dir/chart.png" "$dir/mine.csv" || fail "frontier.sh on the CSV"
  [ -s "$dir/chart.png" ] || fail "no chart"
  echo "ok: frontier.sh charted it"
else
  echo "gnuplot missing (tools/bench/frontier.sh --install-deps): the chart is not tried"
fi

# Bad input: the reader's error, with the file's name, before any GPU work.
printf 'OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n' > "$dir/empty.off"
printf 'OFF\n3 1 0\n0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n' > "$dir/nan.off"
expectError "'$bench' --mesh '$dir/missing.off' --csv '$dir/x.csv'" "$dir/missing.off"
expectError "'$bench' --mesh '$dir/cube.off' --mesh '$dir/empty.off' --csv '$dir/x.csv'" "$dir/empty.off"
expectError "'$bench' --mesh '$dir/nan.off' --csv '$dir/x.csv'" "$dir/nan.off"
[ ! -e "$dir/x.csv" ] || fail "a CSV was written for bad input"
