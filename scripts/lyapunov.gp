# scripts/lyapunov.gp - largest Lyapunov exponent [1/s] of every sweep point, with its standard
# error as an error bar, against the forcing frequency [Hz] (or amplitude [mm peak to peak]),
# from a gapbeam PREFIX.sweep.dat (columns: 1 frequency [Hz], 2 amplitude_pp [m], 3 period,
# 4 label (p >= 1: period p; 0: undecided; -1: chaotic), 5 lyapunov [1/s], 6 lyapunov_error
# [1/s], 7.. impact statistics).
#
# Usage:
#   gnuplot -e "datafile='x.sweep.dat'; outfile='x.lyapunov.png'" scripts/lyapunov.gp
#   gnuplot -e "datafile='x.sweep.dat'; outfile='x.png'; xaxis='amplitude'" scripts/lyapunov.gp
# Variables: datafile (required), outfile (required; PNG, PDF or SVG by format), plottitle (optional),
#   xaxis (optional): 'frequency' (default; x = column 1 [Hz]) or 'amplitude' (x = column 2
#   in mm p-p). scripts/plot.sh picks 'amplitude' when the sweep has a single frequency.
#   label1, label2 (optional): axis texts of columns 1 and 2 (a sweep over other deck
#   variables; defaults: the forcing frequency [Hz] and amplitude [mm peak to peak]); scale2
#   (optional): factor on column 2 (default 1e3).
# Failed points (label -3, no exponent) are left out; unsettled ones (-2) are drawn as undecided.
# A black zero line separates contraction (periodic, < 0) from divergence (chaos, > 0).
# One line of the sweep (the other forcing variable takes one value): points coloured by the
# program's label, chaotic red, periodic blue, undecided grey, joined by a thin grey line in
# point order. A grid: a heat map of the exponent over the frequency-amplitude plane (tiles of
# the grid's spacing, a diverging palette centred on zero), chaotic points dotted, failed points
# (NaN exponent) crossed.
# Terminal: scripts/terminal.gp (format png, pdf or svg); 1000x600.

if (!exists("datafile") || !exists("outfile")) {
   print "lyapunov.gp: set datafile and outfile, e.g. gnuplot -e \"datafile='x.sweep.dat'; outfile='x.png'\" scripts/lyapunov.gp"
   exit status 1
}
if (!exists("plottitle") || strlen(plottitle) == 0) { plottitle = "gapbeam: sweep" }
if (!exists("xaxis") || strlen(xaxis) == 0) { xaxis = "frequency" }
if (!exists("label1") || strlen(label1) == 0) { label1 = "forcing frequency [Hz]" }
if (!exists("label2") || strlen(label2) == 0) { label2 = "forcing amplitude [mm peak to peak]" }
if (!exists("scale2")) { scale2 = 1.0e3 }
if (xaxis ne "frequency" && xaxis ne "amplitude") {
   print sprintf("lyapunov.gp: xaxis = '%s': expected 'frequency' or 'amplitude'", xaxis)
   exit status 1
}

# x: frequency [Hz] or amplitude [mm p-p]; c: the other forcing variable (one curve per value).
byfreq = (xaxis eq "frequency") ? 1 : 0
xval(f, a) = byfreq ? f : a*scale2
cval(f, a) = byfreq ? a*scale2 : f

# Distinct values of c: a datablock of "value count" rows (smooth frequency sorts and merges
# equal values), read into a word list. Fixed wide ranges: no autoscaling warnings.
set format x "%.15e"   # %e: gnuplot 5.4 cannot read back a %g such as 5e-05
set xrange [-1.0e30 : 1.0e30]
set yrange [-1.0e30 : 1.0e30]
set table $lyapunov_c
plot datafile using (cval($1, $2)):(($4 > -2.5) ? 1 : 1/0) smooth frequency
unset table
cvalues = ""
do for [i = 1:|$lyapunov_c|] {
   line = $lyapunov_c[i]
   if (strlen(line) > 0 && line[1:1] ne "#" && words(line) >= 2) { cvalues = cvalues . " " . word(line, 1) }
}
nc = words(cvalues)
set autoscale
set format x "%g"

stats datafile using (xval($1, $2)):(($4 > -2.5) ? $5 : 1/0) nooutput
npts = STATS_records
xmin = STATS_min_x;  xmax = STATS_max_x
stats datafile using (($4 == -1) ? 1 : 0) nooutput
nchaos = int(STATS_sum)
cmin = real(word(cvalues, 1));  cmax = real(word(cvalues, nc))
# Same value to 1e-9 relative (the text tables carry 17 digits, the word list 15).
same(a, b) = abs(a - b) <= 1.0e-9*(abs(a) + abs(b)) + 1.0e-300

# The terminal (format png, pdf or svg; see scripts/terminal.gp), from this script's folder.
dirof_(s, i) = (i < 1) ? "." : ((s[i:i] eq "/") ? s[1:i-1] : dirof_(s, i - 1))
width = 1000; height = 600
load dirof_(ARG0, strlen(ARG0)) . "/terminal.gp"
if (cairo) {
   psz = 0.9
} else {
   psz = 1.3
}

set output outfile
set title sprintf("%s\nLargest Lyapunov exponent of each of %d sweep points (%d chaotic), error bars: its standard error", \
   plottitle, npts, nchaos)
set xlabel byfreq ? label1 : label2
set ylabel "largest Lyapunov exponent λ [1/s]"
set format x "%g"
set format y "%g"
set grid lc rgb "#d8d8d8"
set xzeroaxis lt 1 lw 1.5 lc rgb "black"
# x: the extent plus 3 % each side (+-5 % of the value for a single one); y: autoscaled.
xpad = (xmax > xmin) ? 0.03*(xmax - xmin) : ((abs(xmin) > 0) ? 0.05*abs(xmin) : 1.0)
set xrange [xmin - xpad : xmax + xpad]
set offsets 0, 0, graph 0.05, graph 0.05
set key below horizontal box samplen 1.5 width 1
set bmargin 5
set tics front

if (nc <= 1) {
   unset colorbox
   # Classes: 1 periodic (label >= 1), 2 undecided (0, -2), 3 chaotic (-1), 4 failed (-3, no
   # exponent: not drawn); the key lists those present.
   lcls(l) = (l > 0.5) ? 1 : (l > -0.5) ? 2 : (l > -1.5) ? 3 : (l > -2.5) ? 2 : 4
   array lname[3] = ["periodic", "undecided", "chaotic"]
   array lcolour[3] = ["#1f4e9c", "#8a8a8a", "#d62728"]
   lpresent = ""
   do for [k = 1:3] {
      stats datafile using (lcls($4) == k ? 1 : 0) nooutput
      if (STATS_sum > 0) { lpresent = lpresent . sprintf(" %d", k) }
   }
   plot datafile using (xval($1, $2)):5 with lines lw 1 lc rgb "#c0c0c0" notitle, \
        for [w in lpresent] datafile using (xval($1, $2)):((lcls($4) == int(w)) ? $5 : 1/0):6 \
           with yerrorbars pt 7 ps psz lc rgb lcolour[int(w)] title lname[int(w)]
} else {
   # A grid: a heat map of the exponent over the frequency-amplitude plane, one tile per point
   # (the grid's spacing, from the table's title line as in chaos_map.gp), a diverging palette
   # centred on 0 (blue contracting, red diverging); chaotic points dotted, failed ones crossed.
   set format x "%.12g"
   set xrange [-1.0e30 : 1.0e30]
   set yrange [-1.0e30 : 1.0e30]
   set table $lyapunov_f
   plot datafile using 1:(1) smooth frequency
   set table $lyapunov_a
   plot datafile using ($2*scale2):(1) smooth frequency
   unset table
   set format x "%g"
   stats $lyapunov_f using 1 nooutput
   nf = STATS_records;  fmin = STATS_min;  fmax = STATS_max
   stats $lyapunov_a using 1 nooutput
   na = STATS_records;  amin = STATS_min;  amax = STATS_max
   header = system("head -n 1 '" . datafile . "' 2>/dev/null")
   gpos = strstrt(header, "grid: ")
   if (gpos > 0) {
      g = header[gpos + 6:]
      nf = int(word(g, 1));  fmin = real(word(g, 4));  fmax = real(word(g, 6))
      na = int(word(g, 8));  amin = scale2*real(word(g, 11));  amax = scale2*real(word(g, 13))
   }
   single(v) = (abs(v) > 0) ? 0.02*abs(v) : 0.05
   hf = (nf > 1) ? 0.5*(fmax - fmin)/(nf - 1) : single(fmin)
   ha = (na > 1) ? 0.5*(amax - amin)/(na - 1) : single(amin)
   stats datafile using (($5 == $5) ? abs($5) : 0) nooutput
   lmax = (STATS_max > 0) ? STATS_max : 1.0
   stats datafile using (($5 != $5) ? 1 : 0) nooutput
   nfailed = int(STATS_sum)
   set palette defined (-1 "#2166ac", -0.5 "#92c5de", 0 "#f7f7f7", 0.5 "#f4a582", 1 "#b2182b")
   set cbrange [-lmax : lmax]
   set cblabel "largest Lyapunov exponent λ [1/s]"
   set colorbox vertical user origin screen 0.885, screen 0.2 size screen 0.02, screen 0.62
   set rmargin at screen 0.84
   set xrange [fmin - 1.05*hf : fmax + 1.05*hf]
   set yrange [amin - 1.05*ha : amax + 1.05*ha]
   unset xzeroaxis
   unset grid
   set xlabel label1
   set ylabel label2
   set title sprintf("%s\nLargest Lyapunov exponent over the plane of the sweep: %d points (%d chaotic)", \
      plottitle, npts, nchaos)
   set style fill solid 1.0 noborder
   set key below horizontal nobox samplen 1 width 1
   plot datafile using 1:($2*scale2):(hf):(ha):(($5 == $5) ? $5 : 1/0) with boxxyerror \
           lc palette notitle, \
        for [q = 1:((nchaos > 0) ? 1 : 0)] datafile using 1:(($4 == -1) ? $2*scale2 : 1/0) \
           with points pt 7 ps 0.5 lc rgb "black" title "chaotic (label)", \
        for [q = 1:((nfailed > 0) ? 1 : 0)] datafile using 1:(($5 != $5) ? $2*scale2 : 1/0) \
           with points pt 2 ps 1.2 lw 2 lc rgb "black" title sprintf("failed (%d)", nfailed)
}

unset output
