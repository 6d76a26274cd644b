# scripts/work_precision.gp - work-precision chart of the time integrators: relative error of the
# final state against elapsed time, log-log, one line per series, from the gapbeam
# PREFIX.wp_<series>.dat tables of an analysis = 'work_precision' run (columns: 1 seconds [s],
# 2 error [-] (relative final-state error against the exact integrator), 3 poincare_error [-],
# 4 steps [-], 5 parameter; first line '# <title>: <series>').
#
# Usage:
#   gnuplot -e "prefix='results/work_precision_4el'; outfile='x.png'" scripts/work_precision.gp
#   gnuplot -e "prefix='x'; outfile='x.png'; plottitle='4 elements'; errorcolumn=3" \
#           scripts/work_precision.gp
# Variables: prefix (required: the deck's &job output; every PREFIX.wp_*.dat is drawn),
#            outfile (required; PNG, PDF or SVG by format), plottitle (optional),
#            errorcolumn (optional: 2, the final-state error (default), or 3, the Poincare error).
# Series: found with ls; the legend is the series name from the file name (PREFIX.wp_<series>.dat);
# known series keep a fixed colour and marker across charts; a file without data rows (no run
# completed) is left out of the legend and named in a note under it. The exact integrator (series 'exact', one point) is a single black star.
# A run that failed or diverged is listed in PREFIX.work_precision_failed.dat: it is marked with a
# cross in its series' colour on a dashed line at the top, at its elapsed time, and a note under
# the legend counts them.
# Axes: x elapsed time [s], log; y relative error [-], log, a decade beyond the data, floored at
# 1e-16: an error below 1e-16 (the exact integrator against itself: 0) is drawn on the floor, and a
# note says so.
# Terminal: scripts/terminal.gp (format png, pdf or svg); 900x600.

if (!exists("prefix") || !exists("outfile")) {
   print "work_precision.gp: set prefix and outfile, e.g. gnuplot -e \"prefix='results/work_precision_4el'; outfile='x.png'\" scripts/work_precision.gp"
   exit status 1
}
if (!exists("plottitle") || strlen(plottitle) == 0) { plottitle = "gapbeam: work-precision" }
if (!exists("errorcolumn")) { errorcolumn = 2 }
if (errorcolumn != 2 && errorcolumn != 3) {
   print "work_precision.gp: errorcolumn must be 2 (final-state error) or 3 (Poincare error)"
   exit status 1
}

# The terminal (format png, pdf or svg; see scripts/terminal.gp), from this script's folder.
dirof_(s, i) = (i < 1) ? "." : ((s[i:i] eq "/") ? s[1:i-1] : dirof_(s, i - 1))
width = 900; height = 600
load dirof_(ARG0, strlen(ARG0)) . "/terminal.gp"

# A text as a shell single-quoted word (a quote inside becomes '\'').
# (Halving recursion: its depth is log2 of the length.)
shq_(s) = (strlen(s) <= 1) ? ((s eq "'") ? "'\\''" : s) \
   : shq_(s[1 : strlen(s)/2]) . shq_(s[strlen(s)/2 + 1 :])
shquote(s) = "'" . ((strstrt(s, "'") == 0) ? s : shq_(s)) . "'"

# The series: PREFIX.wp_<series>.dat files that hold a data row; names only (a series name is one
# word, the prefix may hold blanks), in the known order, then any other name in ls order.
lister = "for f in " . shquote(prefix) . ".wp_*.dat; do [ -f \"$f\" ] || continue; g=${f##*.wp_}; "
found = system(lister . "grep -q -v -E '^[[:space:]]*(#|$)' \"$f\" && printf '%s ' \"${g%.dat}\"; done; true")
empty = system(lister . "grep -q -v -E '^[[:space:]]*(#|$)' \"$f\" || printf '%s ' \"${g%.dat}\"; done; true")
known = "newmark_half_step newmark_fixed newmark_fixed_no_events paper hht generalized_alpha central_difference linear_acceleration fox_goodwin rk4 rk45 exact"
colours = "#1f4e9c #6baed6 #9ecae1 #17becf #9467bd #8c564b #ff7f0e #d62728 #2ca02c #e377c2 #bcbd22 #000000"
markers = "7 5 4 9 11 13 6 8 10 12 14 3"
spare_colours = "#1b9e77 #d95f02 #7570b3 #e7298a #66a61e #e6ab02 #a6761d #666666"
has(list, w) = strstrt(" " . list . " ", " " . w . " ") > 0
index_of(w, list) = has(list, w) ? words(substr(list, 1, strstrt(" " . list . " ", " " . w . " ") - 1)) + 1 : 0
series = ""
do for [k = 1 : words(known)] {
   if (has(found, word(known, k))) { series = series . " " . word(known, k) }
}
do for [k = 1 : words(found)] {
   if (!has(known, word(found, k))) { series = series . " " . word(found, k) }
}
nseries = words(series)
if (nseries == 0) {
   print sprintf("work_precision.gp: no %s.wp_*.dat file with data rows%s", prefix, \
      (words(empty) > 0) ? " (without: " . empty . ")" : "")
   exit status 1
}
sname(k) = word(series, k)
sfile(k) = prefix . ".wp_" . sname(k) . ".dat"
scolour(k) = (index_of(sname(k), known) > 0) ? word(colours, index_of(sname(k), known)) \
   : word(spare_colours, (k - 1) % words(spare_colours) + 1)
smarker(k) = (index_of(sname(k), known) > 0) ? int(word(markers, index_of(sname(k), known))) : 7

# Ranges: the extent of the data (errors above the floor only), a decade or so beyond.
floor_err = 1.0e-16
xmin = 1.0e300; xmax = -1.0e300; ymin = 1.0e300; ymax = -1.0e300; nfloor = 0; nfailed = 0
do for [k = 1 : nseries] {
   # (the tests keep a valid value in every row, so that stats never finds no data)
   stats sfile(k) using (($1 > 0) ? 1 : 0) nooutput
   if (STATS_sum > 0) {
      stats sfile(k) using (($1 > 0) ? $1 : NaN) nooutput
      xmin = (STATS_min < xmin) ? STATS_min : xmin
      xmax = (STATS_max > xmax) ? STATS_max : xmax
   }
   stats sfile(k) using (column(errorcolumn) < floor_err ? 1 : 0) nooutput
   nfloor = nfloor + STATS_sum
   stats sfile(k) using ((column(errorcolumn) >= floor_err && column(errorcolumn) <= 1.0e300) \
      ? 1 : 0) nooutput
   if (STATS_sum > 0) {
      stats sfile(k) using ((column(errorcolumn) >= floor_err && column(errorcolumn) <= 1.0e300) \
         ? column(errorcolumn) : NaN) nooutput
      ymin = (STATS_min < ymin) ? STATS_min : ymin
      ymax = (STATS_max > ymax) ? STATS_max : ymax
   }
}
if (ymax < ymin) { ymin = 1.0; ymax = 1.0 }
if (xmax <= 0) { xmin = 1.0e-3; xmax = 1.0 }
decade_down(v) = 10.0**floor(log10(v) - 1.0e-9)
decade_up(v) = 10.0**ceil(log10(v) + 1.0e-9)
y_lo = (nfloor > 0) ? floor_err : decade_down(ymin)
y_lo = (y_lo < floor_err) ? floor_err : y_lo
# The frame starts a little below the floor, so that points on the floor sit clear of the axis.
y_lo = y_lo/2.5
y_hi = decade_up(ymax)
if (y_hi <= 10.0*y_lo) { y_hi = 100.0*y_lo }
x_lo = decade_down(xmin/1.5); x_hi = decade_up(xmax*1.5)

set output outfile
errname = (errorcolumn == 2) ? "relative error of the final state" \
   : "relative error of the Poincare section"
set title sprintf("%s\n%s against the exact integrator, against elapsed time (%d series)", \
   plottitle, errname, nseries)
set xlabel "elapsed time [s]"
set ylabel ((errorcolumn == 2) ? "relative final-state error [-]" : "relative Poincare error [-]")
set logscale xy
set xrange [x_lo : x_hi]
set yrange [y_lo : y_hi]
set format x "%g"
set format y "1e%T"
set mxtics 10
set mytics 10
# y tics on whole decades, at most about 10 of them, one on the floor.
ystep = ceil(log10(y_hi/y_lo)/10.0)
set ytics 10.0**ceil(log10(y_lo) - 1.0e-9), 10.0**ystep
if (ystep > 1) { set mytics ystep }
set grid xtics ytics lc rgb "#d8d8d8"
set key outside right top spacing 1.15 samplen 2.5
set rmargin 25
set lmargin 10
# The exact integrator: drawn last, as a single large black star (its error against itself is 0).
has_exact = has(series, "exact") ? 1 : 0
lines = ""
do for [k = 1 : nseries] { if (sname(k) ne "exact") { lines = lines . " " . sname(k) } }
exact_floor = 0
# the exact integrator is the reference: its error is 0 by definition
if (has_exact) { exact_floor = 1 }
if (nfloor > 0) {
   set arrow 1 from graph 0, first floor_err to graph 1, first floor_err nohead dt 3 lw 1 \
      lc rgb "#808080" back
   set label 1 sprintf("<- errors below %.0e\n    drawn on the dotted line%s", floor_err, \
      (exact_floor > 0) ? "\n    (exact: 0, the reference)" : "") \
      at graph 1.01, first floor_err left front font ",10" textcolor rgb "#404040"
}
if (words(empty) > 0) {
   set label 2 sprintf("no data rows\n(no run completed):\n%s", empty) at graph 1.03, graph 0.35 \
      left front font ",10" textcolor rgb "#a00000"
}

# On the floor below 1e-16; an overflowed error (Infinity) left out.
clip(v) = (v < floor_err) ? floor_err : ((v > 1.0e300) ? NaN : v)
lfile(k) = prefix . ".wp_" . word(lines, k) . ".dat"
lk(k) = index_of(word(lines, k), series)
# Failed or diverged runs (PREFIX.work_precision_failed.dat: series number, seconds, parameter,
# steps; its title line ends with the series names in number order) are marked, not dropped: a
# cross of the series' colour on a dashed line at the top of the chart, at the run's time.
failfile = prefix . ".work_precision_failed.dat"
failnames = system("sed -n '1s/.*series numbers: *//p' " . shquote(failfile) . " 2>/dev/null")
nfailed = int(system("grep -c -v -E '^[[:space:]]*(#|$)' " . shquote(failfile) . " 2>/dev/null || true") + 0)
y_fail = y_hi/1.6
# a run that failed before it was timed (0 s) is drawn at the left edge
x_fail(t) = (t > 0) ? t : x_lo*1.3
fcolour(i) = (index_of(word(failnames, int(i)), series) > 0) \
   ? scolour(index_of(word(failnames, int(i)), series)) : "#808080"
fcol(i) = int(("0x" . fcolour(i)[2:7]) + 0)
if (nfailed > 0) {
   set label 3 sprintf("x on the top line:\n%d run%s failed\nor diverged\n(error not finite)", \
      nfailed, (nfailed == 1) ? "" : "s") at graph 1.03, graph 0.22 left front font ",10" \
      textcolor rgb "#a00000"
   set arrow 2 from graph 0, first y_fail to graph 1, first y_fail nohead dt 2 lw 1 \
      lc rgb "#d0a0a0" back
}
plot for [k = 1 : words(lines)] lfile(k) using 1:(clip(column(errorcolumn))) \
        with linespoints lw 2 pt smarker(lk(k)) ps 1.3 lc rgb scolour(lk(k)) title word(lines, k), \
     for [q = 1 : ((nfailed > 0) ? 1 : 0)] failfile using (x_fail($2)):(y_fail):(fcol($1)) \
        with points pt 2 ps 2.0 lw 2.5 lc rgb variable notitle, \
     for [k = 1 : has_exact] prefix . ".wp_exact.dat" using 1:(clip(column(errorcolumn))) \
        with points pt 3 ps 3.5 lw 2.5 lc rgb "#000000" title "exact"

unset output
