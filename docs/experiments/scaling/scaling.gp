# Written by `sluice figures`; the data is inline. Rerun: gnuplot scaling.gp
set terminal pngcairo size 1200,800 enhanced font "DejaVu Sans,20" linewidth 2
set output "scaling.png"
set grid lc rgb "#dddddd"
set key top left box opaque
set xlabel "fluid particles" noenhanced
set ylabel "wall time [µs]" noenhanced
set logscale x
$s0 << EOD
10000 0.55028
30000 0.58882
100000 0.63111
300000 0.52201
1000000 0.54298
EOD
$s1 << EOD
10000 0.592
30000 0.58002
100000 0.59662
300000 0.50571
1000000 0.50614
EOD
$s2 << EOD
10000 0.2101
30000 0.1839
100000 0.1926
300000 0.1992
1000000 0.2086
EOD
$s3 << EOD
10000 0.06247
30000 0.05965
100000 0.05546
300000 0.04838
1000000 0.05004
EOD
plot $s0 using 1:2 with linespoints pt 7 ps 1.2 lw 2 lc rgb "#1f77b4" title "wall time per particle-step [µs]" noenhanced, \
     $s1 using 1:2 with linespoints pt 7 ps 1.2 lw 2 lc rgb "#d62728" title "us_per_particle_step_fixed_iterations" noenhanced, \
     $s2 using 1:2 with linespoints pt 7 ps 1.2 lw 2 lc rgb "#2ca02c" title "neighbour search per particle-step [µs]" noenhanced, \
     $s3 using 1:2 with linespoints pt 7 ps 1.2 lw 2 lc rgb "#ff7f0e" title "pressure solve per particle and iteration [µs]" noenhanced
