# Variants side by side, one line per scene, from vkcollide_bench CSVs (frames >= 1, means):
#   awk -v VARS="default into sort-cpu device-only" -f tools/bench/variant_table.awk A.csv [B.csv ...]
# Each variant's cell is detect() total / GPU span / narrow phase in ms ("device-only":
# total / GPU span, it has no narrow phase); the last column is the lowest recall of any cell
# (device-only's recall is its pair count against the reference's).
BEGIN { FS = "," }
/^device,/ { delete c; for (i = 1; i <= NF; i++) c[$i] = i; next }
$c["frame"] >= 1 {
  k = $c["scene"]; kv = k SUBSEP $c["variant"]
  n[kv]++; t[kv] += $c["total_ms"]; g[kv] += $c["gpu_span_ms"]; nw[kv] += $c["narrow_ms"]; r[kv] += $c["recall"]
  p[k] = $c["reference_pairs"]; s[k] = $c["set"]
  if (!(k in o)) { o[k] = ++m; ks[m] = k }
}
END {
  nv = split(VARS, V, " ")
  head = sprintf("%-9s %-24s %8s |", "set", "scene", "pairs")
  for (j = 1; j <= nv; j++) head = head sprintf(" %-19s |", V[j])
  print head, "recall min"
  for (i = 1; i <= m; i++) {
    k = ks[i]; line = sprintf("%-9s %-24s %8d |", s[k], k, p[k]); rmin = 9
    for (j = 1; j <= nv; j++) {
      kv = k SUBSEP V[j]
      if (n[kv] == 0) { line = line sprintf(" %-19s |", "-"); continue }
      rr = r[kv] / n[kv]; if (rr < rmin) rmin = rr
      if (V[j] == "device-only") line = line sprintf(" %6.2f/%5.2f       |", t[kv] / n[kv], g[kv] / n[kv])
      else line = line sprintf(" %6.2f/%5.2f/%5.2f |", t[kv] / n[kv], g[kv] / n[kv], nw[kv] / n[kv])
    }
    print line, rmin
  }
}
