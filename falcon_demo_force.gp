set terminal pngcairo size 1000,560 font 'Sans,11'
set output './falcon_demo_force.png'
set datafile separator ','
set key top right
set grid
set xlabel 'time (s)'
set ylabel 'device force (N)'
set y2label 'tissue force on the spatula (N)'
set ytics nomirror
set y2tics
set title 'Falcon demo: the hand feels the coupling, the tissue pushes with Hunt-Crossley'
plot './falcon_demo_force.csv' using 1:11 every ::1 with lines lw 2 title '|device force| (clamped at 8 N)', \
     '' using 1:15 every ::1 axes x1y2 with lines lw 2 title '|tissue force on the tool|'
