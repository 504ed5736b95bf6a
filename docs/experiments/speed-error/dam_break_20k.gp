# Written by `sluice figures`; the data is inline. Rerun: gnuplot dam_break_20k.gp
set terminal pngcairo size 1200,800 enhanced font "DejaVu Sans,20" linewidth 2
set output "dam_break_20k.png"
set grid lc rgb "#dddddd"
set key top left box opaque
set xlabel "wall time per simulated second [s]" noenhanced
set ylabel "average density error [%]" noenhanced
set logscale x
set logscale y
$s0 << EOD
75.3183 0.013186
22.9289 0.093109
16.2995 0.230929
77.6222 0.029454
22.9452 0.104898
8.52146 0.725256
45.4366 0.108746
26.6949 0.134725
7.03453 1.02831
EOD
$s1 << EOD
108.715 4.614358
47.6756 4.614498
22.5631 4.614945
94.8848 0.455705
53.3681 0.455862
24.8659 0.456166
90.1028 0.047404
41.9874 0.047932
EOD
$pareto << EOD
7.03453 1.02831
8.52146 0.725256
16.2995 0.230929
22.9289 0.093109
41.9874 0.047932
75.3183 0.013186
EOD
plot $s0 using 1:2 with points pt 7 ps 1.6 lc rgb "#1f77b4" title "iisph" noenhanced, \
     $s1 using 1:2 with points pt 5 ps 1.6 lc rgb "#d62728" title "wcsph" noenhanced, \
     $pareto using 1:2 with linespoints dt 2 lw 2 pt 6 ps 2.4 lc rgb "black" title "Pareto front"
