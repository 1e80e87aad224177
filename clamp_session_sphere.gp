set terminal pngcairo size 1000,560 font ',11'
set output './clamp_session_sphere.png'
set datafile separator ','
set grid
set key top right
set xlabel 'time (s)'
set ylabel 'force (N)'
set y2label 'body centre height (m)'
set ytics nomirror
set y2tics
set title 'Clamp under the hand (sphere): close, lift, hold, open; the hand feels the load the jaws carry'
plot './clamp_session_sphere.csv' using 1:(-$8) every ::1 with lines lw 2 title 'load the jaws carry, down (N)', '' using 1:(-$11*20.000000) every ::1 with lines lw 1 title 'device force x workspace scale, down (N)', '' using 1:6 every ::1 axes x1y2 with lines lw 1 title 'body centre height (m)'
