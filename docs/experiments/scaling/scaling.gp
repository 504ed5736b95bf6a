# Written by `sluice figures`; the data is inline. Rerun: gnuplot scaling.gp
set terminal pngcairo size 1200,800 enhanced font "DejaVu Sans,20" linewidth 2
set output "scaling.png"
set grid lc rgb "#dddddd"
set key top left box opaque
set xlabel "fluid particles" noenhanced
set ylabel "wall time [µs]" noenhanced
set logscale x
$s0 << EOD
10000 0.52221
30000 0.40829
100000 0.52887
300000 0.45119
1000000 0.50367
EOD
$s1 << EOD
10000 0.55111
30000 0.40144
100000 0.5413
300000 0.46233
1000000 0.47447
EOD
$s2 << EOD
10000 0.1896
30000 0.1474
100000 0.1879
300000 0.182
1000000 0.1973
EOD
$s3 << EOD
10000 0.05271
30000 0.0374
100000 0.04838
300000 0.04512
1000000 0.04449
EOD
plot $s0 using 1:2 with linespoints pt 7 ps 1.2 lw 2 lc rgb "#1f77b4" title "wall time per particle-step [µs]" noenhanced, \
     $s1 using 1:2 with linespoints pt 7 ps 1.2 lw 2 lc rgb "#d62728" title "us_per_particle_step_fixed_iterations" noenhanced, \
     $s2 using 1:2 with linespoints pt 7 ps 1.2 lw 2 lc rgb "#2ca02c" title "neighbour search per particle-step [µs]" noenhanced, \
     $s3 using 1:2 with linespoints pt 7 ps 1.2 lw 2 lc rgb "#ff7f0e" title "pressure solve per particle and iteration [µs]" noenhanced
