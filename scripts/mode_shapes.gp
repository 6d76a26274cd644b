# scripts/mode_shapes.gp - the first (up to) 4 mode shapes w(x) of a gapbeam modal analysis, from
# PREFIX.shapes.dat (columns: 1 x [m], 2.. w_mode1, w_mode2, ... mass-normalised [m/sqrt(kg)], at
# the nodes), with each mode's frequency in the legend read from PREFIX.modes.dat (columns:
# 1 mode, 2 frequency [Hz], 3 ratio_to_f1, 4 participation, 5 eff_mass_fraction).
#
# Usage:
#   gnuplot -e "shapesfile='x.shapes.dat'; modesfile='x.modes.dat'; outfile='x.shapes.png'" \
#      scripts/mode_shapes.gp
# Variables: shapesfile (required), outfile (required; PNG, PDF or SVG by format), modesfile
# (optional: without it, or with it empty, the legend says 'mode k' only), curvesfile (optional:
# PREFIX.shape_curves.dat, the shapes between the nodes from the elements' cubic Hermite shape
# functions, same columns), plottitle (optional).
# The points are the nodal values; the curves are the shapes the finite element model assumes
# between them (with curvesfile; without it, straight lines only join the nodes).
# Terminal: scripts/terminal.gp (format png, pdf or svg); 900x600.

if (!exists("shapesfile") || !exists("outfile")) {
   print "mode_shapes.gp: set shapesfile and outfile (modesfile optional), e.g. gnuplot -e \"shapesfile='x.shapes.dat'; modesfile='x.modes.dat'; outfile='x.png'\" scripts/mode_shapes.gp"
   exit status 1
}
if (!exists("plottitle") || strlen(plottitle) == 0) { plottitle = "gapbeam: mode shapes" }
if (!exists("modesfile")) { modesfile = "" }
if (!exists("curvesfile")) { curvesfile = "" }

# The terminal (format png, pdf or svg; see scripts/terminal.gp), from this script's folder.
dirof_(s, i) = (i < 1) ? "." : ((s[i:i] eq "/") ? s[1:i-1] : dirof_(s, i - 1))
width = 900; height = 600
load dirof_(ARG0, strlen(ARG0)) . "/terminal.gp"

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
set title sprintf("%s\nmode shapes, mass-normalised (points: nodal values%s)", plottitle, \
   (strlen(curvesfile) > 0) ? "; curves: Hermite shape functions" : "")
set xlabel "x [m] (from the root)"
set ylabel "w [kg^-1/2] (mass-normalised)"
set xrange [xmin : xmax]
set offsets 0, 0, graph 0.08, graph 0.08
set format x "%g"
set format y "%g"
set grid lc rgb "#d0d0d0"
set xzeroaxis lt 1 lc rgb "#a0a0a0"
set key top left opaque box samplen 2

array mcolour[4] = ["#1f4e9c", "#d62728", "#2ca02c", "#8c4fbf"]
if (strlen(curvesfile) > 0) {
   plot for [k=1:nplot] curvesfile using 1:(column(k + 1)) with lines lw 2 lc rgb mcolour[k] \
           title legend[k], \
        for [k=1:nplot] shapesfile using 1:(column(k + 1)) with points pt 7 ps 1.1 \
           lc rgb mcolour[k] notitle
} else {
   plot for [k=1:nplot] shapesfile using 1:(column(k + 1)) with linespoints lw 1.5 pt 7 ps 1.0 \
      lc rgb mcolour[k] title legend[k]
}

unset output
