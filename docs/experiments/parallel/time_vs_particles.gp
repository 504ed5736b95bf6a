# Written by `sluice figures`; the data is inline. Rerun: gnuplot time_vs_particles.gp
set terminal pngcairo size 1200,800 enhanced font "DejaVu Sans,20" linewidth 2
set output "time_vs_particles.png"
set grid lc rgb "#dddddd"
set key top left box opaque
set xlabel "fluid particles" noenhanced
set ylabel "wall time per step [ms]" noenhanced
$s0 << EOD
1250 0.62095
2500 1.6331
5000 5.3772
7500 13.567
10000 15.472
12000 19.236
EOD
$s1 << EOD
1250 0.65544
2500 1.3408
5000 5.448
7500 7.7799
10000 12.099
12000 14.346
EOD
plot $s0 using 1:2 with linespoints pt 7 ps 1.2 lw 2 lc rgb "#1f77b4" title "threads = 1" noenhanced, \
     $s1 using 1:2 with linespoints pt 7 ps 1.2 lw 2 lc rgb "#d62728" title "threads = 2" noenhanced
