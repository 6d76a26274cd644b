# scripts/continuation.gp - bifurcation diagram of a continuation: the root strain at the
# Poincare section of every continued orbit against the continued variable, stable orbits solid,
# unstable dashed, one colour per period, the located bifurcations marked, over the points of a
# brute-force sweep (grey dots) when one is given.
#
# Usage:
#   gnuplot -e "datafile='x.branches.dat'; bifile='x.bifurcations.dat'; outfile='x.png'" scripts/continuation.gp
#   gnuplot -e "datafile='x.branches.dat'; bifile='x.bifurcations.dat'; sweepfile='s.bifurcation.dat'; outfile='x.png'" scripts/continuation.gp
# Variables: datafile (PREFIX.branches.dat, required), bifile (PREFIX.bifurcations.dat,
#   optional), sweepfile (a sweep's PREFIX.bifurcation.dat, optional: x = its column 1 [Hz],
#   or column 2 in mm when xcol=2), xcol (1 or 2, default 1), outfile (PNG, required),
#   plottitle (optional), xlabel_text (optional, default from the file's parameter line),
#   sweep_amp (optional: only the sweep points of this amplitude_pp [m], for a grid sweep),
#   sweepname (optional: the sweep's prefix, named in the title).
# PREFIX.branches.dat columns: 1 parameter, 2 strain [-], 3 strain rate [1/s], 4 tip [m],
#   5 stable (1 stable, 0 unstable; a new block wherever it changes), 6 branch,
#   7 period; one block (blank lines) per branch and section point.
# PREFIX.bifurcations.dat columns: 1 kind, 2 parameter, 3 strain, 4 period, 5 branch,
#   6-7 critical multiplier, 8 grazing [m], 9 kind code.
# Markers: period doubling (circle), saddle-node (triangle), Neimark-Sacker (diamond), grazing
# (cross), branch point (square).
# Terminal: pngcairo if this gnuplot has it, else png (libgd); 1100x700.

if (!exists("datafile") || !exists("outfile")) {
   print "continuation.gp: set datafile and outfile"
   exit status 1
}
if (!exists("plottitle") || strlen(plottitle) == 0) { plottitle = "gapbeam: continuation" }
if (!exists("xcol")) { xcol = 1 }
if (!exists("sweep_amp")) { sweep_amp = -1.0 }
if (!exists("xlabel_text") || strlen(xlabel_text) == 0) {
   xlabel_text = system(sprintf("sed -n 's/^# parameter: //p' '%s' | head -n 1", datafile))
}
if (!exists("sweepfile")) { sweepfile = "" }
have_sweep = exists("sweepfile") && strlen(sweepfile) > 0 ? (system(sprintf("test -s '%s' && echo 1 || echo 0", sweepfile)) eq "1") : 0
if (!exists("bifile")) { bifile = "" }
have_bif = exists("bifile") && strlen(bifile) > 0 ? (system(sprintf("grep -qv '^#' '%s' 2>/dev/null && echo 1 || echo 0", bifile)) eq "1") : 0

set encoding utf8
if (strstrt(GPVAL_TERMINALS, "pngcairo") > 0) {
   set terminal pngcairo noenhanced size 1100,700 font ",11" dashed
} else {
   set terminal png noenhanced size 1100,700
}
set output outfile
if (!exists("sweepname") || strlen(sweepname) == 0) { sweepname = sweepfile }
set title plottitle . "\nbifurcation diagram: stable orbits solid, unstable dashed" . \
   (have_sweep ? "; grey: the Poincare points of the sweep " . sweepname : "")
set xlabel xlabel_text
set ylabel "root strain ε [µε]"
set grid lc rgb "#e0e0e0"
set key outside right top vertical Left reverse samplen 2 spacing 1.1
set datafile missing "NaN"

# one colour per period (1, 2, 4, 8, 16, other)
pc(p) = (p == 1) ? 0x1f4e9c : (p == 2) ? 0x2ca02c : (p == 4) ? 0xff7f0e : (p == 8) ? 0x8c4fbf : (p == 16) ? 0xd62728 : 0x8c564b
sx(x) = (xcol == 2) ? x*1.0e3 : x

keep_amp(a) = (sweep_amp < 0 || abs(a - sweep_amp) <= 1.0e-6*abs(sweep_amp)) ? 1 : 0
s_sweep = "sweepfile using (keep_amp($2) ? sx(column(xcol)) : 1/0):($3*1.0e6) with points pt 7 ps 0.2 lc rgb '#b0b0b0' title 'sweep (Poincaré points)', "
s_bif = "bifile using 2:($9 == 1 ? $3*1.0e6 : 1/0) with points pt 6 ps 1.3 lc rgb 'black' title 'period doubling', " . \
   "bifile using 2:((strcol(1) eq 'saddle_node') ? $3*1.0e6 : 1/0) with points pt 8 ps 1.3 lc rgb 'black' title 'saddle-node', " . \
   "bifile using 2:((strcol(1) eq 'neimark_sacker') ? $3*1.0e6 : 1/0) with points pt 12 ps 1.4 lc rgb '#d62728' title 'Neimark-Sacker', " . \
   "bifile using 2:($9 == 3 ? $3*1.0e6 : 1/0) with points pt 2 ps 1.0 lc rgb '#555555' title 'grazing', " . \
   "bifile using 2:((strcol(1) eq 'branch_point') ? $3*1.0e6 : 1/0) with points pt 4 ps 1.2 lc rgb 'black' title 'branch point', "
s_lines = "datafile using 1:($5 > 0.5 ? $2*1.0e6 : 1/0):(pc($7)) with lines lw 2 lc rgb variable title 'stable', " . \
   "datafile using 1:($5 < 0.5 ? $2*1.0e6 : 1/0):(pc($7)) with lines lw 1 dt 2 lc rgb variable title 'unstable', "
s_keys = "NaN with lines lw 2 lc rgb '#1f4e9c' title 'period 1', NaN with lines lw 2 lc rgb '#2ca02c' title 'period 2', " . \
   "NaN with lines lw 2 lc rgb '#ff7f0e' title 'period 4', NaN with lines lw 2 lc rgb '#8c4fbf' title 'period 8', " . \
   "NaN with lines lw 2 lc rgb '#d62728' title 'period 16'"
eval("plot " . (have_sweep ? s_sweep : "") . s_lines . (have_bif ? s_bif : "") . s_keys)
unset output
