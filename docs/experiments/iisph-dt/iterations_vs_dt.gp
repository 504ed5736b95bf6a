# Written by `sluice figures`; the data is inline. Rerun: gnuplot iterations_vs_dt.gp
set terminal pngcairo size 1200,800 enhanced font "DejaVu Sans,20" linewidth 2
set output "iterations_vs_dt.png"
set grid lc rgb "#dddddd"
set key top left box opaque
set xlabel "time step [s]" noenhanced
set ylabel "average solver iterations per step" noenhanced
$s0 << EOD
0.00025 3.003
0.0005 6.734
0.00075 13.97
0.001 23.82
0.0015 50.98
0.002 91.34
EOD
plot $s0 using 1:2 with linespoints pt 7 ps 1.2 lw 2 lc rgb "#1f77b4" title "iisph-dt" noenhanced
