# Written by `sluice figures`; the data is inline. Rerun: gnuplot iterations_vs_height.gp
set terminal pngcairo size 1200,800 enhanced font "DejaVu Sans,20" linewidth 2
set output "iterations_vs_height.png"
set grid lc rgb "#dddddd"
set key top left box opaque
set xlabel "column height [m]" noenhanced
set ylabel "average solver iterations per step" noenhanced
$s0 << EOD
0.25 6.424
0.5 11.95
1 23.53
1.5 34.88
2 45.97
EOD
plot $s0 using 1:2 with linespoints pt 7 ps 1.2 lw 2 lc rgb "#1f77b4" title "column-height" noenhanced
