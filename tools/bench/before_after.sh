#!/usr/bin/env bash
# A before/after table (CHANGELOG.md sums up the one of the reliable method): per scene, crossing recall, recall of all pairs, what
# was read back and the time of every stage, before -> after, from vkcollide_bench CSVs.
#   tools/bench/before_after.sh BEFORE.csv[,MORE.csv][@VARIANT] AFTER.csv[,MORE.csv][@VARIANT]
# VARIANT defaults to "default" on both sides. Means over frames >= 1 (tools/bench/steady.awk),
# recalls are found / reference pairs summed over those frames (shown as 100 % only when no
# pair was missed; "none": the reference has no crossing pair). "read back" is the CSV's `downloaded`: triangle records for the peeling
# method, the distinct triangles named by the pairs read back for the reliable method. Stage times: GPU
# (every pass's timestamps), read back (host), narrow phase (CPU), vertex update
# (updateVertices on deforming scenes; "–" under 0.01 ms: rigid and moving scenes do not call
# it) and the whole frame end to end. Rows follow AFTER's order;
# a scene missing on one side shows "–" there.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
[ $# -eq 2 ] || { sed -n '4p' "$0" | sed 's/^# //' >&2; exit 2; }
args=()
for side in before after; do
  spec="$1"; shift
  files="${spec%@*}"; variant=default; [ "$files" != "$spec" ] && variant="${spec##*@}"
  IFS=, read -r -a list <<< "$files"
  for f in "${list[@]}"; do
    [ -r "$f" ] || { echo "before_after.sh: cannot read $f" >&2; exit 1; }
    args+=("label=$side" "pick=^$variant\$" "$f")
  done
done
awk -f "$here/steady.awk" "${args[@]}" | awk -F'\t' '
function pct(r) { return r >= 1 ? "100 %" : sprintf("%.2f %%", r > 0.9999 ? 99.99 : 100 * r) }
function commas(v,   s, out) { s = sprintf("%.0f", v); out = ""
  while (length(s) > 3) { out = "," substr(s, length(s) - 2) out; s = substr(s, 1, length(s) - 3) }
  return s out }
function ms(v) { return v < 0.1 ? sprintf("%.3f", v) : sprintf("%.2f", v) }
function upd(v) { return v < 0.01 ? "–" : ms(v) }
function pair(a, b) { return a == b && (a == "–" || a == "none") ? a : a " → " b }
NR == 1 { next }
{ k = $3; side = $1
  if (side == "after" && !(k in seen)) { seen[k] = 1; order[++n] = k; set[k] = $4; tri[k] = $5 }
  has[side, k] = 1; cr[side, k] = $16 > 0 ? pct($14) : "none"; ar[side, k] = pct($15); dl[side, k] = commas($13)
  g[side, k] = ms($9); rb[side, k] = ms($10); nw[side, k] = ms($11); up[side, k] = upd($12); t[side, k] = ms($8)
  if (!(k in tri)) tri[k] = $5 }
function v(a, side, k) { return ((side, k) in has) ? a[side, k] : "–" }
END {
  print "| scene | set | triangles | crossing recall | recall, all pairs | read back (peeling: triangle records; reliable: distinct triangles in the pairs) | GPU ms | read-back ms | narrow ms | vertex update ms | end to end ms (update + detect) |"
  print "|---|---|---|---|---|---|---|---|---|---|---|"
  for (i = 1; i <= n; ++i) { k = order[i]
    printf "| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | **%s** |\n", k, set[k], commas(tri[k]),
      pair(v(cr, "before", k), v(cr, "after", k)), pair(v(ar, "before", k), v(ar, "after", k)),
      pair(v(dl, "before", k), v(dl, "after", k)), pair(v(g, "before", k), v(g, "after", k)),
      pair(v(rb, "before", k), v(rb, "after", k)), pair(v(nw, "before", k), v(nw, "after", k)),
      pair(v(up, "before", k), v(up, "after", k)), pair(v(t, "before", k), v(t, "after", k)) }
}'
