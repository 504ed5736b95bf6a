# Written by `sluice figures`; the data is inline. Rerun: gnuplot iterations_vs_height.gp
set terminal pngcairo size 1200,800 enhanced font "DejaVu Sans,20" linewidth 2
set output "iterations_vs_height.png"
set grid lc rgb "#dddddd"
set key top left box opaque
set xlabel "column height [m]" noenhanced
set ylabel "average solver iterations per step" noenhanced
set key outside top center horizontal box opaque
$s0 << EOD
0.25 6.057
0.5 12.09
1 23.84
2 46.56
4 83.96
EOD
$s1 << EOD
0.25 6.465
0.5 8.712
1 12.34
2 20.42
4 36.76
EOD
plot $s0 using 1:2 with linespoints pt 7 ps 1.2 lw 2 lc rgb "#1f77b4" title "jacobi" noenhanced, \
     $s1 using 1:2 with linespoints pt 7 ps 1.2 lw 2 lc rgb "#d62728" title "chebyshev" noenhanced
