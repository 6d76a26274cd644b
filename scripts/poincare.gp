# scripts/poincare.gp - Poincare map of the root strain (paper Figs. 4-9): strain rate [µε/s]
# against strain [µε], one point per forcing period, from a gapbeam PREFIX.poincare.dat
# (columns: 1 strain [-], 2 strain_rate [1/s], 3 tip_displacement [m], 4 tip_velocity [m/s],
# 5 time [s]).
#
# Usage:
#   gnuplot -e "datafile='x.poincare.dat'; outfile='x.poincare.png'" scripts/poincare.gp
#   gnuplot -e "datafile='x.poincare.dat'; outfile='x.png'; plottitle='9.8 Hz'" scripts/poincare.gp
# Variables: datafile (required), outfile (required), plottitle (optional), format (png, pdf,
# svg: scripts/terminal.gp).
# Ranges: the points' extent plus 8 % each side, and at least +-5 % of the largest magnitude, so
# that a fixed point (all points equal to round-off) is drawn as one visible dot in a readable
# frame; such a collapsed map is labelled with its coordinates. A map on at most 16 distinct spots
# (at 1/200 of the frame; a periodic orbit) is drawn with large points, a cloud with small dots.
# Terminal: scripts/terminal.gp; 900x600.

if (!exists("datafile") || !exists("outfile")) {
   print "poincare.gp: set datafile and outfile, e.g. gnuplot -e \"datafile='x.poincare.dat'; outfile='x.png'\" scripts/poincare.gp"
   exit status 1
}
if (!exists("plottitle") || strlen(plottitle) == 0) { plottitle = "gapbeam: Poincare map" }

# The terminal (format png, pdf or svg; see scripts/terminal.gp), from this script's folder.
dirof_(s, i) = (i < 1) ? "." : ((s[i:i] eq "/") ? s[1:i-1] : dirof_(s, i - 1))
width = 900; height = 600
load dirof_(ARG0, strlen(ARG0)) . "/terminal.gp"

stats datafile using ($1*1.0e6):($2*1.0e6) nooutput
npts = STATS_records
xmin = STATS_min_x;  xmax = STATS_max_x
ymin = STATS_min_y;  ymax = STATS_max_y

# Half-width of an axis: 58 % of the spread, at least 5 % of the largest magnitude (1 if all zero).
max2(a, b) = (a > b) ? a : b
hw0(lo, hi) = max2(0.58*(hi - lo), 0.05*max2(abs(lo), abs(hi)))
halfwidth(lo, hi) = (hw0(lo, hi) > 0) ? hw0(lo, hi) : 1.0
xh = halfwidth(xmin, xmax);  xc = 0.5*(xmin + xmax)
yh = halfwidth(ymin, ymax);  yc = 0.5*(ymin + ymax)

# Collapsed map (a fixed point): the spread is below 0.1 % of the frame on both axes.
collapsed = ((xmax - xmin) < 1.0e-3*xh && (ymax - ymin) < 1.0e-3*yh) ? 1 : 0
# Distinct spots: the frame cut into 200 x 200 cells (centred on the frame's centre), cells hit.
# A periodic orbit hits a few cells: draw large points so each spot shows; a cloud: small dots.
cell(v, c, h) = floor((v - c)/(2.0*h)*200.0 + 0.5)
set xrange [-1.0e9 : 1.0e9]
set yrange [-1.0e9 : 1.0e9]
set table $poincare_cells
plot datafile using (cell($1*1.0e6, xc, xh)*1000 + cell($2*1.0e6, yc, yh)):(1) smooth frequency
unset table
stats $poincare_cells using 1 nooutput
nspots = STATS_records
if (exists("verbose") && verbose) { print sprintf("poincare.gp: %d points, %d spots", npts, nspots) }
psize = (collapsed || nspots <= 16) ? 1.6 : 0.45
if (!cairo) { psize = 1.5*psize }

set output outfile
set xrange [xc - xh : xc + xh]
set yrange [yc - yh : yc + yh]

spots = (nspots <= 16) ? sprintf(" on %d distinct spot%s", nspots, (nspots == 1) ? "" : "s") : ""
set title sprintf("%s\nPoincare map of the root strain, once per forcing period (%d points%s)", \
   plottitle, npts, spots)
set xlabel "root strain ε [µε]"
set ylabel "root strain rate dε/dt [µε/s]"
set format x "%g"
set format y "%g"
set grid lc rgb "#d0d0d0"
set xzeroaxis lt 1 lc rgb "#a0a0a0"
set yzeroaxis lt 1 lc rgb "#a0a0a0"
set key off
if (collapsed) {
   set label 1 sprintf("all %d points at (%.6g µε, %.6g µε/s)", npts, xc, yc) \
      at graph 0.03, graph 0.95 left front
}

plot datafile using ($1*1.0e6):($2*1.0e6) with points pt 7 ps psize lc rgb "#1f4e9c" notitle

unset output
