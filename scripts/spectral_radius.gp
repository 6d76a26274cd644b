# scripts/spectral_radius.gp - spectral radius of one step of each time integrator against
# omega dt (undamped test equation), from a gapbeam PREFIX.spectral_radius.dat
# (analysis = 'stability'; columns: 1 omega_dt [-], then one spectral radius [-] per method; the
# header line '# omega_dt newmark_fixed linear_acceleration ...' names the methods).
#
# Usage:
#   gnuplot -e "datafile='x.spectral_radius.dat'; outfile='x.spectral_radius.png'" \
#           scripts/spectral_radius.gp
#   gnuplot -e "datafile='x.spectral_radius.dat'; outfile='x.png'; plottitle='4 elements'" \
#           scripts/spectral_radius.gp
# Variables: datafile (required), outfile (required, PNG), plottitle (optional).
# Axes: omega dt on a log axis from 1e-2 to 1e3; spectral radius linear from 0 to 1.5, larger
# values clipped at the frame (an unstable method's curve leaves through the top). A dashed line
# marks radius 1 (neutral stability); dotted vertical lines mark the theoretical stability limits
# of the conditionally stable methods: central difference 2, Fox-Goodwin sqrt(6), RK4 2 sqrt(2),
# linear acceleration 2 sqrt(3). Methods whose radius is exactly 1 below their limit share the
# line at 1: they are drawn widest first, so each shows as a coloured edge.
# Legend: the method names of the header line (column numbers if the header is missing).
# Terminal: pngcairo if this gnuplot has it, else png (libgd); 900x600.

if (!exists("datafile") || !exists("outfile")) {
   print "spectral_radius.gp: set datafile and outfile, e.g. gnuplot -e \"datafile='x.spectral_radius.dat'; outfile='x.png'\" scripts/spectral_radius.gp"
   exit status 1
}
if (!exists("plottitle") || strlen(plottitle) == 0) { plottitle = "gapbeam: stability of the integrators" }

if (strstrt(GPVAL_TERMINALS, "pngcairo") > 0) {
   set terminal pngcairo noenhanced size 900,600 font ",11"
} else {
   set terminal png noenhanced size 900,600
}

# A text as a shell single-quoted word (a quote inside becomes '\'').
shq_(s, i) = (i > strlen(s)) ? "" : (((s[i:i] eq "'") ? "'\\''" : s[i:i]) . shq_(s, i + 1))
shquote(s) = "'" . shq_(s, 1) . "'"

# Method names: the header line '# omega_dt name name ...' (the first comment line that starts
# with omega_dt), without the '#'.
header = system("awk '/^#[[:space:]]*omega_dt([[:space:]]|$)/ { sub(/^#[[:space:]]*/, \"\"); print; exit }' " . shquote(datafile))
stats datafile using 1 nooutput
ncol = STATS_columns
if (words(header) >= 2) { ncol = words(header) }
name(i) = (words(header) >= i) ? word(header, i) : sprintf("column %d", i)
# A method's colour: fixed per name, so that charts of different decks agree.
known = "newmark_fixed linear_acceleration fox_goodwin central_difference hht generalized_alpha rk4 rk45 newmark_half_step paper exact"
palette = "#1f4e9c #d62728 #2ca02c #ff7f0e #9467bd #8c564b #e377c2 #17becf #7f7f7f #bcbd22 #000000"
spare = "#1b9e77 #d95f02 #7570b3 #e7298a #66a61e #e6ab02"
index_of(w, list) = (strstrt(" " . list . " ", " " . w . " ") == 0) ? 0 : \
   words(substr(list, 1, strstrt(" " . list . " ", " " . w . " ") - 1)) + 1
colour(i) = (index_of(name(i), known) > 0) ? word(palette, index_of(name(i), known)) \
   : word(spare, (i - 2) % words(spare) + 1)
# Line width: widest first, so that curves lying on each other at radius 1 all show.
lwidth(i) = 1.5 + 1.2*(ncol - i)

set output outfile
set title sprintf("%s\nspectral radius of one step, undamped test equation (%d methods)", \
   plottitle, ncol - 1)
set xlabel "omega dt [-]   (omega: circular frequency [rad/s], dt: time step [s])"
set ylabel "spectral radius [-]"
set logscale x
set xrange [1.0e-2 : 1.0e3]
set yrange [0 : 1.5]
set format x "%g"
set mxtics 10
set ytics 0.25
set grid xtics ytics lc rgb "#d8d8d8"
set key left bottom invert opaque box lc rgb "#b0b0b0" spacing 1.1 width 1

# Theoretical limits (omega dt): dotted vertical lines, labelled in steps above the line at 1.
limit_x = "2.0 2.449489742783178 2.8284271247461903 3.4641016151377544"
limit_tag = "CD FG RK4 LA"
limit_text = "2 sqrt(6) 2sqrt(2) 2sqrt(3)"
set style textbox opaque noborder margins 1, 1
do for [k = 1 : 4] {
   xl = real(word(limit_x, k))
   set arrow k from xl, graph 0 to xl, graph 1 nohead dt 3 lw 1.2 lc rgb "#404040" front
   set label 10 + k sprintf("%s: %s", word(limit_tag, k), word(limit_text, k)) \
      at xl/1.04, 1.46 - 0.075*(k - 1) right boxed front font ",10"
}

plot 1 with lines dt 2 lw 1.2 lc rgb "#000000" title "radius 1", \
     for [i = ncol : 2 : -1] datafile using 1:i with lines lw lwidth(i) lc rgb colour(i) \
        title name(i)

unset output
