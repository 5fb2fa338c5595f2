#!/usr/bin/env bash
# vkcollide_bench on the user's own meshes, then frontier.sh on its CSV (docs/results.md,
# "Your own meshes"). Two small generated meshes in a temporary folder:
#   user_meshes_test.sh bench VKCOLLIDE_BENCH FRONTIER_SH   the CSV's rows and recall column, no
#       file but the one asked for, a chart when gnuplot is installed, and the readers' errors
#       (missing file, no triangle, a NaN vertex) named with the file
#   user_meshes_test.sh frontier FRONTIER_SH                an empty CSV: exit 1, the file named
#   user_meshes_test.sh obj VKCOLLIDE_BENCH VKCOLLIDE_CLI   --write-obj: a built-in scene (the touching stack,
#       scaled down) written as OBJ, which the CLI reads and detects with exactly the pairs of the
#       bench's exact reference; a folder it cannot create is named
#   user_meshes_test.sh peers FRONTIER_SH                   a vkcollide_peer_bench CSV charted beside a
#       vkcollide_bench one (both written here): the peers' series in the data gnuplot gets, on
#       the user's panel; the drawing only where gnuplot is installed; peer CSVs without rows
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

if [ "$mode" = obj ]; then
  bench="$2"; cli="$3"
  "$bench" --scenes stack-touching --scale 0.1 --write-obj "$dir/scenes" > "$dir/out.txt" || fail "--write-obj failed"
  [ -s "$dir/scenes/stack-touching.obj" ] || fail "no $dir/scenes/stack-touching.obj"
  objects=$(grep -c '^o ' "$dir/scenes/stack-touching.obj")
  grep -qF "stack-touching.obj: $objects objects" "$dir/out.txt" || { cat "$dir/out.txt"; fail "the objects written are not the ones reported"; }
  want=$("$bench" --scenes stack-touching --scale 0.1 --reference-only --no-cache | awk '$2 == "stack-touching" { print $6 }')
  got=$("$cli" detect "$dir/scenes/stack-touching.obj" --quiet | awk -F': ' '/^colliding triangle pairs/ { print $2 }')
  echo "stack-touching at scale 0.1: $objects objects, reference $want pairs, the CLI on the OBJ $got"
  [ -n "$want" ] && [ "$want" -gt 0 ] && [ "$got" = "$want" ] || fail "the CLI found $got pairs in the OBJ, the reference has $want"
  : > "$dir/file"
  expectError "'$bench' --scenes stack-touching --scale 0.1 --write-obj '$dir/file/sub'" "--write-obj" "$dir/file/sub"
  exit 0
fi

if [ "$mode" = peers ]; then
  frontier="$2"
  # vkcollide_bench's header (tools/bench/vkcollide_bench.cpp) and rows given by column name,
  # the rest 0: the user's scene cube+slab, two variants, frames 0 and 1.
  header="device,set,scene,motion,triangles,objects,gpu_objects,scale,variant,frame,backend,resolution,direction,axes,coverage,dual,layer_cap,packing,open,async,depth_complexity,layers,peel_passes,sampling_ms,merging_ms,separation_ms,packing_ms,gpu_ms,readback_ms,narrow_ms,update_ms,total_ms,collision_rays,downloaded,pot_colliding,tests,positive_tests,pairs,reference_pairs,reference_crossing,found_crossing,recall,recall_crossing,precision,gpu_mib,host_peak_mib,narrow_threads,reference_s,reference_cached,method,footprints_ms,pairing_ms,filtering_ms,cell_candidates,cell_survivors,settings_note,cell_entries,cell_duplicates,cell_filtered,cell_deep_cells,cell_max_cell,gpu_exact_tests,cpu_exact_tests,gpu_span_ms,sorting_ms"
  awk -v header="$header" 'BEGIN { n = split(header, h, ","); print header }
    { delete v; for (i = 1; i <= NF; ++i) { split($i, kv, "="); v[kv[1]] = kv[2] }
      line = ""; for (i = 1; i <= n; ++i) line = line (i > 1 ? "," : "") (h[i] in v ? v[h[i]] : 0); print line }' > "$dir/mine.csv" <<'ROWS'
device=lavapipe set=user scene=cube+slab variant=default method=reliable frame=0 total_ms=9 reference_pairs=40 reference_crossing=30 found_crossing=30 recall=1
device=lavapipe set=user scene=cube+slab variant=default method=reliable frame=1 total_ms=2 reference_pairs=40 reference_crossing=30 found_crossing=30 recall=1
device=lavapipe set=user scene=cube+slab variant=peeling method=peeling frame=0 total_ms=8 reference_pairs=40 reference_crossing=30 found_crossing=29 recall=0.95
device=lavapipe set=user scene=cube+slab variant=peeling method=peeling frame=1 total_ms=1 reference_pairs=40 reference_crossing=30 found_crossing=29 recall=0.95
ROWS
  # vkcollide_peer_bench's (tools/bench/peer_bench.cpp): the same scene, two peers, and a
  # built-in scene of the tuning set.
  cat > "$dir/peers.csv" <<'CSV'
# vkcollide_peer_bench: test CPU, 2 hardware threads; peers run with 2 threads
scene,triangles,objects,peer,mode,frame,build_ms,query_ms,total_ms,pairs,recall,precision,candidates,memory_mb,reference_pairs,threads,set
cube+slab,108,2,fcl-aabb,rigid-between,0,3.000,1.000,4.000,36,0.900000,1.000000,0,0.1,40,2,user
cube+slab,108,2,fcl-aabb,rigid-between,1,2.000,1.000,3.000,36,0.900000,1.000000,0,0.1,40,2,user
cube+slab,108,2,fcl-aabb,rigid-between,2,4.000,1.000,5.000,36,0.900000,1.000000,0,0.1,40,2,user
cube+slab,108,2,embree,rigid-self,0,1.000,1.000,2.000,40,1.000000,1.000000,0,0.1,40,2,user
cube+slab,108,2,embree,rigid-self,1,1.000,0.500,1.500,40,1.000000,1.000000,0,0.1,40,2,user
spheres-8x10K,79520,8,cgal,rigid-between,0,50.000,50.000,100.000,2882,1.000000,1.000000,0,12.4,2882,2,tuning
spheres-8x10K,79520,8,cgal,rigid-between,1,40.000,40.000,80.000,2882,1.000000,1.000000,0,12.4,2882,2,tuning
CSV
  status=0
  FRONTIER_KEEP=1 bash "$frontier" "$dir/chart.png" "$dir/mine.csv" "$dir/peers.csv" > "$dir/out.txt" 2> "$dir/err.txt" || status=$?
  kept=$(sed -n 's/^frontier.sh: keeping //p' "$dir/err.txt")
  [ -n "$kept" ] && [ -d "$kept" ] || { cat "$dir/err.txt" >&2; fail "frontier.sh kept no data folder"; }
  trap 'rm -rf "$dir" "$kept"' EXIT
  if command -v gnuplot > /dev/null; then
    [ "$status" -eq 0 ] && [ -s "$dir/chart.png" ] || { cat "$dir/err.txt" >&2; fail "frontier.sh on a vkcollide_bench and a peer CSV"; }
    echo "ok: frontier.sh charted both"
  else
    grep -q "gnuplot missing" "$dir/err.txt" || { cat "$dir/err.txt" >&2; fail "frontier.sh without gnuplot"; }
    echo "gnuplot missing (tools/bench/frontier.sh --install-deps): the drawing is not tried, its data is"
  fi
  # steady.awk's means over frames >= 1: a series per peer and mode, the scene named and set as
  # vkcollide_bench's, x = total_ms, the recall (all pairs) in both recall columns.
  awk -F'\t' '
    NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next }
    { got[$c["variant"] "|" $c["scene"] "|" $c["set"]] = $c["total_ms"] " " $c["recall"] " " $c["crossing_recall"] }
    END {
      want["default|cube+slab|user"] = "2 1 1"; want["peeling|cube+slab|user"] = "1 0.95 0.966667"
      want["fcl-aabb/rigid-between|cube+slab|user"] = "4 0.9 0.9"; want["embree/rigid-self|cube+slab|user"] = "1.5 1 1"
      want["cgal/rigid-between|spheres-8x10K|tuning"] = "80 1 1"
      for (k in want) if (got[k] != want[k]) { print k ": got \"" got[k] "\", want \"" want[k] "\""; bad = 1 }
      for (k in got) if (!(k in want)) { print "unexpected " k; bad = 1 }
      exit bad }' "$kept/steady.tsv" || { cat "$kept/steady.tsv" >&2; fail "steady.awk's lines"; }
  # frontier.awk: the user's panel (10) has a point file per series, 4 of them, and the legend names the peers.
  [ "$(ls "$kept" | grep -c '^pts_10_')" -eq 4 ] || { ls "$kept" >&2; fail "the user's panel lacks series"; }
  for series in fcl-aabb/rigid-between embree/rigid-self cgal/rigid-between; do
    grep -qF "title '$series'" "$kept/frontier.gp" || fail "no legend entry for $series in frontier.gp"
  done
  echo "ok: the peers' series are in the chart's data, cube+slab on the user's panel"
  # A peer CSV without rows, without a column, without a usable row.
  head -2 "$dir/peers.csv" > "$dir/header.csv"
  expectError "bash '$frontier' '$dir/x.png' '$dir/header.csv'" "$dir/header.csv" "has a header but no rows" "vkcollide_peer_bench"
  sed 's/,total_ms,/,time_ms,/' "$dir/peers.csv" > "$dir/column.csv"
  expectError "bash '$frontier' '$dir/x.png' '$dir/column.csv'" "$dir/column.csv" "lacks the column(s) total_ms" "vkcollide_peer_bench"
  sed '3,$s/,0\.900000,/,1.5,/; 3,$s/,1\.000000,1\.000000,/,2,1,/' "$dir/peers.csv" > "$dir/recall.csv"
  expectError "bash '$frontier' '$dir/x.png' '$dir/recall.csv'" "$dir/recall.csv" "none of its 7 rows has"
  [ ! -e "$dir/x.png" ] || fail "a chart was written from a peer CSV without usable rows"
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
