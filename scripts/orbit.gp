# scripts/orbit.gp - the tube's orbit at each support of a two-plane run (issue 15): v against w
# [mm] over the history, with the support's clearance circle (radius gap, centred at the hole's
# offset) drawn, one panel per support. From a gapbeam PREFIX.orbit.dat (columns: 1 time [s],
# then per support j: w_j [m], v_j [m], normal_force_j [N], tangential_force_j [N]) and
# PREFIX.supports.dat (columns: 1 stop, 2 node, 3 x [m], 4 gap [m], 5 offset_w [m],
# 6 offset_v [m], 7 circular (1) or flat (0)).
#
# Usage:
#   gnuplot -e "orbitfile='x.orbit.dat'; supportsfile='x.supports.dat'; outfile='x.orbit.png'" \
#      scripts/orbit.gp
# Variables: orbitfile, supportsfile, outfile (required); plottitle (optional); format (png, pdf,
# svg: scripts/terminal.gp).
# Samples in contact (normal force > 0) are drawn in red, the free flight in blue. A flat stop
# (circular 0) is drawn as the line w = offset_w + gap instead of a circle. Equal scales on both
# axes, so that a circle looks round. Terminal: scripts/terminal.gp; 450 pixels per panel wide.

if (!exists("orbitfile") || !exists("supportsfile") || !exists("outfile")) {
   print "orbit.gp: set orbitfile, supportsfile and outfile, e.g. gnuplot -e \"orbitfile='x.orbit.dat'; supportsfile='x.supports.dat'; outfile='x.png'\" scripts/orbit.gp"
   exit status 1
}
if (!exists("plottitle") || strlen(plottitle) == 0) { plottitle = "gapbeam: orbits at the supports" }

stats supportsfile using 1 nooutput
ns = STATS_records
if (ns < 1) {
   print "orbit.gp: no support in ", supportsfile
   exit status 1
}

dirof_(s, i) = (i < 1) ? "." : ((s[i:i] eq "/") ? s[1:i-1] : dirof_(s, i - 1))
width = 450 * ns; height = 520
load dirof_(ARG0, strlen(ARG0)) . "/terminal.gp"
set output outfile

set multiplot layout 1, ns title plottitle
set size ratio -1
set grid
set xlabel "w [mm]"
set ylabel "v [mm]"
set key bottom right font ",9"
set trange [0:2*pi]
set samples 361
do for [j=1:ns] {
   unset parametric
   set autoscale xy
   stats supportsfile every ::(j-1)::(j-1) using 2 nooutput;  node = STATS_min
   stats supportsfile every ::(j-1)::(j-1) using 3 nooutput;  xs = STATS_min
   stats supportsfile every ::(j-1)::(j-1) using 4 nooutput;  g = STATS_min*1.0e3
   stats supportsfile every ::(j-1)::(j-1) using 5 nooutput;  ow = STATS_min*1.0e3
   stats supportsfile every ::(j-1)::(j-1) using 6 nooutput;  ov = STATS_min*1.0e3
   stats supportsfile every ::(j-1)::(j-1) using 7 nooutput;  circ = STATS_min
   cw = 4*j - 2; cv = 4*j - 1; cf = 4*j
   stats orbitfile using (column(cw)*1.0e3):(column(cv)*1.0e3) nooutput
   r = 1.15*(abs(STATS_min_x - ow) > abs(STATS_max_x - ow) ? abs(STATS_min_x - ow) : abs(STATS_max_x - ow))
   r2 = 1.15*(abs(STATS_min_y - ov) > abs(STATS_max_y - ov) ? abs(STATS_min_y - ov) : abs(STATS_max_y - ov))
   r = (r2 > r) ? r2 : r
   r = (1.15*g > r) ? 1.15*g : r
   set xrange [ow - r:ow + r]
   set yrange [ov - r:ov + r]
   set title sprintf("support %d: node %d, x = %.3g m, gap %.3g mm", j, node, xs, g)
   set parametric
   if (circ > 0.5) {
      plot ow + g*cos(t), ov + g*sin(t) with lines lw 2 lc rgb "black" title "clearance", \
           orbitfile using (column(cw)*1.0e3):(column(cf) > 0 ? NaN : column(cv)*1.0e3) \
              with lines lc rgb "#1f77b4" title "free", \
           orbitfile using (column(cw)*1.0e3):(column(cf) > 0 ? column(cv)*1.0e3 : NaN) \
              with points pt 7 ps 0.4 lc rgb "#d62728" title "in contact"
   } else {
      plot ow + g, (ov - r) + 2*r*t/(2*pi) with lines lw 2 lc rgb "black" title "stop", \
           orbitfile using (column(cw)*1.0e3):(column(cf) > 0 ? NaN : column(cv)*1.0e3) \
              with lines lc rgb "#1f77b4" title "free", \
           orbitfile using (column(cw)*1.0e3):(column(cf) > 0 ? column(cv)*1.0e3 : NaN) \
              with points pt 7 ps 0.4 lc rgb "#d62728" title "in contact"
   }
}
unset multiplot
set output
