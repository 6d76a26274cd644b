# scripts/bifurcation.gp - bifurcation diagram of a sweep: the Poincare root strain [microstrain]
# (once per forcing period, every recorded period of every sweep point) against the forcing
# frequency [Hz] or the forcing amplitude [mm peak to peak], from a gapbeam
# PREFIX.bifurcation.dat (columns: 1 frequency [Hz], 2 amplitude_pp [m], 3 strain [-],
# 4 strain_rate [1/s]).
#
# Usage:
#   gnuplot -e "datafile='x.bifurcation.dat'; outfile='x.bifurcation.png'" scripts/bifurcation.gp
#   gnuplot -e "datafile='x.bifurcation.dat'; outfile='x.png'; xaxis='amplitude'" scripts/bifurcation.gp
# Variables: datafile (required), outfile (required, PNG), plottitle (optional),
#   xaxis (optional): 'frequency' (default; x = column 1 [Hz]) or 'amplitude' (x = column 2
#   in mm p-p). scripts/plot.sh picks 'amplitude' when the sweep has a single frequency.
# A period-p point shows as p dots above its x; a chaotic point as a vertical smear. When the
# other forcing variable takes more than one value (a grid), the dots are coloured by it
# (palette, colour box on the right): the diagram of every line of the grid at once.
# Terminal: pngcairo if this gnuplot has it, else png (libgd); 1000x650.

if (!exists("datafile") || !exists("outfile")) {
   print "bifurcation.gp: set datafile and outfile, e.g. gnuplot -e \"datafile='x.bifurcation.dat'; outfile='x.png'\" scripts/bifurcation.gp"
   exit status 1
}
if (!exists("plottitle") || strlen(plottitle) == 0) { plottitle = "gapbeam: sweep" }
if (!exists("xaxis") || strlen(xaxis) == 0) { xaxis = "frequency" }
if (xaxis ne "frequency" && xaxis ne "amplitude") {
   print sprintf("bifurcation.gp: xaxis = '%s': expected 'frequency' or 'amplitude'", xaxis)
   exit status 1
}

if (strstrt(GPVAL_TERMINALS, "pngcairo") > 0) {
   set terminal pngcairo noenhanced size 1000,650 font ",11"
   dotsize = 0.25
} else {
   set terminal png noenhanced size 1000,650
   dotsize = 0.4
}

# x: frequency [Hz] or amplitude [mm p-p]; c: the other forcing variable (colour).
byfreq = (xaxis eq "frequency") ? 1 : 0
xval(f, a) = byfreq ? f : a*1.0e3
cval(f, a) = byfreq ? a*1.0e3 : f

stats datafile using (xval($1, $2)):($3*1.0e6) nooutput
npts = STATS_records
xmin = STATS_min_x;  xmax = STATS_max_x
ymin = STATS_min_y;  ymax = STATS_max_y
stats datafile using (cval($1, $2)) nooutput
cmin = STATS_min;  cmax = STATS_max
# Colour by the other variable only when it varies (relative spread above round-off).
colour = ((cmax - cmin) > 1.0e-9*(abs(cmax) + abs(cmin))) ? 1 : 0

# Frame: the extent plus 3 % each side (x) and 5 % (y); a degenerate extent gets +-5 % of its
# magnitude (1 if zero).
max2(a, b) = (a > b) ? a : b
pad(lo, hi, f) = ((hi - lo) > 0) ? f*(hi - lo) : ((max2(abs(lo), abs(hi)) > 0) ? 0.05*max2(abs(lo), abs(hi)) : 1.0)
set xrange [xmin - pad(xmin, xmax, 0.03) : xmax + pad(xmin, xmax, 0.03)]
set yrange [ymin - pad(ymin, ymax, 0.05) : ymax + pad(ymin, ymax, 0.05)]

set output outfile
set title sprintf("%s\nBifurcation diagram: Poincare root strain once per forcing period (%d points)", \
   plottitle, npts)
set xlabel byfreq ? "forcing frequency [Hz]" : "forcing amplitude [mm peak to peak]"
set ylabel "root strain at the Poincare phase [microstrain]"
set format x "%g"
set format y "%g"
set grid lc rgb "#d0d0d0"
set key off
set tics front

if (colour) {
   set palette defined (0 "#2c3e9e", 1 "#1e9bd7", 2 "#2fb36b", 3 "#e3b21b", 4 "#d73027")
   set cbrange [cmin : cmax]
   set cblabel byfreq ? "forcing amplitude [mm peak to peak]" : "forcing frequency [Hz]"
   set colorbox vertical user origin screen 0.905, screen 0.12 size screen 0.02, screen 0.72
   set rmargin at screen 0.86
   plot datafile using (xval($1, $2)):($3*1.0e6):(cval($1, $2)) \
      with points pt 7 ps dotsize lc palette notitle
} else {
   unset colorbox
   plot datafile using (xval($1, $2)):($3*1.0e6) with points pt 7 ps dotsize lc rgb "#1f4e9c" notitle
}

unset output
