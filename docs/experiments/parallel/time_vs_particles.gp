# Written by `sluice figures`; the data is inline. Rerun: gnuplot time_vs_particles.gp
set terminal pngcairo size 1200,800 enhanced font "DejaVu Sans,20" linewidth 2
set output "time_vs_particles.png"
set grid lc rgb "#dddddd"
set key top left box opaque
set xlabel "fluid particles" noenhanced
set ylabel "wall time per step [ms]" noenhanced
$s0 << EOD
1250 0.9842
2500 2.7621
5000 6.3513
7500 15.581
10000 17.662
12000 30.334
EOD
$s1 << EOD
1250 0.98078
2500 1.5937
5000 4.1306
7500 12.245
10000 14.161
12000 16.657
EOD
plot $s0 using 1:2 with linespoints pt 7 ps 1.2 lw 2 lc rgb "#1f77b4" title "threads = 1" noenhanced, \
     $s1 using 1:2 with linespoints pt 7 ps 1.2 lw 2 lc rgb "#d62728" title "threads = 2" noenhanced
