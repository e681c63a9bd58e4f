set datafile missing '?'
set logscale x 2
set grid
set style line 100 lc rgb 'black' dt 2 lw 2 pt 6
set style line 101 lc rgb '#777777' dt 4 lw 2 pt 8
set terminal svg size 760,520 dynamic noenhanced font 'sans,12' background rgb 'white'
set output 'astronaut.svg'
set title 'PSNR against bits per pixel: astronaut'
set xlabel 'bits per pixel'
set ylabel 'PSNR (dB, all channels)'
set key bottom right
plot \
  'astronaut.dat' index 0 using 1:2 with linespoints lw 1.5 pt 1 title 'cdf97', \
  'astronaut.dat' index 1 using 1:2 with linespoints lw 1.5 pt 2 title 'cdf97+ebcot', \
  'astronaut.dat' index 2 using 1:2 with linespoints ls 100 title 'openjpeg', \
  'astronaut.dat' index 3 using 1:2 with linespoints lw 1.5 pt 4 title 'avif'
set terminal svg size 760,520 dynamic noenhanced font 'sans,12' background rgb 'white'
set output 'astronaut-vs-openjpeg.svg'
set title 'PSNR minus the PSNR of OpenJPEG at the same rate: astronaut'
set xlabel 'bits per pixel'
set ylabel 'PSNR difference (dB)'
set key bottom right
plot \
  'astronaut.dat' index 0 using 1:3 with linespoints lw 1.5 pt 1 title 'cdf97', \
  'astronaut.dat' index 1 using 1:3 with linespoints lw 1.5 pt 2 title 'cdf97+ebcot', \
  'astronaut.dat' index 2 using 1:3 with linespoints ls 100 title 'openjpeg', \
  'astronaut.dat' index 3 using 1:3 with linespoints lw 1.5 pt 4 title 'avif'
