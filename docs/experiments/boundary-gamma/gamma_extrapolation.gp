# Written by `sluice figures`; the data is inline. Rerun: gnuplot gamma_extrapolation.gp
set terminal pngcairo size 1200,800 enhanced font "DejaVu Sans,20" linewidth 2
set output "gamma_extrapolation.png"
set grid lc rgb "#dddddd"
set key top left box opaque
set xlabel "γ1" noenhanced
set ylabel "γ3" noenhanced
set palette defined (0 "#fde725", 0.5 "#21918c", 1 "#440154")
set cblabel "average solver iterations per step" noenhanced
$s0 << EOD
0.84 1 20.8
0.9 0.86 20.92
0.8 1.02 20.9
1 1.18 18.94
0.75 1.34 19.87
0.95 0.732 20.15
0.85 0.892 20.68
EOD
$highlight << EOD
1 1.18
EOD
plot $s0 using 1:2:3 with points pt 7 ps 1.6 lc palette title "pressure extrapolation" noenhanced, \
     $highlight using 1:2 with points pt 6 ps 3.2 lw 3 lc rgb "#e31a1c" title "best" noenhanced
