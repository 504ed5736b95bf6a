# Written by `sluice figures`; the data is inline. Rerun: gnuplot column_2m.gp
set terminal pngcairo size 1200,800 enhanced font "DejaVu Sans,20" linewidth 2
set output "column_2m.png"
set grid lc rgb "#dddddd"
set key top left box opaque
set xlabel "wall time per simulated second [s]" noenhanced
set ylabel "average density error [%]" noenhanced
set logscale x
set logscale y
$s0 << EOD
71.3504 0.017177
17.5917 0.099304
6.78634 0.499688
29.1598 0.054367
16.8263 0.11133
3.63562 0.920762
EOD
$s1 << EOD
46.9844 12.130078
27.2124 12.130958
14.7412 12.131424
52.5312 1.079399
25.0198 1.075139
13.6083 1.082578
51.1756 0.178819
EOD
$pareto << EOD
3.63562 0.920762
6.78634 0.499688
16.8263 0.11133
17.5917 0.099304
29.1598 0.054367
71.3504 0.017177
EOD
plot $s0 using 1:2 with points pt 7 ps 1.6 lc rgb "#1f77b4" title "iisph" noenhanced, \
     $s1 using 1:2 with points pt 5 ps 1.6 lc rgb "#d62728" title "wcsph" noenhanced, \
     $pareto using 1:2 with linespoints dt 2 lw 2 pt 6 ps 2.4 lc rgb "black" title "Pareto front"
