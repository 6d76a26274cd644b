# scripts/mode_shapes.gp - the first (up to) 4 mode shapes w(x) of a gapbeam modal analysis, from
# PREFIX.shapes.dat (columns: 1 x [m], 2.. w_mode1, w_mode2, ... mass-normalised [m/sqrt(kg)], at
# the nodes), with each mode's frequency in the legend read from PREFIX.modes.dat (columns:
# 1 mode, 2 frequency [Hz], 3 ratio_to_f1, 4 participation, 5 eff_mass_fraction).
#
# Usage:
#   gnuplot -e "shapesfile='x.shapes.dat'; modesfile='x.modes.dat'; outfile='x.shapes.png'" \
#      scripts/mode_shapes.gp
# Variables: shapesfile (required), outfile (required, PNG), modesfile (optional: without it, or
# with it empty, the legend says 'mode k' only), plottitle (optional).
# The points are the nodal values; the straight lines only join them (the rotations, which the
# Hermite elements would need to draw w between the nodes, are not in the file).
# Terminal: pngcairo if this gnuplot has it, else png (libgd); 900x600.

if (!exists("shapesfile") || !exists("outfile")) {
   print "mode_shapes.gp: set shapesfile and outfile (modesfile optional), e.g. gnuplot -e \"shapesfile='x.shapes.dat'; modesfile='x.modes.dat'; outfile='x.png'\" scripts/mode_shapes.gp"
   exit status 1
}
if (!exists("plottitle") || strlen(plottitle) == 0) { plottitle = "gapbeam: mode shapes" }
if (!exists("modesfile")) { modesfile = "" }

if (strstrt(GPVAL_TERMINALS, "pngcairo") > 0) {
   set terminal pngcairo noenhanced size 900,600 font ",11"
} else {
   set terminal png noenhanced size 900,600
}

stats shapesfile using 1 nooutput
nmodes = STATS_columns - 1
xmin = STATS_min
xmax = STATS_max
nplot = (nmodes < 4) ? nmodes : 4
if (nplot < 1) {
   print sprintf("mode_shapes.gp: %s has no mode-shape column", shapesfile)
   exit status 1
}

# Legend entries: 'mode k, f = ... Hz' where the modes file gives the frequency of mode k.
array legend[4]
do for [k=1:nplot] { legend[k] = sprintf("mode %d", k) }
if (strlen(modesfile) > 0) {
   do for [k=1:nplot] {
      stats modesfile using ((int($1 + 0.5) == k) ? $2 : NaN) nooutput
      if (STATS_records == 1) { legend[k] = sprintf("mode %d, f = %.2f Hz", k, STATS_min) }
   }
}

set output outfile
set title sprintf("%s\nmode shapes, mass-normalised (points: nodal values)", plottitle)
set xlabel "x [m] (from the root)"
set ylabel "w [m/sqrt(kg)]"
set xrange [xmin : xmax]
set offsets 0, 0, graph 0.08, graph 0.08
set format x "%g"
set format y "%g"
set grid lc rgb "#d0d0d0"
set xzeroaxis lt 1 lc rgb "#a0a0a0"
set key top left opaque box samplen 2

plot for [k=1:nplot] shapesfile using 1:(column(k + 1)) with linespoints lw 1.5 pt 7 ps 1.0 \
   title legend[k]

unset output
