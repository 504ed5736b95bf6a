# Written by `sluice figures`; the data is inline. Rerun: gnuplot error_vs_iterations.gp
set terminal pngcairo size 1200,800 enhanced font "DejaVu Sans,20" linewidth 2
set output "error_vs_iterations.png"
set grid lc rgb "#dddddd"
set key top left box opaque
set xlabel "solver iterations per step (fixed)" noenhanced
set ylabel "average compression error [%]" noenhanced
set logscale y
$s0 << EOD
2 1.605
3 1.005
4 0.6839
6 0.4501
8 0.3224
12 0.2125
16 0.159
24 0.1058
32 0.07965
EOD
$s1 << EOD
2 1.594
3 1.001
4 0.6792
6 0.4457
8 0.3187
12 0.208
16 0.1545
24 0.1006
32 0.07425
EOD
plot $s0 using 1:2 with linespoints pt 7 ps 1.2 lw 2 lc rgb "#1f77b4" title "average density error [%]" noenhanced, \
     $s1 using 1:2 with linespoints pt 7 ps 1.2 lw 2 lc rgb "#d62728" title "predicted compression error (Eq. 23) [%]" noenhanced
