# Written by `sluice figures`; the data is inline. Rerun: gnuplot scaling.gp
set terminal pngcairo size 1200,800 enhanced font "DejaVu Sans,20" linewidth 2
set output "scaling.png"
set grid lc rgb "#dddddd"
set key top left box opaque
set xlabel "fluid particles" noenhanced
set ylabel "wall time [µs]" noenhanced
set logscale x
set offsets 0, 0, graph 0.3513513514, 0
$s0 << EOD
10000 0.36787
30000 0.46597
100000 0.47983
300000 0.48314
1000000 0.50323
EOD
$s1 << EOD
10000 0.4171
30000 0.49292
100000 0.49257
300000 0.44456
1000000 0.48758
EOD
$s2 << EOD
10000 0.1723
30000 0.189
100000 0.1865
300000 0.161
1000000 0.1969
EOD
$s3 << EOD
10000 0.04158
30000 0.05635
100000 0.04876
300000 0.03896
1000000 0.04714
EOD
plot $s0 using 1:2 with linespoints pt 7 ps 1.2 lw 2 lc rgb "#1f77b4" title "wall time per particle-step [µs]" noenhanced, \
     $s1 using 1:2 with linespoints pt 7 ps 1.2 lw 2 lc rgb "#d62728" title "wall time per particle-step, fixed iterations [µs]" noenhanced, \
     $s2 using 1:2 with linespoints pt 7 ps 1.2 lw 2 lc rgb "#2ca02c" title "neighbour search per particle-step [µs]" noenhanced, \
     $s3 using 1:2 with linespoints pt 7 ps 1.2 lw 2 lc rgb "#ff7f0e" title "pressure solve per particle and iteration [µs]" noenhanced
