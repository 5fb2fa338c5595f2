# A vkcollide_peer_bench CSV as rows of vkcollide_bench's CSV, the columns steady.awk reads,
# so that frontier.sh charts the peers beside vkcollide's variants:
#   awk -f tools/bench/peer_rows.awk peers.csv > rows.csv
# Each (peer, mode) is one variant, PEER/MODE (e.g. fcl-aabb/rigid-between); scenes keep the
# names the peer bench wrote, which for --scene files are vkcollide_bench --mesh's (both name
# them in user_scene.cpp), so a user's scene lands on one point per series in one panel.
# x: total_ms (build + query: the peer's whole frame). y: the peer bench measures recall of
# all pairs only, so the crossing-pair columns carry it too (found_crossing = recall x
# reference_pairs, reference_crossing = reference_pairs): on the crossing-recall panels a
# peer's point is its recall of all pairs. The set column (written by newer peer benches) says
# "user" for --scene scenes; older CSVs lack it and get "-" (panels then by scene name).
# Columns vkcollide_bench has and the peers do not (gpu_ms, readback_ms, ...) are 0.
# csv_check.awk has checked the file; rows without a frame number are dropped.
BEGIN {
  FS = ","; OFS = ","
  print "device,set,scene,variant,method,triangles,frame,total_ms,gpu_ms,readback_ms,narrow_ms,update_ms,downloaded," \
        "reference_pairs,reference_crossing,found_crossing,recall"
}
{ sub(/\r$/, "") }
/^#/ || /^[ \t]*$/ { next }
/^scene,/ { delete c; for (i = 1; i <= NF; ++i) c[$i] = i; next }
$c["frame"] ~ /^[0-9]+$/ {
  set = ("set" in c) && $c["set"] != "" ? $c["set"] : "-"
  # recall x reference_pairs is the count found; rounded, as the CSV's recall has 6 digits.
  found = int($c["recall"] * $c["reference_pairs"] + 0.5)
  print "peers", set, $c["scene"], $c["peer"] "/" $c["mode"], "-", $c["triangles"], $c["frame"], $c["total_ms"], 0, 0, 0, 0, 0,
        $c["reference_pairs"], $c["reference_pairs"], found, $c["recall"]
}
