# Written by `sluice figures`; the data is inline. Rerun: gnuplot iterations_vs_particles.gp
set terminal pngcairo size 1200,800 enhanced font "DejaVu Sans,20" linewidth 2
set output "iterations_vs_particles.png"
set grid lc rgb "#dddddd"
set key top left box opaque
set xlabel "fluid particles" noenhanced
set ylabel "average solver iterations per step" noenhanced
$s0 << EOD
1250 6.637
2500 12.03
5000 20.83
7500 27.11
10000 33.81
12000 36.55
EOD
$s1 << EOD
1250 6.637
2500 12.03
5000 20.83
7500 27.11
10000 33.81
12000 36.55
EOD
plot $s0 using 1:2 with linespoints pt 7 ps 1.2 lw 2 lc rgb "#1f77b4" title "threads = 1" noenhanced, \
     $s1 using 1:2 with linespoints pt 7 ps 1.2 lw 2 lc rgb "#d62728" title "threads = 2" noenhanced
