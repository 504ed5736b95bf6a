# Written by `sluice figures`; the data is inline. Rerun: gnuplot times_vs_dt.gp
set terminal pngcairo size 1200,800 enhanced font "DejaVu Sans,20" linewidth 2
set output "times_vs_dt.png"
set grid lc rgb "#dddddd"
set key top left box opaque
set xlabel "time step [s]" noenhanced
set ylabel "wall time for the run [s]" noenhanced
$s0 << EOD
0.00025 9.889
0.0005 10.04
0.00075 14.35
0.001 18.34
0.0015 24.26
0.002 26.07
EOD
$s1 << EOD
0.00025 13.24
0.0005 6.875
0.00075 4.978
0.001 3.652
0.0015 2.391
0.002 1.533
EOD
$s2 << EOD
0.00025 23.77
0.0005 17.32
0.00075 19.67
0.001 22.25
0.0015 26.82
0.002 27.7
EOD
plot $s0 using 1:2 with linespoints pt 7 ps 1.2 lw 2 lc rgb "#1f77b4" title "pressure solve [s]" noenhanced, \
     $s1 using 1:2 with linespoints pt 7 ps 1.2 lw 2 lc rgb "#d62728" title "neighbour search [s]" noenhanced, \
     $s2 using 1:2 with linespoints pt 7 ps 1.2 lw 2 lc rgb "#2ca02c" title "overall [s]" noenhanced
