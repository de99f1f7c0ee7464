# The analogue of the paper's Fig. 7 on the shipped sample: joint 1 while the
# tip is held in a divot and pushed along +joint 1 and then along -joint 1.
# Regenerate (after ./scripts/demo.sh):  gnuplot docs/figures/divot_push.gp
set datafile separator ','
set terminal pngcairo size 900,420 font 'sans,10'
set output 'docs/figures/divot_push_joint1.png'
set key top left box opaque
set xlabel 't (s)'
set ylabel 'joint 1 (mrad)'
set grid
set xrange [3:24]
plot 'out/divot_push_paper.csv'    using 't':(1000*column('q1'))      with lines lw 1.5 lc rgb '#999999' title 'encoder (uncorrected)', \
     ''                            using 't':(1000*column('q1_corr')) with lines lw 2 lc rgb '#d62728' title 'equation (2), paper', \
     'out/divot_push_deadzone.csv' using 't':(1000*column('q1_corr')) with lines lw 2 lc rgb '#1f77b4' title 'dead-zone', \
     ''                            using 't':(1000*column('q1_true')) with lines lw 1.5 dt 2 lc rgb 'black' title 'truth (tip held)'
