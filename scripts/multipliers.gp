# scripts/multipliers.gp - Floquet multipliers of every continued orbit in the complex plane,
# with the unit circle: a multiplier leaving the circle through -1 is a period doubling,
# through +1 a fold, as a complex pair a Neimark-Sacker bifurcation. Coloured by the continued
# variable; only |mu| <= rmax is shown (default 3).
#
# Usage:
#   gnuplot -e "datafile='x.multipliers.dat'; outfile='x.multipliers.png'" scripts/multipliers.gp
# Variables: datafile (PREFIX.multipliers.dat, required), outfile (PNG, required), plottitle,
#   rmax (optional), branch (optional: only this branch).
# PREFIX.multipliers.dat columns: 1 parameter, 2 real, 3 imag, 4 modulus, 5 branch, 6 period.
# Terminal: pngcairo if this gnuplot has it, else png (libgd); 800x800.

if (!exists("datafile") || !exists("outfile")) {
   print "multipliers.gp: set datafile and outfile"
   exit status 1
}
if (!exists("plottitle") || strlen(plottitle) == 0) { plottitle = "gapbeam: continuation" }
if (!exists("rmax")) { rmax = 3.0 }
if (!exists("branch")) { branch = 0 }
xlabel_text = system(sprintf("sed -n 's/^# parameter: //p' '%s' | head -n 1", datafile))
if (strstrt(GPVAL_TERMINALS, "pngcairo") > 0) {
   set terminal pngcairo noenhanced size 800,800 font ",11"
} else {
   set terminal png noenhanced size 800,800
}
set output outfile
set title plottitle . "\nFloquet multipliers and the unit circle"
set size ratio -1
set xrange [-rmax : rmax]
set yrange [-rmax : rmax]
set xlabel "Re(multiplier)"
set ylabel "Im(multiplier)"
set grid lc rgb "#e0e0e0"
set palette defined (0 "#2c3e9e", 1 "#1e9bd7", 2 "#2fb36b", 3 "#e3b21b", 4 "#d73027")
set cblabel xlabel_text
set parametric
set trange [0 : 2*pi]
set key top left
keep(b) = (branch == 0 || branch == b)
plot cos(t), sin(t) with lines lc rgb "black" lw 1.5 title "unit circle", \
     datafile using ((keep($5) && $4 <= rmax) ? $2 : 1/0):3:1 with points pt 7 ps 0.35 lc palette title "multipliers"
unset output
