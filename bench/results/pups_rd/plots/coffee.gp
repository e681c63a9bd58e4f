set datafile missing '?'
set logscale x 2
set grid
set style line 100 lc rgb 'black' dt 2 lw 2 pt 6
set style line 101 lc rgb '#777777' dt 4 lw 2 pt 8
set terminal svg size 1000,560 dynamic noenhanced font 'sans,12' background rgb 'white'
set output 'coffee.svg'
set title 'PSNR against bits per pixel: coffee'
set xlabel 'bits per pixel'
set ylabel 'PSNR (dB, all channels)'
set key outside right top
plot \
  'coffee.dat' index 0 using 1:2 with linespoints lw 1.5 pt 1 title 'cdf97', \
  'coffee.dat' index 1 using 1:2 with linespoints lw 1.5 pt 2 title 'cdf53', \
  'coffee.dat' index 2 using 1:2 with linespoints lw 1.5 pt 3 title 'pups:chaikin', \
  'coffee.dat' index 3 using 1:2 with linespoints lw 1.5 pt 4 title 'pups:cubic-bspline', \
  'coffee.dat' index 4 using 1:2 with linespoints lw 1.5 pt 5 title 'pups:cinpact-c3', \
  'coffee.dat' index 5 using 1:2 with linespoints lw 1.5 pt 6 title 'pups:cinpact-c3-ext', \
  'coffee.dat' index 6 using 1:2 with linespoints lw 1.5 pt 7 title 'pups:cinpact-interp-c5', \
  'coffee.dat' index 7 using 1:2 with linespoints lw 1.5 pt 8 title 'pups:cinpact-interp-c5-ext', \
  'coffee.dat' index 8 using 1:2 with linespoints lw 1.5 pt 9 title 'pups:poly10', \
  'coffee.dat' index 9 using 1:2 with linespoints lw 1.5 pt 10 title 'pups:chaikin-ext', \
  'coffee.dat' index 10 using 1:2 with linespoints lw 1.5 pt 11 title 'pups:cinpact-interp-vm4', \
  'coffee.dat' index 11 using 1:2 with linespoints lw 1.5 pt 12 title 'pups:poly16-vm4-cg', \
  'coffee.dat' index 12 using 1:2 with linespoints ls 100 title 'openjpeg'
set terminal svg size 1000,560 dynamic noenhanced font 'sans,12' background rgb 'white'
set output 'coffee-vs-openjpeg.svg'
set title 'PSNR minus the PSNR of OpenJPEG at the same rate: coffee'
set xlabel 'bits per pixel'
set ylabel 'PSNR difference (dB)'
set key outside right top
plot \
  'coffee.dat' index 0 using 1:3 with linespoints lw 1.5 pt 1 title 'cdf97', \
  'coffee.dat' index 1 using 1:3 with linespoints lw 1.5 pt 2 title 'cdf53', \
  'coffee.dat' index 2 using 1:3 with linespoints lw 1.5 pt 3 title 'pups:chaikin', \
  'coffee.dat' index 3 using 1:3 with linespoints lw 1.5 pt 4 title 'pups:cubic-bspline', \
  'coffee.dat' index 4 using 1:3 with linespoints lw 1.5 pt 5 title 'pups:cinpact-c3', \
  'coffee.dat' index 5 using 1:3 with linespoints lw 1.5 pt 6 title 'pups:cinpact-c3-ext', \
  'coffee.dat' index 6 using 1:3 with linespoints lw 1.5 pt 7 title 'pups:cinpact-interp-c5', \
  'coffee.dat' index 7 using 1:3 with linespoints lw 1.5 pt 8 title 'pups:cinpact-interp-c5-ext', \
  'coffee.dat' index 8 using 1:3 with linespoints lw 1.5 pt 9 title 'pups:poly10', \
  'coffee.dat' index 9 using 1:3 with linespoints lw 1.5 pt 10 title 'pups:chaikin-ext', \
  'coffee.dat' index 10 using 1:3 with linespoints lw 1.5 pt 11 title 'pups:cinpact-interp-vm4', \
  'coffee.dat' index 11 using 1:3 with linespoints lw 1.5 pt 12 title 'pups:poly16-vm4-cg', \
  'coffee.dat' index 12 using 1:3 with linespoints ls 100 title 'openjpeg'
