# Written by `sluice figures`; the data is inline. Rerun: gnuplot time_vs_particles.gp
set terminal pngcairo size 1200,800 enhanced font "DejaVu Sans,20" linewidth 2
set output "time_vs_particles.png"
set grid lc rgb "#dddddd"
set key top left box opaque
set xlabel "fluid particles" noenhanced
set ylabel "wall time per step [ms]" noenhanced
$s0 << EOD
1250 0.97688
2500 2.0484
5000 8.617
7500 15.266
10000 24.683
12000 24.147
EOD
$s1 << EOD
1250 0.99899
2500 1.3476
5000 5.0408
7500 8.7598
10000 13.304
12000 21.93
EOD
plot $s0 using 1:2 with linespoints pt 7 ps 1.2 lw 2 lc rgb "#1f77b4" title "threads = 1" noenhanced, \
     $s1 using 1:2 with linespoints pt 7 ps 1.2 lw 2 lc rgb "#d62728" title "threads = 2" noenhanced
