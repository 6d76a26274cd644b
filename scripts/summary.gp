# scripts/summary.gp - the main job's summary figure: what gapbeam is for, on one page.
#
#   Top row: the Poincare maps of the paper's three 4-element cases (10.5 Hz at 3.7 mm, 10.2 and
#   9.8 Hz at 4.0 mm p-p) with the reference decks (lumped mass, translational masses only), each
#   titled with this model's label, Lyapunov exponent and certificate, the paper's claim, and the
#   label the same case gets with the rigid half element's rotary inertia (the sensitivity of
#   docs/paper_regimes.md). Second row: their root strain over the first 5 forcing periods of
#   the record, against the simulation time t (as in every figure: /history/time).
#   Bottom left: the bifurcation diagram along 4.0 mm p-p, frequency swept up (blue) and down
#   (orange), the up sweep's chaotic bands shaded, the paper's two 4 mm cases marked; under it the
#   largest Lyapunov exponent along the up sweep. Bottom right: the paper's claims against this
#   model's results, as scripts/main_summary.py wrote them (labels read from the result files).
#
# Usage (scripts/run.sh runs it after the main job and main_summary.py):
#   gnuplot -e "dir='results/main'; outfile='results/main/summary.png'" scripts/summary.gp
# Variables: dir (required: the main job's folder, with paper_10p5hz.*, paper_10p2hz.*,
# paper_9p8hz.*, line_4mm_up.*, line_4mm_down.* and summary_vars.gp), outfile (required), format
# (png, pdf, svg: scripts/terminal.gp).

if (!exists("dir") || !exists("outfile")) {
   print "summary.gp: set dir and outfile, e.g. gnuplot -e \"dir='results/main'; outfile='x.png'\" scripts/summary.gp"
   exit status 1
}
dirof_(s, i) = (i < 1) ? "." : ((s[i:i] eq "/") ? s[1:i-1] : dirof_(s, i - 1))
width = 1700; height = 1250
load dirof_(ARG0, strlen(ARG0)) . "/terminal.gp"
load dir . "/summary_vars.gp"
if (!exists("label1")) { label1 = "?"; lambda1 = "" }
if (!exists("label2")) { label2 = "?"; lambda2 = "" }
if (!exists("label3")) { label3 = "?"; lambda3 = "" }
if (!exists("alt1")) { alt1 = "" }
if (!exists("alt2")) { alt2 = "" }
if (!exists("alt3")) { alt3 = "" }
if (!exists("bands")) { bands = "" }
if (!exists("band_step")) { band_step = 0.01 }

array pre[3] = ["paper_10p5hz", "paper_10p2hz", "paper_9p8hz"]
array cases[3]
array labels[3]
array lambdas[3]
array papers[3]
array verdicts[3]
array alts[3]
alts[1] = alt1; alts[2] = alt2; alts[3] = alt3
cases[1] = case1; cases[2] = case2; cases[3] = case3
labels[1] = label1; labels[2] = label2; labels[3] = label3
lambdas[1] = lambda1; lambdas[2] = lambda2; lambdas[3] = lambda3
papers[1] = paper1; papers[2] = paper2; papers[3] = paper3
verdicts[1] = verdict1; verdicts[2] = verdict2; verdicts[3] = verdict3

set output outfile
set multiplot title "gapbeam: a cantilever against a one-sided stop (Moon & Shaw), the paper's 4-element model\nwhere the response is periodic and where chaotic, and how that compares with Moorthy et al." font ",14"
set grid lc rgb "#e0e0e0"
set format x "%g"
set format y "%g"
set key off
set tics front

# --- top row: Poincare maps; second row: strain histories ---
px0 = 0.05; pw = 0.295; pgap = 0.025
do for [k = 1:3] {
   x0 = px0 + (k - 1)*(pw + pgap)
   set lmargin at screen x0 + 0.035
   set rmargin at screen x0 + pw
   set tmargin at screen 0.86
   set bmargin at screen 0.655
   f = dir . "/" . pre[k] . ".poincare.dat"
   set autoscale xy
   stats f using ($1*1.0e6):($2*1.0e6) nooutput
   n = STATS_records
   xs = STATS_max_x - STATS_min_x; ys = STATS_max_y - STATS_min_y
   xh = (xs > 0.02*abs(STATS_max_x)) ? 0.6*xs : 0.05*abs(STATS_max_x) + 1
   yh = (ys > 0.02*abs(STATS_max_y)) ? 0.6*ys : 0.05*abs(STATS_max_y) + 1
   xc = 0.5*(STATS_max_x + STATS_min_x); yc = 0.5*(STATS_max_y + STATS_min_y)
   set xrange [xc - xh : xc + xh]
   set yrange [yc - yh : yc + yh]
   vcol = (verdicts[k] eq "agrees") ? "#1a7f37" : "#b00020"
   set title sprintf("%s: gapbeam %s\n%s; %s%s", cases[k], labels[k], lambdas[k], papers[k], \
      (strlen(alts[k]) > 0) ? "\nrigid half element: " . alts[k] : "") font ",10" \
      textcolor rgb vcol
   set xlabel "root strain ε [µε]" offset 0, 0.4
   set ylabel (k == 1) ? "root strain rate dε/dt [µε/s]" : ""
   plot f using ($1*1.0e6):($2*1.0e6) with points pt 7 ps ((n > 50) ? 0.35 : 1.2) \
      lc rgb "#1f4e9c"
   # strain history: the first 5 forcing periods of the record
   set tmargin at screen 0.605
   set bmargin at screen 0.505
   h = dir . "/" . pre[k] . ".history.dat"
   set autoscale xy
   stats h using 1 nooutput
   t0 = STATS_min
   stats f every ::0::1 using 5 nooutput
   period = STATS_max - STATS_min
   set xrange [t0 : t0 + 5*period]
   unset title
   set autoscale y
   set xlabel "time t [s]" offset 0, 0.4
   set ylabel (k == 1) ? "root strain ε [µε]" : ""
   plot h using 1:($2*1.0e6) with lines lw 1.3 lc rgb "#1f4e9c"
}

# --- bottom left: bifurcation diagram along 4 mm, and the exponent ---
up = dir . "/line_4mm_up"
down = dir . "/line_4mm_down"
set autoscale xy
stats up . ".bifurcation.dat" using 1:($3*1.0e6) nooutput
fmin = STATS_min_x; fmax = STATS_max_x
emin = STATS_min_y; emax = STATS_max_y
stats down . ".bifurcation.dat" using ($3*1.0e6) nooutput
emin = (STATS_min < emin) ? STATS_min : emin
emax = (STATS_max > emax) ? STATS_max : emax
epad = 0.05*(emax - emin)
set lmargin at screen 0.085
set rmargin at screen 0.62
set tmargin at screen 0.425
set bmargin at screen 0.20
set xrange [fmin - 0.02 : fmax + 0.02]
set yrange [emin - epad : emax + epad]
set title "Bifurcation diagram at 4.0 mm p-p: swept up (blue) and down (orange); shaded: chaotic (up)" font ",11"
set xlabel ""
set format x ""
set ylabel "root strain ε [µε]"
nb = words(bands)/2
do for [b = 1:nb] {
   set object 100 + b rectangle from real(word(bands, 2*b - 1)) - band_step/2, graph 0 \
      to real(word(bands, 2*b)) + band_step/2, graph 1 fc rgb "#f6c9c9" fs solid 1.0 noborder behind
}
set arrow 1 from 9.8, graph 0 to 9.8, graph 1 nohead dt 2 lw 1.5 lc rgb "#404040" front
set arrow 2 from 10.2, graph 0 to 10.2, graph 1 nohead dt 2 lw 1.5 lc rgb "#404040" front
set label 1 "9.8 Hz (Fig. 5)" at 9.8, graph 0.04 right offset -0.3, 0 front font ",10"
set label 2 "10.2 Hz (Fig. 6)" at 10.2, graph 0.04 left offset 0.3, 0 front font ",10"
dot = cairo ? 0.18 : 0.35
plot up . ".bifurcation.dat" using 1:($3*1.0e6) with points pt 7 ps dot lc rgb "#1f4e9c", \
     down . ".bifurcation.dat" using ($1 + 0.25*band_step):($3*1.0e6) with points pt 7 ps dot \
        lc rgb "#e07b00"
unset object
do for [b = 1:nb] { unset object 100 + b }
unset label 1
unset label 2
set tmargin at screen 0.19
set bmargin at screen 0.06
unset title
set format x "%g"
set xlabel "forcing frequency [Hz]"
set ylabel "largest Lyapunov\nexponent λ [1/s]"
set autoscale y
set xzeroaxis lt 1 lw 1.2 lc rgb "black"
plot up . ".sweep.dat" using 1:5 with linespoints pt 7 ps 0.4 lw 1 lc rgb "#1f4e9c", \
     up . ".sweep.dat" using 1:(($4 == -1) ? $5 : 1/0) with points pt 7 ps 0.6 lc rgb "#d62728"
unset arrow 1
unset arrow 2
unset xzeroaxis

# --- bottom right: the claims ---
set lmargin at screen 0.65
set rmargin at screen 0.985
set tmargin at screen 0.425
set bmargin at screen 0.06
unset border
unset tics
unset xlabel
unset ylabel
unset grid
set xrange [0 : 1]
set yrange [0 : 1]
set title "The paper against this model (labels from the result files)" font ",12"
# rows placed by their line counts (rowlines<i>, from main_summary.py), a blank line between
rowy = 1.0
do for [i = 1:nclaims] {
   eval sprintf("rowtext = row%d", i)
   eval sprintf("v = verdict%d", i)
   nl = exists(sprintf("rowlines%d", i)) ? value(sprintf("rowlines%d", i)) : 5
   set label 10 + i rowtext at graph 0.0, graph rowy left front font ",10" \
      textcolor rgb ((v eq "agrees") ? "#1a7f37" : "#b00020")
   rowy = rowy - (nl + 0.6)*0.036
}
set label 30 "green: agrees with the paper; red: differs. The regime is very sensitive to the\nlumped mass's rotary inertia and to the mesh (docs/paper_regimes.md)." \
   at graph 0.0, graph -0.03 left front font ",9" textcolor rgb "#505050"
plot NaN notitle
unset multiplot
unset output
