# Written by `sluice figures`; the data is inline. Rerun: gnuplot neighbour_search.gp
set terminal pngcairo size 1200,800 enhanced font "DejaVu Sans,20" linewidth 2
set output "neighbour_search.png"
set grid lc rgb "#dddddd"
set key top left box opaque
set xlabel "fluid particles" noenhanced
set ylabel "neighbour search [ms per step]" noenhanced
$s0 << EOD
500 1.0806
1000 3.7854
2000 11.374
4000 20.4
8000 83.423
12000 181.38
EOD
$s1 << EOD
500 0.15229
1000 0.29455
2000 0.601
4000 0.56676
8000 1.4164
12000 2.0112
EOD
plot $s0 using 1:2 with linespoints pt 7 ps 1.2 lw 2 lc rgb "#1f77b4" title "naive" noenhanced, \
     $s1 using 1:2 with linespoints pt 7 ps 1.2 lw 2 lc rgb "#d62728" title "hashing" noenhanced
