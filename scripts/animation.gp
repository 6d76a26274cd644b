# scripts/animation.gp - animated GIF of the beam against its stop over a few forcing periods,
# from a gapbeam PREFIX.shape.dat (a transient run with &output state_history = .true.): one
# block (gnuplot index) per history sample, columns x [m], w [m] (the deflected shape relative to
# the base, from the elements' Hermite shape functions), each block after a line '# t = <time>';
# header lines '# stop J: x = <m> m, dof w, side positive, gap <m>' name the stops.
#
# Usage:
#   gnuplot -e "datafile='x.shape.dat'; outfile='x.gif'" scripts/animation.gp
#   gnuplot -e "datafile='x.shape.dat'; outfile='x.gif'; frames=128; plottitle='9.8 Hz'" \
#           scripts/animation.gp
# Variables: datafile (required), outfile (required, GIF), plottitle (optional), frames
# (optional: the first `frames` samples are drawn, default 192 = 3 periods at 64 samples per
# period), delay (optional: hundredths of a second per frame, default 4).
# Picture: w in mm against x in mm (the deflection is drawn to its own scale: the y axis is
# stretched, the beam is 200 mm long and deflects a few mm); the beam's shape as a thick line,
# its nodes as dots (every shape_points-th point, from the header), the stops as red bars at their
# position and gap (a w stop on the + side sits at +gap, on the - side at -gap, 'both' at both),
# a thin grey trail of the tip over the frames so far, the time in the corner.
# Terminal: gif animate (libgd), 800x450.

if (!exists("datafile") || !exists("outfile")) {
   print "animation.gp: set datafile and outfile, e.g. gnuplot -e \"datafile='x.shape.dat'; outfile='x.gif'\" scripts/animation.gp"
   exit status 1
}
if (!exists("plottitle") || strlen(plottitle) == 0) { plottitle = "gapbeam: the beam in motion" }
if (!exists("frames")) { frames = 192 }
if (!exists("delay")) { delay = 4 }

# Blocks (samples) in the file, the extent of x and w over the frames drawn.
# the time of each block: the '# t = ...' lines, in order (one per block)
times = system("sed -n 's/^# t = *//p' '" . datafile . "'")
nblocks = words(times)
nframes = (frames < nblocks) ? int(frames) : nblocks
if (nframes < 1) {
   print sprintf("animation.gp: %s has no shape block", datafile)
   exit status 1
}
stats datafile index 0:(nframes - 1) using ($1*1.0e3):($2*1.0e3) nooutput
xlen = STATS_max_x
wmin = STATS_min_y;  wmax = STATS_max_y

# Points per element (the nodes are every per_element-th point), from the header.
per_element = int(system("sed -n 's/^# points per element: \\([0-9]*\\).*/\\1/p' '" . datafile . "' | awk 'NR == 1'"))
if (per_element < 1) { per_element = 8 }
# Stops from the header: x [mm], side (+1, -1, 2 both), gap [mm] (w stops only).
stopinfo = system("sed -n 's/^# stop [0-9]*: x = \\([^ ]*\\) m, dof w, side \\([a-z]*\\), gap \\([^ ]*\\).*/\\1 \\2 \\3/p' '" . datafile . "'")
nstops = words(stopinfo)/3
stopx(j) = 1.0e3*real(word(stopinfo, 3*j - 2))
stopside(j) = word(stopinfo, 3*j - 1)
stopgap(j) = 1.0e3*real(word(stopinfo, 3*j))
# The frame takes in the stops too.
do for [j = 1:nstops] {
   if (stopside(j) ne "negative" && stopgap(j) > wmax) { wmax = stopgap(j) }
   if (stopside(j) ne "positive" && -stopgap(j) < wmin) { wmin = -stopgap(j) }
}
wpad = 0.12*((wmax - wmin) > 0 ? (wmax - wmin) : 1.0)

set terminal gif animate delay int(delay) size 800,450 noenhanced font ",11"
set encoding utf8
set output outfile
set xrange [-0.03*xlen : 1.06*xlen]
set yrange [wmin - wpad : wmax + wpad]
set xlabel "x from the root [mm]"
set ylabel "w relative to the base [mm] (stretched)"
set grid lc rgb "#e0e0e0"
set xzeroaxis lt 1 lc rgb "#909090"
set key off
set style line 1 lw 3 lc rgb "#1f4e9c"
do for [j = 1:nstops] {
   if (stopside(j) ne "negative") {
      set arrow 10 + 2*j from stopx(j) - 0.03*xlen, stopgap(j) to stopx(j) + 0.03*xlen, stopgap(j) \
         nohead lw 5 lc rgb "#d62728" front
   }
   if (stopside(j) ne "positive") {
      set arrow 11 + 2*j from stopx(j) - 0.03*xlen, -stopgap(j) to stopx(j) + 0.03*xlen, -stopgap(j) \
         nohead lw 5 lc rgb "#d62728" front
   }
}
do for [i = 0:(nframes - 1)] {
   set title sprintf("%s\nt = %.4f s (frame %d of %d); red: the stop", plottitle, real(word(times, i + 1)), i + 1, nframes)
   plot datafile index 0:i using ($1*1.0e3 >= xlen*0.999 ? $1*1.0e3 : 1/0):($2*1.0e3) \
           with points pt 7 ps 0.4 lc rgb "#b0b0b0", \
        datafile index i using ($1*1.0e3):($2*1.0e3) with lines ls 1, \
        datafile index i every per_element using ($1*1.0e3):($2*1.0e3) with points pt 7 ps 0.9 lc rgb "#1f4e9c"
}
unset output
