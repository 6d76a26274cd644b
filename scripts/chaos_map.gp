# scripts/chaos_map.gp - chaos map of a sweep: every sweep point as a filled tile in the plane of
# forcing frequency [Hz] (x) and forcing amplitude [mm peak to peak] (y), coloured by its label,
# from a gapbeam PREFIX.sweep.dat (columns: 1 frequency [Hz], 2 amplitude_pp [m], 3 period,
# 4 label (p >= 1: period p; 0: undecided; -1: chaotic), 5 lyapunov [1/s], 6 lyapunov_error
# [1/s], 7 impacts_stop1, 8 peak_force_stop1 [N], 9 rms_force_stop1 [N], 10 work_rate_stop1 [W],
# 11 status, 12 certificate (1 certified, 2 disputed, 0 none), ..., 22 dispute (1 a contradiction
# within the label's own evidence, 2 a chaotic transient that settled on a period, 3 a check run
# disagrees, 0 none)). A sweep over other deck
# variables has their values in columns 1 and 2: give label1, label2 and scale2.
#
# Usage:
#   gnuplot -e "datafile='x.sweep.dat'; outfile='x.chaos_map.png'" scripts/chaos_map.gp
#   gnuplot -e "datafile='x.sweep.dat'; outfile='x.png'; plottitle='gap 1 mm'" scripts/chaos_map.gp
# Variables: datafile (required), outfile (required; PNG, PDF or SVG by format), plottitle
# (optional), label1 and label2 (axis texts of columns 1 and 2; defaults: forcing frequency
# [Hz], forcing amplitude [mm p-p]), scale2 (factor on column 2, default 1e3).
# Colours: chaotic red; undecided grey; period 1 blue, 2 green, 3 orange, 4 purple, 5-8 cyan,
# more than 8 brown; unsettled (the transient did not settle) dark grey; failed black. A point
# whose certificate is disputed carries a marker of what disputes it, counted in the legend: an
# open triangle for a contradiction (a period beside a positive exponent, or chaos beside a
# detected period), an open diamond for a chaotic transient (the chaos did not persist: the run
# continued settled on a period), a cross (x) for a check run giving another label (files
# without column 22: a cross for every disputed point). The legend (right) lists the classes present with their point counts. A
# small white dot with a black ring marks a point whose stop 1 saw no impact in the recorded periods (the linear,
# non-impacting response; such points are usually 'undecided' as long as the free vibration of
# the first mode has not died out).
# Tiles are as wide and as high as the grid spacing (the axis's extent over its number of values
# less one: exact on a uniform grid), taken from the whole grid named in the table's title line,
# so that a shard's points (a part of the grid) get the grid's tiles on the grid's frame. A failed
# point (NaN exponent) carries a black cross. A single frequency or a single amplitude (a line
# sweep) gives a strip of tiles in a shorter picture.
# Terminal: scripts/terminal.gp (format png, pdf or svg); 1000x650 (1000x330 for a strip).

if (!exists("datafile") || !exists("outfile")) {
   print "chaos_map.gp: set datafile and outfile, e.g. gnuplot -e \"datafile='x.sweep.dat'; outfile='x.png'\" scripts/chaos_map.gp"
   exit status 1
}
if (!exists("plottitle") || strlen(plottitle) == 0) { plottitle = "gapbeam: sweep" }
if (!exists("label1") || strlen(label1) == 0) { label1 = "forcing frequency [Hz]" }
if (!exists("label2") || strlen(label2) == 0) { label2 = "forcing amplitude [mm p-p]" }
if (!exists("scale2")) { scale2 = 1.0e3 }
# the certificate column (absent in files written before issue 11)
disputed(dummy) = (valid(12) && column(12) == 2) ? 1 : 0
# what disputes it (column 22; absent in files written before it: a check, for every dispute)
dkind(dummy) = (disputed(0) == 0) ? 0 : (valid(22) ? int(column(22)) : 3)

# Distinct values of a column: a datablock of "value count" rows (smooth frequency sorts and
# merges equal values); format with enough digits that distinct grid values stay distinct.
# (Fixed wide ranges: no autoscaling, so no warning about an empty range.)
set format x "%.12g"
set xrange [-1.0e30 : 1.0e30]
set yrange [-1.0e30 : 1.0e30]
set table $chaos_map_f
plot datafile using 1:(1) smooth frequency
set table $chaos_map_a
plot datafile using ($2*scale2):(1) smooth frequency
unset table
stats $chaos_map_f using 1 nooutput
nf = STATS_records;  fmin = STATS_min;  fmax = STATS_max
stats $chaos_map_a using 1 nooutput
na = STATS_records;  amin = STATS_min;  amax = STATS_max

# The whole grid, from the table's title line ('...; grid: NF frequencies from F1 to F2 Hz, NA
# amplitudes from A1 to A2 m'): a shard's file holds some points only, and its tiles must have
# the grid's size and sit on the grid's frame. Without that line, the points' own extent.
header = system("head -n 1 '" . datafile . "' 2>/dev/null")
gpos = strstrt(header, "grid: ")
if (gpos > 0) {
   g = header[gpos + 6:]
   nf = int(word(g, 1));  fmin = real(word(g, 4));  fmax = real(word(g, 6))
   na = int(word(g, 8));  amin = scale2*real(word(g, 11));  amax = scale2*real(word(g, 13))
}
# Half-widths of a tile (92 % of the spacing, so that a thin white seam shows between tiles);
# a single value gets a tile of 2 % of its magnitude (0.05 if zero) on that axis.
single(v) = (abs(v) > 0) ? 0.02*abs(v) : 0.05
hf = (nf > 1) ? 0.46*(fmax - fmin)/(nf - 1) : single(fmin)
ha = (na > 1) ? 0.46*(amax - amin)/(na - 1) : single(amin)
strip = (nf == 1 || na == 1) ? 1 : 0

# Classes: 1 chaotic, 2 undecided, 3 period 1, 4 period 2, 5 period 3, 6 period 4,
# 7 period 5-8, 8 period > 8, 9 unsettled, 10 failed.
cls(l) = (l < -2.5) ? 10 : (l < -1.5) ? 9 : (l < -0.5) ? 1 : (l < 0.5) ? 2 : (l < 1.5) ? 3 : \
   (l < 2.5) ? 4 : (l < 3.5) ? 5 : (l < 4.5) ? 6 : (l < 8.5) ? 7 : 8
array cname[10] = ["chaotic", "undecided", "period 1", "period 2", "period 3", "period 4", \
   "period 5-8", "period > 8", "unsettled", "failed"]
array ccolour[10] = ["#d62728", "#a8a8a8", "#1f4e9c", "#2ca02c", "#ff7f0e", "#8c4fbf", \
   "#17becf", "#8c564b", "#505050", "#000000"]
array ccount[10]
present = ""
do for [k = 1:10] {
   stats datafile using (cls($4) == k ? 1 : 0) nooutput
   ccount[k] = int(STATS_sum)
   if (ccount[k] > 0) { present = present . sprintf(" %d", k) }
}
stats datafile using (($7 == 0 && $4 > -2.5) ? 1 : 0) nooutput
nquiet = int(STATS_sum)
stats datafile using (dkind(0) == 3 ? 1 : 0) nooutput
ndisputed = int(STATS_sum)
stats datafile using (dkind(0) == 1 ? 1 : 0) nooutput
ncontra = int(STATS_sum)
stats datafile using (dkind(0) == 2 ? 1 : 0) nooutput
ntransient = int(STATS_sum)
npts = STATS_records
# failed points (their exponent is NaN in the table): marked with a black cross
stats datafile using (($5 != $5) ? 1 : 0) nooutput
nfailed = int(STATS_sum)

# The terminal (format png, pdf or svg; see scripts/terminal.gp), from this script's folder.
dirof_(s, i) = (i < 1) ? "." : ((s[i:i] eq "/") ? s[1:i-1] : dirof_(s, i - 1))
width = 1000; height = strip ? 330 : 650
load dirof_(ARG0, strlen(ARG0)) . "/terminal.gp"
ringsize = cairo ? 1.2 : 0.8

set output outfile
set xrange [fmin - 1.2*hf : fmax + 1.2*hf]
set yrange [amin - 1.2*ha : amax + 1.2*ha]
plural(n, one, many) = sprintf("%d %s", n, (n == 1) ? one : many)
if (label1 eq "forcing frequency [Hz]" && label2 eq "forcing amplitude [mm p-p]") {
   set title sprintf("%s\nChaos map: response class of each of %s (%s x %s)", plottitle, \
      plural(npts, "sweep point", "sweep points"), plural(nf, "frequency", "frequencies"), \
      plural(na, "amplitude", "amplitudes"))
} else {
   set title sprintf("%s\nChaos map: response class of each of %s (%d x %d values)", plottitle, \
      plural(npts, "sweep point", "sweep points"), nf, na)
}
set xlabel label1
set ylabel label2
set format x "%g"
set format y "%g"
if (na == 1) { set ytics (sprintf("%g", amin) amin) }
if (nf == 1) { set xtics (sprintf("%g", fmin) fmin) }
set key outside right top vertical Left reverse noautotitle samplen 1.5 spacing 1.2
set tics front out
set style fill solid 1.0 noborder

ringtitle = sprintf("no impact at stop 1 (%d)", nquiet)
plot for [w in present] datafile \
        using 1:(cls($4) == int(w) ? $2*scale2 : 1/0):(hf):(ha) with boxxyerror \
        lc rgb ccolour[int(w)] title sprintf("%s (%d)", cname[int(w)], ccount[int(w)]), \
     for [q = 1:(nquiet > 0 ? 1 : 0)] datafile using 1:(($7 == 0 && $4 > -2.5) ? $2*scale2 : 1/0) \
        with points pt 7 ps ringsize lc rgb "white" notitle, \
     for [q = 1:(nquiet > 0 ? 1 : 0)] datafile using 1:(($7 == 0 && $4 > -2.5) ? $2*scale2 : 1/0) \
        with points pt 6 ps ringsize lc rgb "black" title ringtitle, \
     for [q = 1:(ndisputed > 0 ? 1 : 0)] datafile using 1:(dkind(0) == 3 ? $2*scale2 : 1/0) \
        with points pt 2 ps 2.0*ringsize lw 2 lc rgb "black" \
        title sprintf("x: %d point%s whose check run gives another label", ndisputed, \
           (ndisputed == 1) ? "" : "s"), \
     for [q = 1:(ncontra > 0 ? 1 : 0)] datafile using 1:(dkind(0) == 1 ? $2*scale2 : 1/0) \
        with points pt 8 ps 2.0*ringsize lw 2 lc rgb "black" \
        title sprintf("triangle: %d label%s contradicting its own evidence", ncontra, \
           (ncontra == 1) ? "" : "s"), \
     for [q = 1:(ntransient > 0 ? 1 : 0)] datafile using 1:(dkind(0) == 2 ? $2*scale2 : 1/0) \
        with points pt 12 ps 2.0*ringsize lw 2 lc rgb "black" \
        title sprintf("diamond: %d chaotic transient%s, then a period", ntransient, \
           (ntransient == 1) ? "" : "s")

unset output
