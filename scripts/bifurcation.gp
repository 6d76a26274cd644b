# scripts/bifurcation.gp - bifurcation diagram of a sweep: the Poincare root strain ε [µε]
# (once per forcing period, every recorded period of every sweep point) against the forcing
# frequency [Hz] or the forcing amplitude [mm peak to peak], from a gapbeam
# PREFIX.bifurcation.dat (columns: 1 frequency [Hz], 2 amplitude_pp [m], 3 strain [-],
# 4 strain_rate [1/s], 5 label of the point, 6 its certificate: 1 certified, 2 disputed, 0 none).
# A sweep over other deck variables has their values in columns 1 and 2 (x and y axes): give
# label1, label2 and scale2 (scripts/plot.sh does, from the table's header).
#
# Usage:
#   gnuplot -e "datafile='x.bifurcation.dat'; outfile='x.bifurcation.png'" scripts/bifurcation.gp
#   gnuplot -e "datafile='x.bifurcation.dat'; outfile='x.png'; xaxis='amplitude'" scripts/bifurcation.gp
# Variables: datafile (required), outfile (required; PNG, PDF or SVG by format), plottitle (optional),
#   xaxis (optional): 'frequency' (default; x = column 1 [Hz]) or 'amplitude' (x = column 2
#   in mm p-p). scripts/plot.sh picks 'amplitude' when the sweep has a single frequency.
#   label1, label2 (optional): axis text of columns 1 and 2 (defaults: the forcing frequency
#   [Hz] and amplitude [mm peak to peak]); scale2 (optional): factor on column 2 (default 1e3).
# Points of a disputed certificate (column 6 = 2) are ringed in black and counted in the key; a
# failed point (label -3, no Poincare points) is a black cross on the lower frame.
# A period-p point shows as p dots above its x; a chaotic point as a vertical smear. When the
# other forcing variable takes more than one value (a grid), small multiples: one panel per value
# (at most 16, evenly chosen, the title says how many of how many), on the same axes.
# Terminal: scripts/terminal.gp (format png, pdf or svg); 1000x650.

if (!exists("datafile") || !exists("outfile")) {
   print "bifurcation.gp: set datafile and outfile, e.g. gnuplot -e \"datafile='x.bifurcation.dat'; outfile='x.png'\" scripts/bifurcation.gp"
   exit status 1
}
if (!exists("plottitle") || strlen(plottitle) == 0) { plottitle = "gapbeam: sweep" }
if (!exists("xaxis") || strlen(xaxis) == 0) { xaxis = "frequency" }
if (!exists("label1") || strlen(label1) == 0) { label1 = "forcing frequency [Hz]" }
if (!exists("label2") || strlen(label2) == 0) { label2 = "forcing amplitude [mm peak to peak]" }
if (!exists("scale2")) { scale2 = 1.0e3 }
if (xaxis ne "frequency" && xaxis ne "amplitude") {
   print sprintf("bifurcation.gp: xaxis = '%s': expected 'frequency' or 'amplitude'", xaxis)
   exit status 1
}

# The terminal (format png, pdf or svg; see scripts/terminal.gp), from this script's folder.
dirof_(s, i) = (i < 1) ? "." : ((s[i:i] eq "/") ? s[1:i-1] : dirof_(s, i - 1))
width = 1000; height = 650
load dirof_(ARG0, strlen(ARG0)) . "/terminal.gp"
if (cairo) {
   dotsize = 0.25
} else {
   dotsize = 0.4
}

# x: frequency [Hz] or amplitude [mm p-p]; c: the other forcing variable (colour).
byfreq = (xaxis eq "frequency") ? 1 : 0
xval(f, a) = byfreq ? f : a*scale2
cval(f, a) = byfreq ? a*scale2 : f
# certificate and label columns (absent in files written before issue 11: none, no failure)
disputed(dummy) = (valid(6) && column(6) == 2) ? 1 : 0
failed(dummy) = (valid(5) && column(5) < -2.5) ? 1 : 0

stats datafile using (xval($1, $2)):($3*1.0e6) nooutput
npts = STATS_records
xmin = STATS_min_x;  xmax = STATS_max_x
ymin = STATS_min_y;  ymax = STATS_max_y
stats datafile using (cval($1, $2)) nooutput
cmin = STATS_min;  cmax = STATS_max
# disputed points (not dots: a point has a dot per recorded period, its rows consecutive)
lastx = -1.0e300
newpoint(x) = (isnew = (x != lastx) ? 1 : 0, lastx = x, isnew)
stats datafile using (disputed(0) ? newpoint(xval($1, $2)) : 0) nooutput
ndisputed = int(STATS_sum)
stats datafile using (failed(0)) nooutput
nfailed = int(STATS_sum)
# Colour by the other variable only when it varies (relative spread above round-off).
colour = ((cmax - cmin) > 1.0e-9*(abs(cmax) + abs(cmin))) ? 1 : 0

# Frame: the extent plus 3 % each side (x) and 5 % (y); a degenerate extent gets +-5 % of its
# magnitude (1 if zero).
max2(a, b) = (a > b) ? a : b
pad(lo, hi, f) = ((hi - lo) > 0) ? f*(hi - lo) : ((max2(abs(lo), abs(hi)) > 0) ? 0.05*max2(abs(lo), abs(hi)) : 1.0)
set xrange [xmin - pad(xmin, xmax, 0.03) : xmax + pad(xmin, xmax, 0.03)]
set yrange [ymin - pad(ymin, ymax, 0.05) : ymax + pad(ymin, ymax, 0.05)]

set output outfile
set title sprintf("%s\nBifurcation diagram: Poincare root strain once per forcing period (%d points)", \
   plottitle, npts)
set xlabel byfreq ? label1 : label2
set ylabel "root strain ε [µε]"
set format x "%g"
set format y "%g"
set grid lc rgb "#d0d0d0"
if (ndisputed + nfailed > 0) { set key top left opaque } else { set key off }
set tics front

if (colour) {
   # A grid: small multiples, one panel per value of the other forcing variable (at most 16,
   # evenly chosen when there are more), all on the same axes.
   # (%e, not %g: gnuplot 5.4 cannot read back '5e-05', a %g without a decimal point)
   set format x "%.15e"
   set table $bifurcation_c
   plot datafile using (cval($1, $2)):(1) smooth frequency
   unset table
   set format x "%g"
   cvalues = ""
   do for [i = 1:|$bifurcation_c|] {
      line = $bifurcation_c[i]
      if (strlen(line) > 0 && line[1:1] ne "#" && words(line) >= 2) { cvalues = cvalues . " " . word(line, 1) }
   }
   nc = words(cvalues)
   npanel = (nc > 16) ? 16 : nc
   pick(k) = (nc <= 16) ? k : 1 + int(floor((k - 1)*(nc - 1.0)/(npanel - 1) + 0.5))
   ncols = int(ceil(sqrt(npanel)))
   nrows = int(ceil(npanel*1.0/ncols))
   same(a, b) = abs(a - b) <= 1.0e-9*(abs(a) + abs(b)) + 1.0e-300
   cunit = ""
   unset title
   set multiplot layout nrows, ncols title sprintf("%s\nBifurcation diagrams, one per %s%s (%d points)", \
      plottitle, "value of " . (byfreq ? label2 : label1), \
      (nc > npanel) ? sprintf(" (%d of %d shown)", npanel, nc) : "", npts) margins 0.07, 0.98, 0.08, 0.90 spacing 0.035, 0.06
   set xlabel ""
   set ylabel ""
   set format x "%g"
   do for [k = 1:npanel] {
      cv = real(word(cvalues, pick(k)))
      set label 1 sprintf("%g %s", cv, cunit) at graph 0.03, graph 0.92 left front font ",9" \
         textcolor rgb "#404040"
      if (k > npanel - ncols) { set xlabel byfreq ? label1 : label2 } else { set xlabel "" }
      if ((k - 1) % ncols == 0) { set ylabel "root strain ε [µε]" } else { set ylabel "" }
      plot datafile using (same(cval($1, $2), cv) ? xval($1, $2) : 1/0):($3*1.0e6) \
         with points pt 7 ps dotsize lc rgb "#1f4e9c" notitle
   }
   unset multiplot
} else {
   unset colorbox
   plot datafile using (xval($1, $2)):($3*1.0e6) with points pt 7 ps dotsize lc rgb "#1f4e9c" notitle, \
      for [q = 1:(ndisputed > 0 ? 1 : 0)] datafile using (xval($1, $2)):(disputed(0) ? \
      $3*1.0e6 : 1/0) with points pt 6 ps 3*dotsize lc rgb "black" \
      title sprintf("ringed: %d point%s whose check run (perturbed start, tighter accuracy) gives another label", \
         ndisputed, (ndisputed == 1) ? "" : "s"), \
      for [q = 1:(nfailed > 0 ? 1 : 0)] datafile using (xval($1, $2)):(failed(0) ? \
      ymin - 0.5*pad(ymin, ymax, 0.05) : 1/0) with points pt 2 ps 1.5 lc rgb "black" \
      title "failed point (the run stopped: its error is in the file)"
}

unset output
