#include "tools/bench/plots.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "tools/bench/process.h"
#include "tools/bench/rd_report.h"

namespace pupwave::bench {
namespace {

namespace fs = std::filesystem;

// One plotted measurement.
struct PlotPoint {
  double bpp = 0.0, psnr = 0.0;
  double ms_ssim_db = 0.0;  // -10 log10(1 - MS-SSIM); infinite when MS-SSIM is 1
  bool operator<(const PlotPoint& o) const { return bpp < o.bpp; }
};

// A value for gnuplot: non-finite values become the missing marker '?'.
std::string cell(double v) {
  if (!std::isfinite(v)) return "?";
  std::ostringstream s;
  s.precision(8);
  s << v;
  return s.str();
}

// PSNR of the reference curve at `bpp`, linear in log(bpp) between its points, and extended
// along the end segments by up to 3% in rate (rate control lands a little off target); NaN
// farther out.
double interpolate(const std::vector<PlotPoint>& ref, double bpp) {
  constexpr double kReach = 0.03;
  const double x = std::log(bpp);
  for (std::size_t i = 0; i + 1 < ref.size(); ++i) {
    const double a = std::log(ref[i].bpp), b = std::log(ref[i + 1].bpp);
    const bool first = i == 0, last = i + 2 == ref.size();
    if (b > a && x >= a - (first ? kReach : 0.0) && x <= b + (last ? kReach : 0.0))
      return ref[i].psnr + (ref[i + 1].psnr - ref[i].psnr) * (x - a) / (b - a);
  }
  return NAN;
}

// The points of one image and codec with a finite PSNR (lossless points are left out), by rate.
std::vector<PlotPoint> points(const std::vector<RdRecord>& records, const std::string& image,
                              const std::string& codec) {
  std::vector<PlotPoint> p;
  for (const RdRecord& r : records)
    if (r.image == image && r.codec == codec && r.ok && std::isfinite(r.psnr))
      p.push_back({r.bpp, r.psnr, -10.0 * std::log10(1.0 - r.ms_ssim)});
  std::sort(p.begin(), p.end());
  return p;
}

// Points of every codec for one image (bpp, PSNR, PSNR minus OpenJPEG's at that rate, MS-SSIM
// in dB; "?" where missing); gnuplot reads block k with `index k`.
std::string data_blocks(const std::vector<RdRecord>& records, const std::string& image,
                        const std::vector<std::string>& codecs) {
  const auto reference = points(records, image, "openjpeg");
  std::ostringstream d;
  d << "# bpp psnr_db psnr_minus_openjpeg_db ms_ssim_db\n";
  for (const std::string& codec : codecs) {
    d << "# " << codec << "\n";
    const auto curve = points(records, image, codec);
    // A codec without points still needs a (missing) row, or gnuplot would merge its empty
    // block into the separator and shift every later `index`.
    if (curve.empty()) d << "? ? ? ?\n";
    for (const PlotPoint& p : curve)
      d << cell(p.bpp) << ' ' << cell(p.psnr) << ' ' << cell(p.psnr - interpolate(reference, p.bpp)) << ' '
        << cell(p.ms_ssim_db) << '\n';
    d << "\n\n";
  }
  return d.str();
}

// One plot of column `column` of the data file into `svg`. Anchors are drawn dashed in black
// and grey so our transforms stand out against them.
std::string plot_commands(const std::string& title, const std::string& ylabel, int column,
                          const std::vector<std::string>& codecs, const fs::path& data, const fs::path& svg) {
  std::ostringstream g;
  // Many curves need the key beside the plot rather than over it.
  const bool many = codecs.size() > 6;
  g << "set terminal svg size " << (many ? "1000,560" : "760,520")
    << " dynamic noenhanced font 'sans,12' background rgb 'white'\n"
    << "set output '" << svg.filename().string() << "'\n"
    << "set title '" << title << "'\nset xlabel 'bits per pixel'\nset ylabel '" << ylabel << "'\n"
    << (many ? "set key outside right top\n" : "set key bottom right\n") << "plot \\\n";
  for (std::size_t k = 0; k < codecs.size(); ++k) {
    std::string style = "with linespoints lw 1.5 pt " + std::to_string(1 + k % 13);
    if (codecs[k] == "openjpeg") style = "with linespoints ls 100";
    if (codecs[k] == "jxl") style = "with linespoints ls 101";
    g << "  '" << data.filename().string() << "' index " << k << " using 1:" << column << " " << style
      << " title '" << codecs[k] << "'" << (k + 1 < codecs.size() ? ", \\\n" : "\n");
  }
  return g.str();
}

// The script drawing the plots of one image: PSNR, MS-SSIM, and PSNR relative to OpenJPEG when
// it ran (`svgs` in that order).
std::string plot_script(const std::string& image, const std::vector<std::string>& codecs,
                        const fs::path& data, const std::vector<fs::path>& svgs) {
  std::string g =
      "set datafile missing '?'\nset logscale x 2\nset grid\n"
      "set style line 100 lc rgb 'black' dt 2 lw 2 pt 6\nset style line 101 lc rgb '#777777' dt 4 lw 2 pt "
      "8\n";
  g += plot_commands("PSNR against bits per pixel: " + image, "PSNR (dB, all channels)", 2, codecs, data,
                     svgs[0]);
  g += plot_commands("MS-SSIM against bits per pixel: " + image,
                     "MS-SSIM of luma (dB, -10 log10(1 - MS-SSIM))", 4, codecs, data, svgs[1]);
  if (svgs.size() > 2)
    g += plot_commands("PSNR minus the PSNR of OpenJPEG at the same rate: " + image, "PSNR difference (dB)",
                       3, codecs, data, svgs[2]);
  return g;
}

}  // namespace

std::vector<std::vector<fs::path>> draw_rd_plots(const std::vector<RdRecord>& records,
                                                 const std::vector<std::string>& images,
                                                 const std::vector<std::string>& codecs, const fs::path& dir,
                                                 const std::string& search_path, std::string& note) {
  std::vector<std::vector<fs::path>> drawn(images.size());
  const auto gnuplot = find_tool("gnuplot", search_path);
  if (!gnuplot) {
    note = "plots not drawn: gnuplot not found in PATH (Debian package gnuplot-nox)";
    return drawn;
  }
  const bool relative = std::find(codecs.begin(), codecs.end(), "openjpeg") != codecs.end();
  fs::create_directories(dir);
  // Plots of images no longer in the run would otherwise survive a regeneration.
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string ext = entry.path().extension().string();
    if (entry.is_regular_file() && (ext == ".svg" || ext == ".dat" || ext == ".gp")) fs::remove(entry.path());
  }
  for (std::size_t i = 0; i < images.size(); ++i) {
    const std::string base = (dir / images[i]).string();
    const fs::path data = base + ".dat", script = base + ".gp", log = base + ".log";
    std::vector<fs::path> svgs = {base + ".svg", base + "-ms-ssim.svg"};
    if (relative) svgs.emplace_back(base + "-vs-openjpeg.svg");
    write_text_file(data, data_blocks(records, images[i], codecs));
    write_text_file(script, plot_script(images[i], codecs, data, svgs));
    // gnuplot resolves the data and output names relative to its working directory.
    const ProcessResult r = run_process({"/bin/sh", "-c", "cd \"$1\" && exec \"$2\" \"$3\"", "sh",
                                         dir.string(), gnuplot->string(), script.filename().string()},
                                        log);
    const std::string tail = log_tail(log);
    fs::remove(log);
    const bool ok = r.exit_code == 0 &&
                    std::all_of(svgs.begin(), svgs.end(), [](auto& p) { return fs::is_regular_file(p); });
    if (ok)
      drawn[i] = svgs;
    else
      note = "plot of " + images[i] + " failed: gnuplot exit " + std::to_string(r.exit_code) + ": " + tail;
  }
  return drawn;
}

}  // namespace pupwave::bench
