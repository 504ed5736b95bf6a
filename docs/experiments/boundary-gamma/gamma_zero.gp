# Written by `sluice figures`; the data is inline. Rerun: gnuplot gamma_zero.gp
set terminal pngcairo size 1200,800 enhanced font "DejaVu Sans,20" linewidth 2
set output "gamma_zero.png"
set grid lc rgb "#dddddd"
set key top left box opaque
set xlabel "γ1" noenhanced
set ylabel "γ3" noenhanced
set palette defined (0 "#fde725", 0.5 "#21918c", 1 "#440154")
set cblabel "average solver iterations per step" noenhanced
$s0 << EOD
0.84 1 20.88
0.9 0.86 20.84
0.8 1.02 20.76
1 1.18 20.79
0.75 1.34 20.85
0.95 0.732 19.43
0.85 0.892 20.84
EOD
$highlight << EOD
0.95 0.732
EOD
plot $s0 using 1:2:3 with points pt 7 ps 1.6 lc palette title "pressure zero" noenhanced, \
     $highlight using 1:2 with points pt 6 ps 3.2 lw 3 lc rgb "#e31a1c" title "best" noenhanced
