#include "tools/bench/plots.h"

#include <cmath>
#include <sstream>

#include "tools/bench/process.h"
#include "tools/bench/rd_report.h"

namespace pupwave::bench {
namespace {

namespace fs = std::filesystem;

// Points of every codec for one image; gnuplot reads block k with `index k`.
std::string data_blocks(const std::vector<RdRecord>& records, const std::string& image,
                        const std::vector<std::string>& codecs) {
  std::ostringstream d;
  d.precision(8);
  for (const std::string& codec : codecs) {
    d << "# " << codec << "\n";
    for (const RdRecord& r : records)
      if (r.image == image && r.codec == codec && r.ok && std::isfinite(r.psnr)) d << r.bpp << ' ' << r.psnr << '\n';
    d << "\n\n";
  }
  return d.str();
}

// Anchors are drawn dashed and black/grey so our transforms stand out against them.
std::string plot_script(const std::string& image, const std::vector<std::string>& codecs, const fs::path& data,
                        const fs::path& svg) {
  std::ostringstream g;
  // Many curves need the key beside the plot rather than over it.
  const bool many = codecs.size() > 6;
  g << "set terminal svg size " << (many ? "1000,560" : "760,520")
    << " dynamic noenhanced font 'sans,12' background rgb 'white'\n"
    << "set output '" << svg.filename().string() << "'\n"
    << "set title 'PSNR against bits per pixel: " << image << "'\n"
    << "set xlabel 'bits per pixel'\nset ylabel 'PSNR (dB, all channels)'\n"
    << "set logscale x 2\nset grid\n" << (many ? "set key outside right top\n" : "set key bottom right\n")
    << "set style line 100 lc rgb 'black' dt 2 lw 2 pt 6\nset style line 101 lc rgb '#777777' dt 4 lw 2 pt 8\n"
    << "plot \\\n";
  for (std::size_t k = 0; k < codecs.size(); ++k) {
    std::string style = "with linespoints lw 1.5 pt " + std::to_string(1 + k % 13);
    if (codecs[k] == "openjpeg") style = "with linespoints ls 100";
    if (codecs[k] == "jxl") style = "with linespoints ls 101";
    g << "  '" << data.filename().string() << "' index " << k << " using 1:2 " << style << " title '" << codecs[k]
      << "'" << (k + 1 < codecs.size() ? ", \\\n" : "\n");
  }
  return g.str();
}

}  // namespace

std::vector<fs::path> draw_rd_plots(const std::vector<RdRecord>& records, const std::vector<std::string>& images,
                                    const std::vector<std::string>& codecs, const fs::path& dir,
                                    const std::string& search_path, std::string& note) {
  std::vector<fs::path> svgs(images.size());
  const auto gnuplot = find_tool("gnuplot", search_path);
  if (!gnuplot) {
    note = "plots not drawn: gnuplot not found in PATH (Debian package gnuplot-nox)";
    return svgs;
  }
  fs::create_directories(dir);
  for (std::size_t i = 0; i < images.size(); ++i) {
    const fs::path base = dir / images[i];
    const fs::path data = base.string() + ".dat", script = base.string() + ".gp", svg = base.string() + ".svg";
    write_text_file(data, data_blocks(records, images[i], codecs));
    write_text_file(script, plot_script(images[i], codecs, data, svg));
    const fs::path log = base.string() + ".log";
    // gnuplot resolves the data and output names relative to its working directory.
    const ProcessResult r = run_process({"/bin/sh", "-c", "cd \"$1\" && exec \"$2\" \"$3\"", "sh",
                                         dir.string(), gnuplot->string(), script.filename().string()}, log);
    const std::string tail = log_tail(log);
    fs::remove(log);
    if (r.exit_code == 0 && fs::is_regular_file(svg)) svgs[i] = svg;
    else note = "plot of " + images[i] + " failed: gnuplot exit " + std::to_string(r.exit_code) + ": " + tail;
  }
  return svgs;
}

}  // namespace pupwave::bench
