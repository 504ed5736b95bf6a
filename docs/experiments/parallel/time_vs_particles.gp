# Written by `sluice figures`; the data is inline. Rerun: gnuplot time_vs_particles.gp
set terminal pngcairo size 1200,800 enhanced font "DejaVu Sans,20" linewidth 2
set output "time_vs_particles.png"
set grid lc rgb "#dddddd"
set key top left box opaque
set xlabel "fluid particles" noenhanced
set ylabel "wall time per step [ms]" noenhanced
$s0 << EOD
1250 0.92466
2500 2.3288
5000 5.1874
7500 15.122
10000 18.678
12000 28.683
EOD
$s1 << EOD
1250 0.95721
2500 1.8809
5000 4.9163
7500 9.0417
10000 13.841
12000 20.005
EOD
plot $s0 using 1:2 with linespoints pt 7 ps 1.2 lw 2 lc rgb "#1f77b4" title "threads = 1" noenhanced, \
     $s1 using 1:2 with linespoints pt 7 ps 1.2 lw 2 lc rgb "#d62728" title "threads = 2" noenhanced
