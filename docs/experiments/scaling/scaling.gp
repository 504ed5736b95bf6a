# Written by `sluice figures`; the data is inline. Rerun: gnuplot scaling.gp
set terminal pngcairo size 1200,800 enhanced font "DejaVu Sans,20" linewidth 2
set output "scaling.png"
set grid lc rgb "#dddddd"
set key top left box opaque
set xlabel "fluid particles" noenhanced
set ylabel "wall time [µs]" noenhanced
set logscale x
$s0 << EOD
10000 0.2989
30000 0.34807
100000 0.55122
300000 0.60565
1000000 0.6275
EOD
$s1 << EOD
10000 0.1382
30000 0.1494
100000 0.1998
300000 0.2586
1000000 0.2413
EOD
$s2 << EOD
10000 0.03059
30000 0.03266
100000 0.05147
300000 0.06322
1000000 0.06016
EOD
plot $s0 using 1:2 with linespoints pt 7 ps 1.2 lw 2 lc rgb "#1f77b4" title "wall time per particle-step [µs]" noenhanced, \
     $s1 using 1:2 with linespoints pt 7 ps 1.2 lw 2 lc rgb "#d62728" title "neighbour search per particle-step [µs]" noenhanced, \
     $s2 using 1:2 with linespoints pt 7 ps 1.2 lw 2 lc rgb "#2ca02c" title "pressure solve per particle and iteration [µs]" noenhanced
