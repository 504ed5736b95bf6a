# Written by `sluice figures`; the data is inline. Rerun: gnuplot column_1m.gp
set terminal pngcairo size 1200,800 enhanced font "DejaVu Sans,20" linewidth 2
set output "column_1m.png"
set grid lc rgb "#dddddd"
set key top left box opaque
set xlabel "wall time per simulated second [s]" noenhanced
set ylabel "average density error [%]" noenhanced
set logscale x
set logscale y
$s0 << EOD
18.1328 0.014233
4.11121 0.093944
2.90886 0.253558
15.3305 0.028639
4.1131 0.106825
1.32825 0.737202
7.48227 0.106952
6.63966 0.127751
1.48779 1.182595
EOD
$s1 << EOD
21.42 4.344115
9.83767 4.342948
4.38035 4.344455
21.5388 0.499262
10.3134 0.500251
5.4562 0.499469
22.724 0.060718
11.2123 0.07008
EOD
$pareto << EOD
1.32825 0.737202
2.90886 0.253558
4.11121 0.093944
11.2123 0.07008
15.3305 0.028639
18.1328 0.014233
EOD
plot $s0 using 1:2 with points pt 7 ps 1.6 lc rgb "#1f77b4" title "iisph" noenhanced, \
     $s1 using 1:2 with points pt 5 ps 1.6 lc rgb "#d62728" title "wcsph" noenhanced, \
     $pareto using 1:2 with linespoints dt 2 lw 2 pt 6 ps 2.4 lc rgb "black" title "Pareto front"
