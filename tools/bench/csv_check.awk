# Whether a CSV can be charted by frontier.sh: says what is wrong, naming the file, and exits 1.
#   awk -v file=NAME -v pick=REGEX -f tools/bench/csv_check.awk NAME
# Usable: a vkcollide_bench header (a line starting "device,") with the columns steady.awk reads,
# or a vkcollide_peer_bench header (a line starting "scene,") with those peer_rows.awk reads,
# then rows with a frame number, total_ms > 0 (the chart's x is logarithmic) and a recall in [0, 1],
# of a series that `pick` (frontier.sh's CSV@NAME@REGEX) matches: vkcollide_bench's variant, or
# the peers' PEER/MODE. `#` lines are comments. The first header decides which program the file
# is of; the two are not mixed in one file.
BEGIN {
  FS = ","; lines = 0; rows = 0; usable = 0
  need["device"] = "variant scene frame total_ms recall reference_pairs reference_crossing"
  need["scene"] = "scene peer mode frame total_ms recall reference_pairs triangles"
  prog["device"] = "vkcollide_bench"; prog["scene"] = "vkcollide_peer_bench"
  what["device"] = "variant"; what["scene"] = "peer"
}
{ sub(/\r$/, "") }
/^#/ || /^[ \t]*$/ { next }
{ ++lines }
(/^device,/ || /^scene,/) && (kind == "" || $0 ~ ("^" kind ",")) {
  kind = $1; delete c; for (i = 1; i <= NF; ++i) c[$i] = i
  n = split(need[kind], want, " "); missing = ""
  for (i = 1; i <= n; ++i) if (!(want[i] in c)) missing = missing (missing == "" ? "" : ", ") want[i]
  if (kind == "device" && !("found_crossing" in c) && !("recall_crossing" in c)) missing = missing (missing == "" ? "" : ", ") "found_crossing or recall_crossing"
  if (missing != "") { print "frontier.sh: " file ": its header lacks the column(s) " missing " (a CSV of " prog[kind] " --csv has them)" > "/dev/stderr"; bad = 1; exit 1 }
  next
}
kind == "" { print "frontier.sh: " file ": line " NR " comes before any header (vkcollide_bench's starts 'device,', vkcollide_peer_bench's 'scene,'): is it a CSV of either's --csv?" > "/dev/stderr"; bad = 1; exit 1 }
{
  ++rows
  if (kind == "scene") v = $c["peer"] "/" $c["mode"]
  else { v = $c["variant"]; if (!("set" in c) && "backend" in c) v = v "-" $c["backend"] }
  if (pick != "" && v !~ pick) next
  ++picked
  t = $c["total_ms"]; r = $c["recall"]; f = $c["frame"]
  if (f ~ /^[0-9]+$/ && t ~ /^[0-9.eE+-]+$/ && t + 0 > 0 && r ~ /^[0-9.eE+-]+$/ && r >= 0 && r <= 1) ++usable
}
END {
  if (bad) exit 1
  if (lines == 0) { print "frontier.sh: " file " is empty: expected a CSV of vkcollide_bench --csv or vkcollide_peer_bench --csv (a header line, then one row per timed frame)" > "/dev/stderr"; exit 1 }
  if (rows == 0) { print "frontier.sh: " file " has a header but no rows: " prog[kind] " wrote none (its stderr says which scene or " what[kind] " failed)" > "/dev/stderr"; exit 1 }
  if (pick != "" && picked == 0) { print "frontier.sh: " file ": none of its " rows " rows is of a " (kind == "scene" ? "PEER/MODE" : "variant") " matching '" pick "'" > "/dev/stderr"; exit 1 }
  if (usable == 0) { print "frontier.sh: " file ": none of its " rows " rows has a frame number, total_ms > 0 and a recall in [0, 1]" > "/dev/stderr"; exit 1 }
}
