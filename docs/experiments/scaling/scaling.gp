# Written by `sluice figures`; the data is inline. Rerun: gnuplot scaling.gp
set terminal pngcairo size 1200,800 enhanced font "DejaVu Sans,20" linewidth 2
set output "scaling.png"
set grid lc rgb "#dddddd"
set key top left box opaque
set xlabel "fluid particles" noenhanced
set ylabel "wall time [µs]" noenhanced
set logscale x
$s0 << EOD
10000 0.34028
30000 0.37284
100000 0.53242
300000 0.52769
1000000 0.56649
EOD
$s1 << EOD
10000 0.36476
30000 0.38108
100000 0.43186
300000 0.53717
1000000 0.56613
EOD
$s2 << EOD
10000 0.1568
30000 0.1529
100000 0.1853
300000 0.191
1000000 0.2097
EOD
$s3 << EOD
10000 0.03355
30000 0.04459
100000 0.03969
300000 0.05571
1000000 0.05903
EOD
plot $s0 using 1:2 with linespoints pt 7 ps 1.2 lw 2 lc rgb "#1f77b4" title "wall time per particle-step [µs]" noenhanced, \
     $s1 using 1:2 with linespoints pt 7 ps 1.2 lw 2 lc rgb "#d62728" title "us_per_particle_step_fixed_iterations" noenhanced, \
     $s2 using 1:2 with linespoints pt 7 ps 1.2 lw 2 lc rgb "#2ca02c" title "neighbour search per particle-step [µs]" noenhanced, \
     $s3 using 1:2 with linespoints pt 7 ps 1.2 lw 2 lc rgb "#ff7f0e" title "pressure solve per particle and iteration [µs]" noenhanced
