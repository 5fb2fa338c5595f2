# frontier.sh's layout: reads the legend table (NAME \t TEXT) and steady.awk's lines, writes
# one data file per (panel, series, tuning/held-out) under tmp and the gnuplot script tmp/frontier.gp.
#   awk -F'\t' -v tmp=DIR -v out=PNG -v title=TEXT -v link=FROM:TO -f frontier.awk legends.tsv steady.tsv
# Panels are scene kinds (kind() below, by scene name); series are named by the CSV's name
# (frontier.sh's CSV@NAME) or else the variant. link draws a thin line per scene from its
# FROM point to its TO point and puts the scene's name at FROM (without it: at the slowest).
# Scene names are placed greedily so that no two overlap (in an estimate of the panel's pixels).

# Scene kinds: the user's own scenes (vkcollide_bench --mesh: set "user"), the bench set's, then the
# grids of the 2026-11-22 sweep; "other" catches scenes added later.
function kind(s, set) {
  if (set == "user") return 10
  if (s ~ /^(drape-flap|ball-cloth)/) return 1
  if (s ~ /^twisted-/) return 2
  if (s ~ /^pile-/) return 3
  if (s ~ /^deep-/ || s ~ /^(spheres-2x640K|bunnies-2x75K-deep|bunnies-2x75K-twin)$/) return 4
  if (s ~ /^deform-/) return 5
  if (s ~ /^(spheres|bunnies)-/) return 6
  if (s ~ /^mixed-gpu/) return 7
  if (s ~ /-touching$/) return 8
  return 9
}
function q(t) { gsub(/\047/, "\047\047", t); return "\047" t "\047" }   # gnuplot single-quoted string
function log10(v) { return log(v) / log(10) }
# The y axis: recall spaced by the fraction missed; 1e-4 keeps 100 % finite.
function fy(r) { return -log10(1.0001 - r) }
function fyinv(t) { return 1.0001 - 10 ^ (-t) }
# Estimated pixel position in the current panel (plo, phi: log10 of its x range)
function gpx(x) { return (log10(x) - plo) / (phi - plo) * pw }
function gpy(y) { return (fy(y) - fy(ylo)) / (fy(yhi) - fy(ylo)) * ph }
function overlaps(k, x0, x1, y0, y1,   i) {
  for (i = 1; i <= nbox[k]; ++i)
    if (x0 < bx1[k, i] && bx0[k, i] < x1 && y0 < by1[k, i] && by0[k, i] < y1) return 1
  return 0
}
BEGIN {
  ktitle[1] = "cloth: draped with folds, a ball through it"; ktitle[2] = "one mesh twisted into itself"
  ktitle[3] = "piles of 60-240 rigid meshes";  ktitle[4] = "deep overlaps (1.3M-2.6M triangles), twin meshes"
  ktitle[5] = "deforming pairs (mean of the frames)";  ktitle[6] = "grids of spheres and bunnies"
  ktitle[7] = "host and engine GPU meshes";  ktitle[8] = "face-to-face contacts: recall of ALL pairs"
  ktitle[9] = "other scenes";  ktitle[10] = "your meshes: recall of ALL pairs"
  # Known variants (tools/bench/bench_variants.cpp): legend and style; other series take the palette.
  desc["default"] = "default: the reliable method";  col["default"] = "#1a9850"; pt["default"] = 7
  desc["reliable"] = "the reliable method";           col["reliable"] = "#1a9850"; pt["reliable"] = 7
  desc["peeling"] = "peeling (the paper), depth-aware separation"; col["peeling"] = "#2166ac"; pt["peeling"] = 5
  desc["depth-sep"] = desc["peeling"]; col["depth-sep"] = col["peeling"]; pt["depth-sep"] = 5
  desc["paper-sep"] = "peeling, the paper's separation"; col["paper-sep"] = "#e08214"; pt["paper-sep"] = 9
  npal = split("#b2182b #762a83 #8c510a #01665e #c51b7d #4d4d4d", pal, " "); split("13 15 11 3 1 2", ppt, " ")
  split(link, lk, ":"); lfrom = lk[1]; lto = lk[2]
  cw = 6; lh = 12                                # font-8 text in pixels (estimates)
  ylo = -0.3; yhi = 1.00004
}
FILENAME == ARGV[1] { legend[$1] = $2; next }
FNR == 1 { next }
{ label = $1; variant = $2; scene = $3; res = $6; x = $8 + 0; method = $18
  if (x <= 0) next  # no place on a log axis (csv_check.awk made sure some row has one)
  k = kind(scene, $4); y = k == 8 || k == 10 ? $15 : $14
  sweep = res != "-"
  if (!sweep && variant ~ /^(res|cells)-[0-9]+$/) { sweep = 1; res = variant; sub(/^.*-/, "", res); sub(/-[0-9]+$/, "", variant) }
  name = label != "" ? label : (sweep ? variant "-sweep" : variant)
  if (!(name in sid)) {
    s = sid[name] = ++ns; sname[s] = name; ssweep[s] = sweep
    if (name in legend) sdesc[s] = legend[name]
    else if (variant in desc && label == "" && !sweep) sdesc[s] = desc[variant]
    else if (variant == "res" && sweep) sdesc[s] = "peeling, resolution sweep"
    else if (variant == "cells" && sweep) sdesc[s] = "reliable, cell-resolution sweep"
    else sdesc[s] = method != "-" && method != variant ? name " (" method ")" : name
    if (sweep) { ++nsw; scol[s] = nsw == 1 ? "#9a9a9a" : pal[(nsw - 2) % npal + 1]; spt[s] = 7 }
    else if (label == "" && variant in col) { scol[s] = col[variant]; spt[s] = pt[variant] }
    else { ++np; scol[s] = pal[(np - 1) % npal + 1]; spt[s] = ppt[(np - 1) % npal + 1] }
  }
  s = sid[name]; used[k] = 1
  if (!(k in xmin) || x < xmin[k]) xmin[k] = x
  if (!(k in xmax) || x > xmax[k]) xmax[k] = x
  held = $4 == "held-out"; if (held) heldscene[scene] = 1
  ++npt[k]; ptx[k, npt[k]] = x; pty[k, npt[k]] = y
  if (sweep) {
    print scene, res, x, y > (tmp "/raw_" k "_" s); swk[k, s] = 1
    if (!((k, scene) in sslow) || x > sslow[k, scene]) { sslow[k, scene] = x; sslowy[k, scene] = y }
    if (!((k, scene) in sseen)) { sseen[k, scene] = 1; kss[k] = kss[k] " " scene }
    next
  }
  print x, y > (tmp "/pts_" k "_" s "_" held); have[k, s, held] = 1
  if (!((k, scene) in seen)) { seen[k, scene] = 1; ksc[k] = ksc[k] " " scene }
  px[k, scene, name] = x; py[k, scene, name] = y
  if (!((k, scene) in slow) || x > slow[k, scene]) { slow[k, scene] = x; slowy[k, scene] = y }
}
END {
  order = "10 1 2 3 4 5 6 7 8 9"; nk = split(order, ko, " ")
  npanel = 0; for (i = 1; i <= nk; ++i) if (ko[i] in used) panel[++npanel] = ko[i]
  slots = npanel + 1; cols = slots <= 4 ? slots : (slots <= 9 ? 3 : 4); rows = int((slots + cols - 1) / cols)
  # Screen: the plot areas (margins and spacing as fractions), hence each panel's pixels.
  W = 470 * cols; H = 350 * rows + 40; ml = 0.06; mr = 0.99; mb = 0.12 / rows; mt = 1 - 0.17 / rows; sx = 0.08; sy = 0.24 / rows
  pw = ((mr - ml) - (cols - 1) * sx) / cols * W; ph = ((mt - mb) - (rows - 1) * sy) / rows * H
  gp = tmp "/frontier.gp"
  printf "set terminal pngcairo enhanced size %d,%d font \",10\"\n", W, H > gp
  print "set output " q(out) >> gp
  printf "set multiplot layout %d,%d title %s font \",13\" margins %g,%g,%g,%g spacing %g,%g\n", rows, cols, q(title), ml, mr, mb, mt, sx, sy >> gp
  print "set yrange [" ylo ":" yhi "]; set ytics (\"0 %%\" 0, \"90 %%\" 0.9, \"99 %%\" 0.99, \"99.9 %%\" 0.999, \"100 %%\" 1); set mytics 1" >> gp
  print "set nonlinear y via -log10(1.0001 - y) inverse 1.0001 - 10**(-y)" >> gp
  print "set logscale x; set xtics (0.1, 0.2, 0.5, 1, 2, 5, 10, 20, 50, 100, 200, 500, 1000, 2000, 5000, 10000, 20000, 50000); set mxtics default" >> gp
  print "set grid xtics ytics lc rgb \"#e4e4e4\"; set key off; set format x \"%g\"" >> gp
  print "set xlabel \"ms per frame, end to end (log)\" offset 0,0.6 font \",9\"" >> gp
  for (i = 1; i <= npanel; ++i) {
    k = panel[i]; lo = xmin[k] / 1.5; hi = xmax[k] * 1.5; plo = log10(lo); phi = log10(hi)
    print "set title " q(ktitle[k]) " font \",11\" offset 0,-0.4" >> gp
    print "set ylabel " q(k == 8 || k == 10 ? "recall of all pairs" : "crossing-pair recall") " offset 2.2,0 font \",9\"" >> gp
    printf "set xrange [%g:%g]\n", lo, hi >> gp
    # Lines FROM -> TO per scene, and each scene's name where it sits best.
    lf = tmp "/links_" k; nl = 0
    nf[0] = tmp "/names_" k "_left"; nf[1] = tmp "/names_" k "_right"; delete hasn
    for (j = 1; j <= npt[k]; ++j) { g = gpx(ptx[k, j]); h = gpy(pty[k, j])
      ++nbox[k]; bx0[k, nbox[k]] = g - 5; bx1[k, nbox[k]] = g + 5; by0[k, nbox[k]] = h - 5; by1[k, nbox[k]] = h + 5 }
    n = split(substr(ksc[k], 2), sc, " ")
    # scenes with sweep points only: named at their slowest sweep point
    m = split(substr(kss[k], 2), ss, " ")
    for (j = 1; j <= m; ++j) if (!((k, ss[j]) in seen)) { sc[++n] = ss[j]; slow[k, ss[j]] = sslow[k, ss[j]]; slowy[k, ss[j]] = sslowy[k, ss[j]] }
    for (j = 1; j <= n; ++j) {
      e = sc[j]; ax = slow[k, e]; ay = slowy[k, e]
      if (lfrom != "" && ((k, e, lfrom) in px) && ((k, e, lto) in px)) {
        ax = px[k, e, lfrom]; ay = py[k, e, lfrom]
        printf "%g %g %g %g\n", ax, ay, px[k, e, lto], py[k, e, lto] > lf; nl++
      }
      text = (e in heldscene) ? "{/:Italic " e "}" : e
      w = length(e) * cw; gx = gpx(ax); gy = gpy(ay)
      # Beside the point (right of it in the left half), else the other side, else a line or
      # more up or down, whichever first overlaps no other name and no marker.
      side0 = gx > 0.55 * pw; placed = 0
      for (t = 0; t < 14 && !placed; ++t) {
        right = (t % 2) ? !side0 : side0; m = int(t / 2)
        dy = (m % 2 ? -1 : 1) * int((m + 1) / 2) * lh; cy = gy + dy
        x0 = right ? gx - 8 - w : gx + 8; x1 = x0 + w
        if (cy - lh / 2 < 0 || cy + lh / 2 > ph || x0 < 0 || x1 > pw) continue
        placed = !overlaps(k, x0, x1, cy - lh / 2, cy + lh / 2)
      }
      if (!placed) { right = side0; cy = gy; x0 = right ? gx - 8 - w : gx + 8; x1 = x0 + w }
      ++nbox[k]; bx0[k, nbox[k]] = x0; bx1[k, nbox[k]] = x1; by0[k, nbox[k]] = cy - lh / 2; by1[k, nbox[k]] = cy + lh / 2
      printf "%g %.9g \"%s\"\n", ax, fyinv(cy / ph * (fy(yhi) - fy(ylo)) + fy(ylo)), text > nf[right]; hasn[right] = 1
    }
    if (0 in hasn) close(nf[0]); if (1 in hasn) close(nf[1]); if (nl) close(lf)
    cmd = "plot NaN notitle"
    if (nl) cmd = cmd ", " q(lf) " using 1:2:($3-$1):($4-$2) with vectors nohead lc rgb \"#b8b8b8\" lw 1 notitle"
    for (s = 1; s <= ns; ++s) if ((k, s) in swk) {
      rf = tmp "/raw_" k "_" s; close(rf); sf = tmp "/sweep_" k "_" s
      system("sort -k1,1 -k2,2n " rf " | awk \047NR > 1 && $1 != p { print \"\" } { print $3, $4; p = $1 }\047 > " sf)
      cmd = cmd ", " q(sf) " using 1:2 with linespoints lc rgb \"" scol[s] "\" dt 2 pt 7 ps 0.4 lw 1 notitle"
    }
    for (s = 1; s <= ns; ++s) if (!ssweep[s]) for (h = 0; h <= 1; ++h) if ((k, s, h) in have) {
      f = tmp "/pts_" k "_" s "_" h; close(f)
      cmd = cmd sprintf(", %s using 1:2 with points lc rgb \"%s\" pt %d ps %s lw 1.5 notitle", q(f), scol[s], spt[s] - h, sname[s] == lto ? "1.6" : "1.25")
    }
    if (0 in hasn) cmd = cmd ", " q(nf[0]) " using 1:2:3 with labels left offset 0.8,0 font \",8\" tc rgb \"#202020\" notitle"
    if (1 in hasn) cmd = cmd ", " q(nf[1]) " using 1:2:3 with labels right offset -0.8,0 font \",8\" tc rgb \"#202020\" notitle"
    print cmd >> gp
  }
  # The legend: a panel of its own.
  print "unset title; unset xlabel; unset ylabel; unset nonlinear y; unset logscale x; unset grid; unset border; unset tics" >> gp
  print "set xrange [0:1]; set yrange [0:1]; set key center center vertical Left reverse samplen 1.2 spacing 1.5 font \",10\" width -6" >> gp
  cmd = "plot"; sep = " "
  # the default first, then the others as they came
  for (s = 1; s <= ns; ++s) if (!ssweep[s] && sname[s] == "default") { cmd = cmd sep sprintf("NaN with points lc rgb \"%s\" pt %d ps 1.4 lw 1.5 title %s", scol[s], spt[s], q(sdesc[s])); sep = ", " }
  for (s = 1; s <= ns; ++s) if (!ssweep[s] && sname[s] != "default") { cmd = cmd sep sprintf("NaN with points lc rgb \"%s\" pt %d ps 1.4 lw 1.5 title %s", scol[s], spt[s], q(sdesc[s])); sep = ", " }
  for (s = 1; s <= ns; ++s) if (ssweep[s]) { cmd = cmd sep sprintf("NaN with linespoints lc rgb \"%s\" dt 2 pt 7 ps 0.4 lw 1 title %s", scol[s], q(sdesc[s])); sep = ", " }
  for (e in heldscene) { cmd = cmd sep "NaN with points lc rgb \"#202020\" pt 6 ps 1.4 lw 1.5 title " q("open marker, {/:Italic italic name}: held-out scene"); break }
  if (lfrom != "") cmd = cmd ", NaN with lines lc rgb \"#b8b8b8\" lw 1 title " q("link" in legend ? legend["link"] : "grey line: one scene, from " lfrom " to " lto)
  print cmd >> gp
  print "unset multiplot" >> gp
}
