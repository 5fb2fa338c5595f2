#!/usr/bin/env bash
# The speed-accuracy chart of docs/results.md: crossing-pair recall against end-to-end time per
# frame, one panel per scene kind, every settings variant its own series.
#   tools/bench/frontier.sh [--title T] [--legend NAME=TEXT]... [--link FROM:TO] OUT.png CSV[@NAME[@REGEX]]...
#   tools/bench/frontier.sh --install-deps        (gnuplot-nox from Debian's archive, if missing)
# Each point is one (scene, series), means over frames >= 1 (or frame 0 where it is the only
# one; tools/bench/steady.awk): x is total_ms (vertex update + detect: what an engine waits
# for), log scale; y is crossing pairs
# found / crossing pairs of the exact reference, on an axis spaced by the share missed (0, 90,
# 99, 99.9, 100 %) so that one pair lost in 10,000 still shows; on the face-to-face contact
# scenes, which have next to no crossing pairs, and on the user's own scenes (vkcollide_bench
# --mesh: set "user", their own panel), recall of all pairs (touching included).
# A CSV of vkcollide_peer_bench --csv (FCL, Embree, CGAL, vkcollide as a peer; told by its
# header, which starts "scene,") charts beside them: tools/bench/peer_rows.awk makes each
# peer and mode a series PEER/MODE (e.g. fcl-aabb/rigid-between; @REGEX matches these), x its
# total_ms (build + query), y its recall of all pairs on every panel (it measures no other);
# its --scene files are named and set as vkcollide_bench --mesh's, so they share the panel:
#   tools/bench/frontier.sh mine.png mine.csv peers.csv
# Series: a CSV's variants by name (default = the reliable method, peeling, paper-sep, ...), or
# with @NAME every row of that CSV is series NAME (a CSV of another build, e.g. the defaults
# before), and @REGEX keeps only the variants it matches (CSVs of the 2026-11-22 sweep: VARIANT-BACKEND, e.g.
# ^single-compute$). --legend gives a series its legend text. Resolution sweeps (res-N and
# cells-N variants; the 2026-11-22 sweep's CSVs over --resolutions) are dashed lines, one per scene. --link
# draws a grey line per scene from series FROM's point to TO's and names the scene at FROM
# (otherwise at its slowest point). Filled markers: tuning scenes; open markers and italic
# names: held-out scenes (never used to choose anything). Panels: frontier.awk's kind().
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
usage() { sed -n '4,5p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 2; }
title="Speed against accuracy per scene kind: recall (as each panel says) against end-to-end ms per frame"
link=""
tmp=$(mktemp -d)
if [ -n "${FRONTIER_KEEP:-}" ]; then echo "frontier.sh: keeping $tmp" >&2; else trap 'rm -rf "$tmp"' EXIT; fi
: > "$tmp/legends.tsv"
while [ $# -gt 0 ]; do
  case "$1" in
    --title) title="$2"; shift 2 ;;
    --legend) printf '%s\t%s\n' "${2%%=*}" "${2#*=}" >> "$tmp/legends.tsv"; shift 2 ;;
    --link) link="$2"; shift 2 ;;
    --install-deps)
      dpkg-query -W -f='${Status}' gnuplot-nox 2>/dev/null | grep -q "install ok installed" && exit 0
      sudo=""; [ "$(id -u)" -eq 0 ] || sudo="sudo"
      $sudo apt-get update -q
      DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends gnuplot-nox
      exit 0 ;;
    --*) usage ;;
    *) break ;;
  esac
done
[ $# -ge 2 ] || usage
out="$1"; shift

# Every CSV is checked before gnuplot runs: an empty or foreign file is named with what it
# lacks (gnuplot would only say "empty x range").
args=()   # steady.awk takes label= and pick= before each file
for spec in "$@"; do
  IFS=@ read -r file name pick <<< "$spec"
  [ -f "$file" ] && [ -r "$file" ] || { echo "frontier.sh: cannot read $file (expected a CSV of vkcollide_bench --csv or vkcollide_peer_bench --csv)" >&2; exit 1; }
  awk -v file="$file" -v pick="$pick" -f "$here/csv_check.awk" "$file"
  # A peer bench CSV (its first line that is no comment starts "scene,") enters steady.awk as
  # vkcollide_bench rows (peer_rows.awk); steady.awk's pick then matches PEER/MODE.
  if awk '/^#/ || /^[ \t\r]*$/ { next } { exit !/^scene,/ }' "$file"; then
    rows="$tmp/peers_${#args[@]}.csv"
    awk -f "$here/peer_rows.awk" "$file" > "$rows"
    file="$rows"
  fi
  args+=("label=$name" "pick=$pick" "$file")
done
awk -f "$here/steady.awk" "${args[@]}" > "$tmp/steady.tsv"
awk -F'\t' -v tmp="$tmp" -v out="$out" -v title="$title" -v link="$link" -f "$here/frontier.awk" "$tmp/legends.tsv" "$tmp/steady.tsv"
# Checked only now, so that without gnuplot the data it would get is still made (FRONTIER_KEEP=1
# keeps it: the tests read it).
command -v gnuplot >/dev/null || { echo "frontier.sh: gnuplot missing: run tools/bench/frontier.sh --install-deps" >&2; exit 1; }
gnuplot "$tmp/frontier.gp"
echo "frontier.sh: wrote $out"
