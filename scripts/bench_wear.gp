# scripts/bench_wear.gp - wear-output error against CPU per simulated second (bench_wear.sh).
# gnuplot -e "datafile='bench_results/wear_error.dat'; outfile='bench_results/wear_error.png'"
#         scripts/bench_wear.gp
# Columns of the data: deck method tolerance stop cpu_s cpu_per_sim_s steps impacts ref_impacts
# err_WN err_Wf err_s WN Wf s. One curve per deck, method and support; points labelled by
# the tolerance; open points where the run's impacts differ from the reference's.
if (!exists("datafile")) datafile = 'bench_results/wear_error.dat'
if (!exists("outfile")) outfile = 'bench_results/wear_error.png'
set terminal pngcairo size 1400,560 font ',10'
set output outfile
keys = system("awk '!/^#/{print $1\":\"$2\":\"$4}' " . datafile . " | sort -u | tr '\\n' ' '")
set logscale xy
set format y '10^{%L}'
set grid
set xlabel 'CPU per simulated second [s] (release, serial)'
set key top right font ',9'
set multiplot layout 1,2 title 'Wear outputs: relative error against the converged run'
do for [col in "10 12"] {
   name = (col eq "10") ? 'normal work rate W_N (friction work rate: the same, W_f = mu W_N)' \
                        : 'sliding distance'
   set title name
   set ylabel 'relative error'
   plot for [k in keys] datafile using \
           ((strcol(1).':'.strcol(2).':'.strcol(4)) eq k ? $6 : 1/0):(column(int(col)) > 0 ? column(int(col)) : 1/0) \
           with linespoints pt 7 title k noenhanced, \
        for [k in keys] datafile using \
           ((strcol(1).':'.strcol(2).':'.strcol(4)) eq k ? $6 : 1/0):(column(int(col)) > 0 ? column(int(col)) : 1/0):3 \
           with labels offset 1.5,0.6 font ',8' notitle
}
unset multiplot
