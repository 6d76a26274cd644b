# scripts/continuation_curves.gp - two-parameter bifurcation curves of a continuation (period
# doubling solid, saddle-node dashed, grazing dotted; one colour per period of the orbit) over
# the chaos map of a brute-force sweep of the same model (tiles coloured by the response class),
# when one is given.
#
# Usage:
#   gnuplot -e "datafile='x.curves.dat'; outfile='x.curves.png'" scripts/continuation_curves.gp
#   gnuplot -e "datafile='x.curves.dat'; sweepfile='s.sweep.dat'; outfile='x.curves.png'" scripts/continuation_curves.gp
# Variables: datafile (PREFIX.curves.dat, required), outfile (PNG, required), sweepfile (a sweep's
#   PREFIX.sweep.dat: columns 1 frequency [Hz], 2 amplitude_pp [m], 4 label), plottitle,
#   yscale (factor on the second variable, default 1e3: m to mm), ylabel_text.
# PREFIX.curves.dat columns: 1 parameter, 2 parameter2, 3 kind (1 PD, 2 SN, 3 grazing),
#   4 period, 5 curve; one block per curve. The background assumes parameter = frequency and
#   parameter2 = amplitude, as in the sweep.
# Terminal: pngcairo if this gnuplot has it, else png (libgd); 1100x700.

if (!exists("datafile") || !exists("outfile")) {
   print "continuation_curves.gp: set datafile and outfile"
   exit status 1
}
if (!exists("plottitle") || strlen(plottitle) == 0) { plottitle = "gapbeam: continuation" }
if (!exists("yscale")) { yscale = 1.0e3 }
xlabel_text = system(sprintf("sed -n 's/^# parameter: //p' '%s' | head -n 1", datafile))
if (!exists("ylabel_text") || strlen(ylabel_text) == 0) {
   ylabel_text = system(sprintf("sed -n 's/^# parameter2: //p' '%s' | head -n 1", datafile))
   if (yscale == 1.0e3) { ylabel_text = ylabel_text . " x 1e3" }
}
if (!exists("sweepfile")) { sweepfile = "" }
have_sweep = exists("sweepfile") && strlen(sweepfile) > 0 ? (system(sprintf("test -s '%s' && echo 1 || echo 0", sweepfile)) eq "1") : 0

if (strstrt(GPVAL_TERMINALS, "pngcairo") > 0) {
   set terminal pngcairo noenhanced size 1100,700 font ",11" dashed
} else {
   set terminal png noenhanced size 1100,700
}
hf = 0.005;  ha = 0.05
if (have_sweep) {
   # tile half-sizes from the grid spacing (as in chaos_map.gp)
   set format x "%.12g"
   set xrange [-1.0e30 : 1.0e30]
   set yrange [-1.0e30 : 1.0e30]
   set table $cc_f
   plot sweepfile using 1:(1) smooth frequency
   set table $cc_a
   plot sweepfile using ($2*yscale):(1) smooth frequency
   unset table
   stats $cc_f using 1 nooutput
   nf = STATS_records;  fmin = STATS_min;  fmax = STATS_max
   stats $cc_a using 1 nooutput
   na = STATS_records;  amin = STATS_min;  amax = STATS_max
   hf = (nf > 1) ? 0.5*(fmax - fmin)/(nf - 1) : 0.01
   ha = (na > 1) ? 0.5*(amax - amin)/(na - 1) : 0.01
   set format x "%g"
}
# frame: the curves' extent, or the sweep's
stats datafile using 1:($2*yscale) nooutput
xlo = STATS_min_x;  xhi = STATS_max_x;  ylo = STATS_min_y;  yhi = STATS_max_y
if (have_sweep) { xlo = (fmin - hf < xlo) ? fmin - hf : xlo;  xhi = (fmax + hf > xhi) ? fmax + hf : xhi }
if (have_sweep) { ylo = (amin - ha < ylo) ? amin - ha : ylo;  yhi = (amax + ha > yhi) ? amax + ha : yhi }
set xrange [xlo : xhi]
set yrange [ylo : yhi]
set output outfile
set title plottitle . "\nbifurcation curves (PD solid, SN dashed, grazing dotted) over the brute-force chaos map"
set xlabel xlabel_text
set ylabel ylabel_text
set grid lc rgb "#e0e0e0" front
set key outside right top vertical Left reverse samplen 2.5 spacing 1.1
set style fill solid 1.0 noborder
cls(l) = (l < -0.5) ? 0xf4a6a6 : (l < 0.5) ? 0xe0e0e0 : (l < 1.5) ? 0xc6d5ee : (l < 2.5) ? 0xc9e8c9 : (l < 4.5) ? 0xffe0b8 : 0xe2d4f0
pc(p) = (p == 1) ? 0x1f4e9c : (p == 2) ? 0x2ca02c : (p == 4) ? 0xff7f0e : (p == 8) ? 0x8c4fbf : 0xd62728
s_sweep = "sweepfile using 1:($2*yscale):(hf):(ha):(cls($4)) with boxxyerror lc rgb variable notitle, "
s_curves = "datafile using 1:($3 == 1 ? $2*yscale : 1/0):(pc($4)) with lines lw 2.5 lc rgb variable title 'period doubling', " . \
   "datafile using 1:($3 == 2 ? $2*yscale : 1/0):(pc($4)) with lines lw 2.5 dt 2 lc rgb variable title 'saddle-node', " . \
   "datafile using 1:($3 == 3 ? $2*yscale : 1/0):(pc($4)) with lines lw 2.5 dt 3 lc rgb variable title 'grazing', "
s_tiles = "NaN with boxes lc rgb '#c6d5ee' title 'sweep: period 1', NaN with boxes lc rgb '#c9e8c9' title 'sweep: period 2', " . \
   "NaN with boxes lc rgb '#ffe0b8' title 'sweep: period 3-4', NaN with boxes lc rgb '#e2d4f0' title 'sweep: period > 4', " . \
   "NaN with boxes lc rgb '#f4a6a6' title 'sweep: chaotic', NaN with boxes lc rgb '#e0e0e0' title 'sweep: undecided', "
s_keys = "NaN with lines lw 2.5 lc rgb '#1f4e9c' title 'orbit period 1', NaN with lines lw 2.5 lc rgb '#2ca02c' title 'orbit period 2', " . \
   "NaN with lines lw 2.5 lc rgb '#ff7f0e' title 'orbit period 4'"
eval("plot " . (have_sweep ? s_sweep : "") . s_curves . (have_sweep ? s_tiles : "") . s_keys)
unset output
