# SPDX-License-Identifier: GPL-3.0-or-later
# Error against cost of every scheme setting (sw_bench run --data DIR), one
# panel per model (up to four), with the Pareto front.  Called by scripts/run-bench.sh:
#   gnuplot -e "dir='bench/results'; out='docs/img/pareto.png'; models='bare frame'" bench/pareto.gp
set terminal pngcairo size 1300,1080 font ",10"
set output out
set multiplot layout 2,2
set logscale xy
set format y "10^{%L}"
set xlabel "CPU ns per input sample while rocking (1 kHz samples; median of 5)"
set ylabel "worst error of max|theta| (rad) vs rk8pd rtol 1e-12"
set grid
set key outside right top box opaque
set yrange [1e-16:2]
schemes = "euler heun rk4 rkf45 rkck rk8pd rk4imp bsimp msbdf"
do for [m in models] {
    set title sprintf("model %s (error 1 = wrong overturn decision)", m)
    f = sprintf("%s/pareto-%s.dat", dir, m)
    g = sprintf("%s/front-%s.dat", dir, m)
    plot for [i=1:words(schemes)] f using (strcol(1) eq word(schemes, i) ? $4 : 1/0):5 \
             with points pt (i+5) ps 1.4 title word(schemes, i), \
         g using 1:2 with steps lw 1.5 lc rgb "black" title "Pareto front"
}
unset multiplot
