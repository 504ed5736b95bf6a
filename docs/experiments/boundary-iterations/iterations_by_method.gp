# Written by `sluice figures`; the data is inline. Rerun: gnuplot iterations_by_method.gp
set terminal pngcairo size 1200,800 enhanced font "DejaVu Sans,20" linewidth 2
set output "iterations_by_method.png"
set grid lc rgb "#dddddd"
set key top left box opaque
set ylabel "pressure solver iterations" noenhanced
$box << EOD
1 8 3 33 18 12 13.72254902
2 8 3 30 17 12 13.19181287
3 9 3 31 18 13 14.53137255
EOD
$outliers << EOD
1 38
1 82
1 37
1 37
1 44
1 44
1 39
1 34
1 34
1 35
1 34
1 34
1 36
1 34
1 35
1 45
1 34
1 38
1 38
1 34
2 35
2 38
2 33
2 31
2 33
2 32
2 31
2 32
2 33
2 31
2 33
2 32
2 31
2 38
2 36
2 36
2 32
2 35
2 35
2 43
2 43
2 42
2 36
2 36
2 33
2 31
3 100
3 58
3 100
3 34
3 34
3 35
3 32
3 33
3 34
3 32
3 34
3 34
3 34
3 34
3 33
3 32
3 32
3 32
3 33
3 32
3 32
3 32
3 32
EOD
set xtics ("extrapolation\nmean 13.7" 1, "mirroring\nmean 13.2" 2, "zero\nmean 14.5" 3) noenhanced
set xrange [0.4:3.6]
set bmargin 5
set boxwidth 0.5
set style fill solid 0.35 border -1
set key top right
plot $box using 1:2:3:4:5 with candlesticks whiskerbars 0.5 lc rgb "#1f77b4" title "quartiles, 1.5 IQR whiskers", \
     $box using 1:6:6:6:6 with candlesticks lc rgb "black" lw 2 notitle, \
     $box using 1:7 with points pt 7 ps 1.6 lc rgb "black" title "mean", \
     $outliers using 1:2 with points pt 6 ps 0.8 lc rgb "#7f7f7f" title "outliers"
