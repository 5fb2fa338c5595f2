# Steady-state means of vkcollide_bench CSVs, one tab-separated line per (label, variant, scene,
# and resolution for the resolution sweeps of 2026-11-22), shared by frontier.sh and before_after.sh:
#   awk -f tools/bench/steady.awk [label=NAME] [pick=REGEX] A.csv [label=OTHER] B.csv ...
# Frames >= 1 only (frame 0 allocates; tools/bench/steady_table.sh does the same), but frame 0
# where it is the only frame (vkcollide_bench --frames 1 on a rigid scene). Times and
# counts are means over those frames; recalls are found / total pairs summed over them, so a
# deforming scene weighs its frames by their pairs. Columns are found by name, so every CSV
# generation mixes: the 2026-11-22 sweep's CSVs (no `set`, no `found_crossing`; variants single/dual per
# backend over --resolutions) get variant VARIANT-BACKEND and one line per resolution, and
# their crossing pairs found are recall_crossing x reference_crossing. `label` names the file's
# series (empty: the variant alone) and `pick`, a regular expression, keeps only the variants
# (VARIANT-BACKEND in the 2026-11-22 CSVs) it matches; both stay set for the files after them.
# Output columns (a header line first):
#   label variant scene set triangles resolution frames total_ms gpu_ms readback_ms narrow_ms
#   update_ms downloaded crossing_recall recall reference_crossing reference_pairs method
# resolution is "-" unless the row is a point of a resolution sweep; recalls are fractions, 1
# where the reference has no such pair; set is "-" in CSVs without one; method likewise.
BEGIN { FS = ","; OFS = "\t"
        print "label", "variant", "scene", "set", "triangles", "resolution", "frames", "total_ms", "gpu_ms", "readback_ms",
              "narrow_ms", "update_ms", "downloaded", "crossing_recall", "recall", "reference_crossing", "reference_pairs", "method" }
/^#/ { next }
/^device,/ { delete c; for (i = 1; i <= NF; ++i) c[$i] = i; sweep = !("set" in c); next }
$c["frame"] >= 0 {
  v = $c["variant"]; r = "-"
  if (sweep) { v = v "-" $c["backend"]; r = $c["resolution"] }
  if (pick != "" && v !~ pick) next
  key = label SUBSEP v SUBSEP $c["scene"] SUBSEP r
  if (!(key in seen)) { seen[key] = 1; order[++count] = key }
  # Frame 0 sums under its own key, used only where no frame >= 1 came.
  k = ($c["frame"] >= 1 ? "" : "0") SUBSEP key
  if (!(k in n)) { set[k] = ("set" in c) ? $c["set"] : "-"; meth[k] = ("method" in c) ? $c["method"] : "-" }
  n[k]++; tri[k] = $c["triangles"]
  t[k] += $c["total_ms"]; g[k] += $c["gpu_ms"]; rb[k] += $c["readback_ms"]; nw[k] += $c["narrow_ms"]; u[k] += $c["update_ms"]
  dl[k] += $c["downloaded"]
  rc[k] += $c["reference_crossing"]; rp[k] += $c["reference_pairs"]
  fc[k] += (("found_crossing" in c) ? $c["found_crossing"] : $c["recall_crossing"] * $c["reference_crossing"])
  fp[k] += $c["recall"] * $c["reference_pairs"]
}
END {
  for (i = 1; i <= count; ++i) {
    k = "" SUBSEP order[i]; if (!(k in n)) k = "0" SUBSEP order[i]
    split(order[i], a, SUBSEP); m = n[k]
    print a[1], a[2], a[3], set[k], tri[k], a[4], m, t[k] / m, g[k] / m, rb[k] / m, nw[k] / m, u[k] / m, dl[k] / m,
          (rc[k] > 0 ? fc[k] / rc[k] : 1), (rp[k] > 0 ? fp[k] / rp[k] : 1), rc[k], rp[k], meth[k]
  }
}
