# scripts/work_rate_map.gp - work-rate map of a sweep (issue 15): every sweep point as a tile in
# the plane of forcing frequency [Hz] (x) and the y axis (the base amplitude, or the deck
# variables y_variable names, e.g. both baffles' clearance '&stops gap(1), &stops gap(2)'),
# coloured by the normal work rate summed over the supports (log scale), with the regime of each
# point marked: 'I' impacting (the most loaded support in contact less than half the time) or
# 'S' sustained contact (a sliding whirl), followed by the period when one was detected, 'C'
# when chaotic or 'u' when unsettled; 'F' a failed point; a tile with no contact (work rate 0)
# is white. From a gapbeam PREFIX.sweep.dat (columns: 1 x (frequency [Hz]), 2 y, 3 period,
# 4 label (p >= 1: period p; 0 undecided; -1 chaotic; -2 unsettled; -3 failed), ...,
# 18 normal_work_rate_total [W], 19 wear_volume_rate_total [m3/s], 20 contact_fraction_max,
# 21 impacts_total, 22 dispute). A disputed certificate adds its own mark: 't' a chaotic
# transient (the chaos did not persist: the run continued settled on a period), '!' a label
# contradicting its own evidence (a period beside a positive exponent, chaos beside a period),
# '?' a check run giving another label (column 22; files without it: no mark).
#
# Usage:
#   gnuplot -e "datafile='x.sweep.dat'; outfile='x.work_rate_map.png'" scripts/work_rate_map.gp
# Variables: datafile, outfile (required); plottitle (optional); format (png, pdf, svg:
# scripts/terminal.gp).
# The y axis: its name and unit from the table's '# columns:' line (column 2, 'NAME [UNIT]'),
# or label2 when given; a value in m is drawn in mm.
# Tiles are as large as the grid spacing (92 %). Terminal: scripts/terminal.gp; 1000x650.

if (!exists("datafile") || !exists("outfile")) {
   print "work_rate_map.gp: set datafile and outfile, e.g. gnuplot -e \"datafile='x.sweep.dat'; outfile='x.png'\" scripts/work_rate_map.gp"
   exit status 1
}
if (!exists("plottitle") || strlen(plottitle) == 0) { plottitle = "gapbeam: work-rate map" }

dirof_(s, i) = (i < 1) ? "." : ((s[i:i] eq "/") ? s[1:i-1] : dirof_(s, i - 1))
width = 1000; height = 650
load dirof_(ARG0, strlen(ARG0)) . "/terminal.gp"

# The y axis: its name and unit from the columns line (column 2).
col2 = system("grep -m1 '^# columns:' '" . datafile . "' 2>/dev/null | cut -d, -f2 | sed 's/^ *//'")
upos = strstrt(col2, " [")
yname = (upos > 0) ? col2[1:upos - 1] : col2
yunit = (upos > 0) ? col2[upos + 2:strlen(col2) - 1] : ""
yscale = 1.0
if (yunit eq "m") { yscale = 1.0e3; yunit = "mm" }
if (yname eq "amplitude_pp" || strlen(yname) == 0) {
   ylab = "base amplitude, peak to peak [mm]"
} else {
   ylab = yname . " [" . yunit . "]"
}
if (exists("label2") && strlen(label2) > 0) { ylab = label2 }

stats datafile using 1 nooutput
nrec = STATS_records
set table $wr_f
plot datafile using 1:(1) smooth frequency
set table $wr_a
plot datafile using ($2*yscale):(1) smooth frequency
unset table
stats $wr_f using 1 nooutput
nf = STATS_records;  fmin = STATS_min;  fmax = STATS_max
stats $wr_a using 1 nooutput
na = STATS_records;  amin = STATS_min;  amax = STATS_max
single(v) = (abs(v) > 0) ? 0.02*abs(v) : 0.05
hf = (nf > 1) ? 0.46*(fmax - fmin)/(nf - 1) : single(fmin)
ha = (na > 1) ? 0.46*(amax - amin)/(na - 1) : single(amin)

# the colour range: the positive work rates, in decades
stats datafile using ($18 > 0 ? log10($18) : NaN) nooutput
lmin = floor(STATS_min);  lmax = ceil(STATS_max)
if (lmax <= lmin) { lmax = lmin + 1 }

set output outfile
set title plottitle . "\nnormal work rate (all supports) and regime"
set xlabel "forcing frequency [Hz]"
set ylabel ylab
set xrange [fmin - 1.2*hf : fmax + 1.2*hf]
set yrange [amin - 1.2*ha : amax + 1.2*ha]
set cbrange [lmin:lmax]
set cblabel "log10 normal work rate [W]"
set palette rgbformulae 22,13,-31
set style fill solid 1.0 noborder
set key off
# the regime: I impacting (the most loaded support in contact less than half the time), S
# sustained contact (sliding whirl), then the period when one was detected or C when chaotic
regime(cf, l, p) = (l < -2.5) ? "F" : ((cf <= 0) ? "" : ((cf < 0.5) ? "I" : "S") . \
   ((l > 0.5) ? sprintf("%d", int(p)) : ((l < -0.5 && l > -1.5) ? "C" : \
   ((l < -1.5) ? "u" : ""))))
# what disputes the certificate (column 22, absent in older files)
dmark(dummy) = !valid(22) ? "" : (column(22) == 1 ? "!" : (column(22) == 2 ? "t" : \
   (column(22) == 3 ? "?" : "")))
set label 2 "certificate disputed: t chaotic transient (then a period), ! contradiction in the label's evidence, ? a check run disagrees" \
   at graph 0.0, graph -0.17 font ",9"
set label 1 "I impacting, S sustained contact (sliding whirl); digit: period, C chaotic, u unsettled; F failed; white: no contact" \
   at graph 0.0, graph -0.13 font ",9"
set bmargin 7
plot datafile using 1:($2*yscale):(hf):(ha):($18 > 0 ? log10($18) : NaN) \
        with boxxyerror fc palette, \
     datafile using 1:($18 > 0 ? NaN : $2*yscale):(hf):(ha) \
        with boxxyerror fc rgb "white" fs solid 1.0 border lc rgb "#bbbbbb", \
     datafile using 1:($2*yscale):(regime($20, $4, $3) . dmark(0)) with labels font ",10" \
        tc rgb "black"
set output
