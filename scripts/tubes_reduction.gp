# scripts/tubes_reduction.gp - work-rate error against CPU, full and reduced tube models
# (the chart of scripts/bench_tubes.sh).
#
# Usage: gnuplot -e "datafile='bench_results/tubes_reduction.dat'; \
#                    outfile='bench_results/tubes_reduction.png'" scripts/tubes_reduction.gp
#        (cases='periodic deck' draws both panels when the periodic part was run; default 'deck')
#
# datafile: one line per run (scripts/bench_tubes.py): case (periodic | deck), curve (full |
# modal | auto | auto_rk45 | auto_exp | modal_exp | full_exp), kind, cut-off [Hz], tolerance, coordinates, CPU per simulated second [s/s],
# then the largest relative errors over the supports of the normal work rate, friction work
# rate, impact rate and peak force against the case's reference (the full model at the
# tightest tolerance), and the steps.
# Left: the periodic case (7 Hz, 0.05 mm; the errors are the model's and the integrator's).
# Right: the deck's own case (8 Hz, 0.2 mm; not periodic: the errors include the statistical
# spread of a 40-period record). Each panel: the full model at tolerances 1e-3 .. 1e-5 (line),
# the reduced model at several cut-offs (points, labelled in Hz) and the 'auto' basis at
# tolerances 1e-3 .. 1e-5 (line).
if (!exists("datafile")) datafile = 'bench_results/tubes_reduction.dat'
if (!exists("outfile")) outfile = 'bench_results/tubes_reduction.png'
if (!exists("cases")) cases = 'deck'
set terminal pngcairo size (700 * words(cases) + 200),700 enhanced font 'Sans,10'
set output outfile
set multiplot layout 1,words(cases) title 'Tube in two baffles: normal work rate error against CPU, full and reduced models'
set logscale xy
set format y '10^{%L}'
set xlabel 'CPU per simulated second [s/s]'
set ylabel 'largest relative error of the normal work rate over the baffles'
# (below the panels: inside, top right hid the points near 1e-3 of the periodic case and
# bottom left the tightest tolerances')
set key below nobox samplen 2 width -4
set grid
sel(c, k) = (strcol(1) eq c && strcol(2) eq k)
pos(x) = (x > 0 ? x : 1e-7)
do for [c in cases] {
   set title (c eq 'periodic' ? \
      'periodic case: 7 Hz, 0.05 mm (reference: full model at tolerance 1e-6)' : \
      'the deck: 8 Hz, 0.2 mm, not periodic (reference: full model at 1e-6, the same record)')
   plot datafile u (sel(c, 'full') ? $7 : NaN):(pos($8)) w lp pt 7 lw 2 t 'full, Newmark, tol. 1e-3..1e-5', \
        datafile u (sel(c, 'auto') ? $7 : NaN):(pos($8)) w lp pt 5 lw 2 t "'auto' basis, Newmark, tol. 1e-3..1e-5", \
        datafile u (sel(c, 'auto_rk45') ? $7 : NaN):(pos($8)) w lp pt 13 lw 2 t "'auto' basis, rk45, tol. 1e-3..1e-5", \
        datafile u (sel(c, 'auto_exp') ? $7 : NaN):(pos($8)) w lp pt 11 lw 2 t "'auto' basis, exponential (the default), tol. 1e-3..1e-6", \
        datafile u (sel(c, 'full_exp') ? $7 : NaN):(pos($8)) w p pt 15 ps 1.8 t 'full, exponential, tol. 1e-4', \
        datafile u (sel(c, 'modal') ? $7 : NaN):(pos($8)) w p pt 9 ps 1.5 t 'cut-off [Hz] (label), Newmark', \
        datafile u (sel(c, 'modal_exp') ? $7 : NaN):(pos($8)) w p pt 8 ps 1.5 t 'cut-off [Hz], exponential', \
        datafile u (sel(c, 'modal_exp') ? $7 : NaN):(pos($8)):(sprintf('%g', $4)) w labels offset 2.5,-0.5 notitle, \
        datafile u (sel(c, 'modal') ? $7 : NaN):(pos($8)):(sprintf('%g', $4)) w labels offset 2.5,0.5 notitle, \
        datafile u (sel(c, 'full') || sel(c, 'auto') || sel(c, 'auto_rk45') || sel(c, 'auto_exp') ? $7 : NaN):(pos($8)):(sprintf('%.0e', $5)) w labels offset 0,-1 tc rgb 'gray40' notitle
}
unset multiplot
