# Written by `sluice figures`; the data is inline. Rerun: gnuplot time_vs_particles.gp
set terminal pngcairo size 1200,800 enhanced font "DejaVu Sans,20" linewidth 2
set output "time_vs_particles.png"
set grid lc rgb "#dddddd"
set key top left box opaque
set xlabel "fluid particles" noenhanced
set ylabel "wall time per step [ms]" noenhanced
$s0 << EOD
1250 0.71152
2500 2.124
5000 6.5263
7500 13.339
10000 18.521
12000 23.521
EOD
$s1 << EOD
1250 0.75786
2500 1.5276
5000 4.5118
7500 7.984
10000 13.571
12000 16.851
EOD
plot $s0 using 1:2 with linespoints pt 7 ps 1.2 lw 2 lc rgb "#1f77b4" title "threads = 1" noenhanced, \
     $s1 using 1:2 with linespoints pt 7 ps 1.2 lw 2 lc rgb "#d62728" title "threads = 2" noenhanced
