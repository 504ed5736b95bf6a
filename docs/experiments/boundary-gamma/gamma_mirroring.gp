# Written by `sluice figures`; the data is inline. Rerun: gnuplot gamma_mirroring.gp
set terminal pngcairo size 1200,800 enhanced font "DejaVu Sans,20" linewidth 2
set output "gamma_mirroring.png"
set grid lc rgb "#dddddd"
set key top left box opaque
set xlabel "γ1" noenhanced
set ylabel "γ3" noenhanced
set palette defined (0 "#fde725", 0.5 "#21918c", 1 "#440154")
set cblabel "average solver iterations per step" noenhanced
$s0 << EOD
0.84 1 20.2
0.9 0.86 20.59
0.8 1.02 20.67
1 1.18 17.05
0.75 1.34 17.72
0.95 0.732 20.26
0.85 0.892 19.64
EOD
$highlight << EOD
0.75 1.34
EOD
plot $s0 using 1:2:3 with points pt 7 ps 1.6 lc palette title "pressure mirroring" noenhanced, \
     $highlight using 1:2 with points pt 6 ps 3.2 lw 3 lc rgb "#e31a1c" title "best" noenhanced
