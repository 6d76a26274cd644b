# scripts/strain_history.gp - time history of the root strain (paper Fig. 3) and of the stop
# force(s), from a gapbeam PREFIX.history.dat (columns: 1 time [s], 2 strain [-],
# 3 strain_rate [1/s], 4 tip_displacement [m], 5.. stop_force_1.. [N]).
#
# Usage:
#   gnuplot -e "datafile='x.history.dat'; outfile='x.history.png'" scripts/strain_history.gp
#   gnuplot -e "datafile='x.history.dat'; outfile='x.png'; plottitle='10.5 Hz'" scripts/strain_history.gp
# Variables: datafile (required), outfile (required; PNG, PDF or SVG by format), plottitle (optional),
# peaks (optional: the largest force of each stop over the whole record [N], event-located, from
# /impacts/peak_force: scripts/plot.sh passes them).
# Two panels over the whole recorded history, sharing the time axis: the root strain in
# microstrain (strain * 1e6) on top, the stop force of every stop (columns 5..) below; without a
# stop-force column (no stops) the strain panel alone is drawn. The history is sampled
# (samples_per_period a period), so a short impact's peak falls between samples and the curve
# under-reads it; the largest force of each stop over the record, which the program locates at
# the events, is drawn as a dashed line with its value, beside the largest sampled value.
# Terminal: scripts/terminal.gp (format png, pdf or svg); 900x600.

if (!exists("datafile") || !exists("outfile")) {
   print "strain_history.gp: set datafile and outfile, e.g. gnuplot -e \"datafile='x.history.dat'; outfile='x.png'\" scripts/strain_history.gp"
   exit status 1
}
if (!exists("plottitle") || strlen(plottitle) == 0) { plottitle = "gapbeam: strain time history" }

# The terminal (format png, pdf or svg; see scripts/terminal.gp), from this script's folder.
dirof_(s, i) = (i < 1) ? "." : ((s[i:i] eq "/") ? s[1:i-1] : dirof_(s, i - 1))
width = 900; height = 600
load dirof_(ARG0, strlen(ARG0)) . "/terminal.gp"

stats datafile using 1 nooutput
ncol = STATS_columns
tmin = STATS_min
tmax = STATS_max
nstops = (ncol >= 5) ? ncol - 4 : 0

set output outfile
set xrange [tmin : tmax]
set format x "%g"
set format y "%g"
set grid lc rgb "#d0d0d0"
set xzeroaxis lt 1 lc rgb "#a0a0a0"
set lmargin at screen 0.11
set rmargin at screen 0.97

if (nstops > 0) {
   set multiplot title plottitle
   # Top panel: root strain.
   set tmargin at screen 0.90
   set bmargin at screen 0.52
   set format x ""
   set xlabel ""
   set ylabel "root strain ε [µε]"
   set key off
   set offsets 0, 0, graph 0.05, graph 0.05
   plot datafile using 1:($2*1.0e6) with lines lw 1.2 lc rgb "#1f4e9c" notitle
   # Bottom panel: stop force(s).
   set tmargin at screen 0.46
   set bmargin at screen 0.10
   set format x "%g"
   set xlabel "time t [s]"
   set ylabel "stop force [N]"
   set offsets 0, 0, graph 0.08, 0
   if (!exists("peaks")) { peaks = "" }
   npk = words(peaks)
   sampled_max = 0.0
   do for [i = 5:ncol] {
      stats datafile using i nooutput
      sampled_max = (STATS_max > sampled_max) ? STATS_max : sampled_max
   }
   if (npk > 0) {
      peak_max = 0.0
      do for [i = 1:npk] { peak_max = (real(word(peaks, i)) > peak_max) ? real(word(peaks, i)) : peak_max }
      set yrange [0 : 1.12*peak_max]
      do for [i = 1:npk] {
         set arrow 10 + i from graph 0, first real(word(peaks, i)) to graph 1, first real(word(peaks, i)) \
            nohead dt 2 lw 1.2 lc rgb "#b00020" front
      }
      set label 10 sprintf("dashed: largest force of the record, located at the events: %.3g N (the samples shown reach %.3g N)", \
         peak_max, sampled_max) at graph 0.01, graph 0.95 left front font ",9" textcolor rgb "#b00020"
   }
   if (nstops > 1) {
      set key horizontal top right opaque samplen 2
      set offsets 0, 0, graph 0.25, 0
   } else {
      set key off
   }
   plot for [i=5:ncol] datafile using 1:i with lines lw 1.2 title sprintf("stop %d", i - 4)
   unset arrow
   unset label
   unset multiplot
} else {
   set title plottitle
   set xlabel "time t [s]"
   set ylabel "root strain ε [µε]"
   set key off
   set offsets 0, 0, graph 0.05, graph 0.05
   plot datafile using 1:($2*1.0e6) with lines lw 1.2 lc rgb "#1f4e9c" notitle
}

unset output
