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
# Variables: datafile (required), outfile (required; PNG, PDF or SVG by format), plottitle (optional).
# Axes: omega dt on a log axis from 1e-2 to 1e3; spectral radius linear from 0 to 1.5, larger
# values clipped at the frame (an unstable method's curve leaves through the top). A dashed line
# marks radius 1 (neutral stability); dotted vertical lines mark the theoretical stability limits
# of the conditionally stable methods: central difference 2, Fox-Goodwin sqrt(6), RK4 2 sqrt(2),
# linear acceleration 2 sqrt(3). Methods whose radius is exactly 1 below their limit share the
# line at 1: they are drawn widest first, so each shows as a coloured edge.
# Legend: the method names of the header line (column numbers if the header is missing).
# Terminal: scripts/terminal.gp (format png, pdf or svg); 900x600.

if (!exists("datafile") || !exists("outfile")) {
   print "spectral_radius.gp: set datafile and outfile, e.g. gnuplot -e \"datafile='x.spectral_radius.dat'; outfile='x.png'\" scripts/spectral_radius.gp"
   exit status 1
}
if (!exists("plottitle") || strlen(plottitle) == 0) { plottitle = "gapbeam: stability of the integrators" }

# The terminal (format png, pdf or svg; see scripts/terminal.gp), from this script's folder.
dirof_(s, i) = (i < 1) ? "." : ((s[i:i] eq "/") ? s[1:i-1] : dirof_(s, i - 1))
width = 900; height = 600
load dirof_(ARG0, strlen(ARG0)) . "/terminal.gp"

# A text as a shell single-quoted word (a quote inside becomes '\'').
# (Halving recursion: its depth is log2 of the length.)
shq_(s) = (strlen(s) <= 1) ? ((s eq "'") ? "'\\''" : s) \
   : shq_(s[1 : strlen(s)/2]) . shq_(s[strlen(s)/2 + 1 :])
shquote(s) = "'" . ((strstrt(s, "'") == 0) ? s : shq_(s)) . "'"

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
# Methods lying on the line at 1 (|radius - 1| < 1e-6 wherever omega dt <= 1, e.g. the trapezoidal
# rule, and the explicit methods below their limits): drawn after the others, widest first (2 px
# steps), so that each shows as a coloured band, and named in a note above the line.
flat = system("awk '!/^[[:space:]]*(#|$)/ && $1 <= 1 { for (i = 2; i <= NF; i++) if ($i - 1 > 1e-6 || 1 - $i > 1e-6) off[i] = 1; n = NF } END { s = \"\"; for (i = 2; i <= n; i++) if (!(i in off)) s = s \" \" i; print s }' " . shquote(datafile))
nflat = words(flat)
flat_rank(i) = (strstrt(flat . " ", " " . sprintf("%d", i) . " ") == 0) ? 0 : \
   words(substr(flat, 1, strstrt(flat . " ", " " . sprintf("%d", i) . " "))) + 1
lwidth(i) = (flat_rank(i) > 0) ? 2.0 + 2.0*(nflat - flat_rank(i)) : 2.0
flat_names = ""
do for [k = 1 : nflat] { flat_names = flat_names . ((k > 1) ? ", " : "") . name(int(word(flat, k))) }

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
set key right bottom opaque box lc rgb "#b0b0b0" spacing 1.1 width 1

# Theoretical limits (omega dt): dotted vertical lines, labelled near the bottom, each label
# ending at its line, in steps (the curves there are all above 0.5).
limit_x = "2.0 2.449489742783178 2.8284271247461903 3.4641016151377544"
limit_text = "CD: 2|FG: sqrt(6) = 2.449|RK4: 2 sqrt(2) = 2.828|LA: 2 sqrt(3) = 3.464"
field(s, k) = (k == 1) ? s[1 : strstrt(s . "|", "|") - 1] : field(s[strstrt(s, "|") + 1 :], k - 1)
set style textbox opaque noborder margins 1, 1
do for [k = 1 : 4] {
   xl = real(word(limit_x, k))
   set arrow k from xl, graph 0 to xl, graph 1 nohead dt 3 lw 1.2 lc rgb "#404040" back
   set label 10 + k field(limit_text, k) at xl/1.02, 0.06 + 0.075*(k - 1) right boxed front \
      font ",10" textcolor rgb "#303030"
}
set label 20 "theoretical stability limits:" at 2.0/1.02, 0.06 + 0.075*4 right front font ",10" \
   textcolor rgb "#303030"
if (nflat > 0) {
   set label 21 sprintf("radius 1 below the limit: %s", flat_names) at 0.013, 1.04 left front \
      font ",10" textcolor rgb "#303030"
}

# Drawing order: the other methods first, then those on the line at 1, widest first, then the
# dashed line; the legend (NaN entries) lists the methods in the header's order.
plot for [i = 2 : ncol] datafile using 1:(flat_rank(i) == 0 ? column(i) : NaN) with lines \
        lw lwidth(i) lc rgb colour(i) notitle, \
     for [k = 1 : nflat] datafile using 1:int(word(flat, k)) with lines \
        lw lwidth(int(word(flat, k))) lc rgb colour(int(word(flat, k))) notitle, \
     1 with lines dt 2 lw 1.2 lc rgb "#000000" notitle, \
     for [i = 2 : ncol] NaN with lines lw 3 lc rgb colour(i) title name(i), \
     NaN with lines dt 2 lw 1.2 lc rgb "#000000" title "radius 1"

unset output
