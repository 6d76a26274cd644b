# scripts/model_size.gp - fidelity against cost of the candidate models of a gapbeam model-size
# study (analysis = 'model_size'): distance of each candidate's Poincare set to the reference
# model's against the candidate's run time, log-log, each point labelled with the candidate's name.
# Data: PREFIX.model_size.dat (columns: 1 candidate [-], 2 coordinates [-], 3 seconds [s],
# 4 poincare_distance [-], 5 frequency_error [-], 6 label [p|0|-1], 7 lyapunov [1/s],
# 8 peak_force [N], 9 acceptable [1|0]); names: PREFIX.model_size.txt (the report: a table whose
# rows start with the candidate number, then the name, then 8 fields: coords ... ok; and a line
# 'recommended: <name> (<n> coordinates)').
#
# Usage:
#   gnuplot -e "datafile='x.model_size.dat'; namefile='x.model_size.txt'; outfile='x.png'" \
#           scripts/model_size.gp
#   gnuplot -e "datafile='x.model_size.dat'; namefile=''; outfile='x.png'; tolerance=0.1; \
#               plottitle='10.5 Hz'" scripts/model_size.gp
# Variables: datafile (required), outfile (required; PNG, PDF or SVG by format), namefile (optional: without it, or for a
#            row whose coordinates disagree with the .dat, a point is labelled #<candidate>),
#            plottitle (optional), tolerance (optional: the Poincare tolerance [-], 0.05),
#            verbose (optional: 1 prints the placed labels).
# Marks: acceptable candidates (column 9 = 1) filled green, the others open grey; the recommended
# one (from namefile) ringed in black; a candidate at distance 0 (the reference itself) is drawn as
# a triangle on a dotted floor line (1e-4, or a decade below the smallest distance if that is
# smaller) and its label says so. A dashed line marks the tolerance. Labels are placed by a small
# greedy search (right, left, above, below the point, then further off with a leader line) that
# avoids the points, the legend and the labels already placed, and if it can the tolerance line.
# Terminal: scripts/terminal.gp (format png, pdf or svg); 900x600.

if (!exists("datafile") || !exists("outfile")) {
   print "model_size.gp: set datafile and outfile, e.g. gnuplot -e \"datafile='x.model_size.dat'; namefile='x.model_size.txt'; outfile='x.png'\" scripts/model_size.gp"
   exit status 1
}
if (!exists("plottitle") || strlen(plottitle) == 0) { plottitle = "gapbeam: model size" }
if (!exists("namefile")) { namefile = "" }
if (!exists("tolerance")) { tolerance = 0.05 }
tolerance = real(tolerance)

# The terminal (format png, pdf or svg; see scripts/terminal.gp), from this script's folder.
dirof_(s, i) = (i < 1) ? "." : ((s[i:i] eq "/") ? s[1:i-1] : dirof_(s, i - 1))
width = 900; height = 600
load dirof_(ARG0, strlen(ARG0)) . "/terminal.gp"
if (cairo) {
   char_w = 6.7; line_h = 14.0
} else {
   char_w = 7.0; line_h = 14.0
}

# A text as a shell single-quoted word (a quote inside becomes '\'').
# (Halving recursion: its depth is log2 of the length.)
shq_(s) = (strlen(s) <= 1) ? ((s eq "'") ? "'\\''" : s) \
   : shq_(s[1 : strlen(s)/2]) . shq_(s[strlen(s)/2 + 1 :])
shquote(s) = "'" . ((strstrt(s, "'") == 0) ? s : shq_(s)) . "'"
decade_down(v) = 10.0**floor(log10(v) - 1.0e-9)
max2(a, b) = (a > b) ? a : b
min2(a, b) = (a < b) ? a : b

# Extent: run times; positive distances (a zero distance goes on the floor).
stats datafile using 3 nooutput
ncand = STATS_records
tmin = STATS_min; tmax = STATS_max
stats datafile using ($4 > 0 ? 1 : 0) nooutput
npos = STATS_sum
nzero = ncand - npos
stats datafile using ($4 > 0 ? 0 : ($9 > 0.5 ? 1 : 0)) nooutput
zero_ok = STATS_sum
dmin = tolerance; dmax = tolerance
if (npos > 0) {
   stats datafile using ($4 > 0 ? $4 : NaN) nooutput
   dmin = STATS_min; dmax = STATS_max
}
dist_floor = min2(1.0e-4, decade_down(min2(dmin, tolerance))/10.0)
if (tmin <= 0) { tmin = 1.0e-6 }
if (tmax <= tmin) { tmax = 10.0*tmin }

# Frame fixed in screen fractions, so that the label search works in pixels of the plot area.
set lmargin at screen 0.105
set rmargin at screen 0.97
set bmargin at screen 0.11
set tmargin at screen 0.87
plot_w = (0.97 - 0.105)*900.0; plot_h = (0.87 - 0.11)*600.0
x_lo = tmin/1.6; x_hi = tmax*2.5
# Top: the data (and the tolerance line) in the lower 74 % of the frame; the legend sits above.
y_lo = dist_floor/2.5
ly0 = log10(y_lo)
ly1 = ly0 + (log10(max2(dmax, tolerance)*1.3) - ly0)/0.74
y_hi = 10.0**ly1
lx0 = log10(x_lo); lx1 = log10(x_hi)
# The legend, top right inside: its box is an obstacle for the labels.
key_w = 43*(char_w + 0.7) + 120.0; key_h = 5*18.0 + 12.0

# Label search (awk): reads the names from the report (first file), the points from the .dat, and
# writes one line per candidate: x y label_x label_y "text" right_aligned leader acceptable zero
# recommended leader_end_x leader_end_y (coordinates in data units). Crowded points (most
# neighbours within 50 x 30 px) are labelled first.
awk_prog = \
 'function ovl(a0, a1, b0, b1, c0, c1, d0, d1,  w, h) {' . \
 ' w = (a1 < c1 ? a1 : c1) - (a0 > c0 ? a0 : c0); h = (b1 < d1 ? b1 : d1) - (b0 > d0 ? b0 : d0);' . \
 ' return (w > 0 && h > 0) ? w * h : 0 }' . \
 'function box(x0, x1, y0, y1) { nb++; bx0[nb] = x0; bx1[nb] = x1; by0[nb] = y0; by1[nb] = y1 }' . \
 'function lg(v) { return log(v) / log(10) }' . \
 'FILENAME == ARGV[1] {' . \
 ' if ($1 == "recommended:") { r = $0; sub(/^[ \t]*recommended:[ \t]*/, "", r);' . \
 '   sub(/[ \t]*\([0-9]+ coordinates?\)[ \t]*$/, "", r); rec = r; next }' . \
 ' if ($1 ~ /^[0-9]+$/ && NF >= 10) { s = $2; for (i = 3; i <= NF - 8; i++) s = s " " $i;' . \
 '   nm[$1 + 0] = s; nc[$1 + 0] = $(NF - 7) }' . \
 ' next }' . \
 '/^[ \t]*(#|$)/ { next }' . \
 '{ n++; id[n] = $1 + 0; co[n] = $2 + 0; t[n] = $3 + 0; d[n] = $4 + 0; ok[n] = ($9 + 0 > 0.5) ? 1 : 0 }' . \
 'END {' . \
 ' for (i = 1; i <= n; i++) {' . \
 '  c = id[i]; nam = ((c in nm) && nc[c] + 0 == co[i]) ? nm[c] : sprintf("#%d", c);' . \
 '  z[i] = (d[i] > 0) ? 0 : 1; y[i] = z[i] ? fl : d[i];' . \
 '  rc[i] = (rec != "" && nam == rec) ? 1 : 0;' . \
 '  tx[i] = nam (z[i] ? " (distance 0)" : "") (rc[i] ? " *" : "");' . \
 '  px[i] = (lg(t[i]) - lx0) / (lx1 - lx0) * W; py[i] = (lg(y[i]) - ly0) / (ly1 - ly0) * H;' . \
 '  box(px[i] - 6, px[i] + 6, py[i] - 6, py[i] + 6) }' . \
 ' box(W - kw, W, H - kh, H); yt = (lg(tol) - ly0) / (ly1 - ly0) * H;' . \
 ' nk = split("9 -9 6 6 -6 -6 9 9 -9 -9 12 12 -12 -12 14 14 -14 -14 40 -40 16 16 -16 -16", kx, " ");' . \
 ' split("0 0 1 -1 1 -1 2 -2 2 -2 3 -3 3 -3 4 -4 4 -4 0 0 5 -5 5 -5", ky, " ");' . \
 ' for (i = 1; i <= n; i++) { cr[i] = 0; ord[i] = i;' . \
 '  for (j = 1; j <= n; j++) if (j != i && (px[j] - px[i])^2 / 2500 + (py[j] - py[i])^2 / 900 < 1) cr[i]++ }' . \
 ' for (i = 1; i <= n; i++) for (j = i + 1; j <= n; j++)' . \
 '  if (cr[ord[j]] > cr[ord[i]]) { q = ord[i]; ord[i] = ord[j]; ord[j] = q }' . \
 ' for (q = 1; q <= n; q++) { i = ord[q];' . \
 '  w = length(tx[i]) * cw + 6; h = lh; best = -1;' . \
 '  for (k = 1; k <= nk; k++) {' . \
 '   al = (kx[k] < 0) ? 1 : 0; ax = px[i] + kx[k]; ay = py[i] + ky[k] * lh;' . \
 '   x0 = al ? ax - w : ax; x1 = al ? ax : ax + w; y0 = ay - h / 2; y1 = ay + h / 2;' . \
 '   s = 2 * k + (k > 6 ? 20 : 0) + ((y0 < yt + 1 && y1 > yt - 1) ? 10 : 0);' . \
 '   for (b = 1; b <= nb; b++) s += ovl(x0, x1, y0, y1, bx0[b], bx1[b], by0[b], by1[b]);' . \
 '   if (x0 < 2) s += 4 * h * (2 - x0); if (x1 > W - 2) s += 4 * h * (x1 - W + 2);' . \
 '   if (y0 < 2) s += 4 * w * (2 - y0); if (y1 > H - 2) s += 4 * w * (y1 - H + 2);' . \
 '   if (best < 0 || s < best) { best = s; bk = k; bx = ax; by = ay; b0 = x0; b1 = x1; c0 = y0; c1 = y1 } }' . \
 '  box(b0, b1, c0, c1);' . \
 '  ld = (ky[bk] >= 2 || ky[bk] <= -2 || kx[bk] >= 40 || kx[bk] <= -40) ? 1 : 0;' . \
 '  ey = by + (ky[bk] > 0 ? -h / 2 : (ky[bk] < 0 ? h / 2 : 0));' . \
 '  printf "%.10g %.10g %.10g %.10g \"%s\" %d %d %d %d %d %.10g %.10g\n", t[i], y[i],' . \
 '   10 ^ (lx0 + bx / W * (lx1 - lx0)), 10 ^ (ly0 + by / H * (ly1 - ly0)), tx[i], (kx[bk] < 0),' . \
 '   ld, ok[i], z[i], rc[i], 10 ^ (lx0 + bx / W * (lx1 - lx0)), 10 ^ (ly0 + ey / H * (ly1 - ly0)) } }'

names_arg = (strlen(namefile) > 0) ? namefile : "/dev/null"
awk_cmd = sprintf("awk -v lx0=%.10g -v lx1=%.10g -v ly0=%.10g -v ly1=%.10g -v W=%.6g -v H=%.6g", \
   lx0, lx1, ly0, ly1, plot_w, plot_h) . \
   sprintf(" -v cw=%.4g -v lh=%.4g -v kw=%.6g -v kh=%.6g -v fl=%.10g -v tol=%.10g ", \
   char_w, line_h, key_w, key_h, dist_floor, tolerance) . \
   shquote(awk_prog) . " " . shquote(names_arg) . " " . shquote(datafile)
placed = system(awk_cmd)
set print $placed
print placed
unset print
if (exists("verbose") && verbose) { print placed }
stats $placed using 10 nooutput
nrec = STATS_sum
# The recommended candidate's name (for the title), from the report.
recommended = ""
if (strlen(namefile) > 0) {
   recommended = system("awk '/^[ \\t]*recommended:/ { sub(/^[ \\t]*recommended:[ \\t]*/, \"\"); print; exit }' " . shquote(namefile))
}

set output outfile
set title sprintf("%s\nPoincare distance to the reference model against run time, %d candidates%s", \
   plottitle, ncand, (strlen(recommended) > 0) ? "\nrecommended: " . recommended : "")
set xlabel "run time [s]"
set ylabel "Poincare distance to the reference [-]"
set logscale xy
set xrange [x_lo : x_hi]
set yrange [y_lo : y_hi]
set format x "%g"
set format y "%g"
# 2 and 5 between the decades when the axis spans few decades.
if (lx1 - lx0 < 3.5) {
   do for [e = floor(lx0) : ceil(lx1)] { set xtics add (2.0*10.0**e, 5.0*10.0**e) }
}
if (ly1 - ly0 < 3.5) {
   do for [e = floor(ly0) : ceil(ly1)] { set ytics add (2.0*10.0**e, 5.0*10.0**e) }
}
set mxtics 10
set mytics 10
set grid xtics ytics lc rgb "#e0e0e0"
set key top right opaque box lc rgb "#b0b0b0" spacing 1.1 samplen 2.5 width 1
if (nzero > 0) {
   set arrow 1 from graph 0, first dist_floor to graph 1, first dist_floor nohead dt 3 lw 1 \
      lc rgb "#808080" back
}

green = "#2ca02c"; grey = "#8c8c8c"
colour(ok) = (ok > 0.5) ? 0x2ca02c : 0x8c8c8c
plot tolerance with lines dt 2 lw 1.5 lc rgb "#c00000" \
        title sprintf("Poincare tolerance %g", tolerance), \
     $placed using 1:($9 == 0 && $8 == 0 ? $2 : NaN) with points pt 6 ps 1.7 lw 1.5 \
        lc rgb grey title "not acceptable (open)", \
     $placed using 1:($9 == 0 && $8 == 1 ? $2 : NaN) with points pt 7 ps 1.7 \
        lc rgb green title "acceptable (filled)", \
     $placed using 1:($9 == 1 ? $2 : NaN):(colour($8)) with points pt 11 ps 2.2 lc rgb variable \
        notitle, \
     for [k = 1 : (nzero > 0)] NaN with points pt 11 ps 2.2 lc rgb (zero_ok > 0 ? green : grey) \
        title sprintf("distance 0 (the reference), drawn at %g", dist_floor), \
     $placed using 1:($10 == 1 ? $2 : NaN) with points pt 6 ps 3.2 lw 2 lc rgb "#000000" \
        notitle, \
     for [k = 1 : (nrec > 0)] NaN with points pt 6 ps 3.2 lw 2 lc rgb "#000000" \
        title "recommended (ringed, name marked *)", \
     $placed using 1:($7 == 1 ? $2 : NaN):($11 - $1):($12 - $2) with vectors nohead lw 1 \
        lc rgb "#909090" notitle, \
     $placed using 3:($6 == 0 ? $4 : NaN):5 with labels left font ",10" tc rgb "#202020" notitle, \
     $placed using 3:($6 == 1 ? $4 : NaN):5 with labels right font ",10" tc rgb "#202020" notitle

unset output
