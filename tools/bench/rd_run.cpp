#include "tools/bench/rd_run.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "codec/image/image_metrics.h"
#include "tools/bench/process.h"
#include "tools/bench/progress.h"
#include "tools/bench/ssim.h"
#include "tools/image_io.h"
#include "transforms/executor.h"

namespace pupwave::bench {
namespace {

namespace fs = std::filesystem;

bool is_image_extension(std::string ext) {
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  for (const char* e : {".png", ".ppm", ".pgm", ".pnm", ".tif", ".tiff", ".bmp"})
    if (ext == e) return true;
  return false;
}

// File-name-safe form of a codec name ("pups:cinpact-l32" -> "pups_cinpact-l32").
std::string safe_name(std::string s) {
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '.') c = '_';
  return s;
}

std::string bpp_label(double bpp) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", bpp);
  return buf;
}

// The reference image as butteraugli reads it (the Debian tool takes PNG and JPEG only).
fs::path reference_png(const fs::path& work, const BenchImage& img) {
  return work / (safe_name(img.name) + ".png");
}

// Runs butteraugli on two PNG files and returns the distance it prints as its last line (libpng
// may warn on stderr before it); std::runtime_error quoting the tool when it fails or prints
// something else.
double butteraugli_distance(const fs::path& tool, const fs::path& reference, const fs::path& decoded,
                            const fs::path& log) {
  const ProcessResult r = run_process({tool.string(), reference.string(), decoded.string()}, log);
  std::ifstream in(log);
  std::string line, last;
  while (std::getline(in, line))
    if (line.find_first_not_of(" \t\r") != std::string::npos) last = line;
  std::istringstream text(last);
  double distance = 0.0;
  std::string rest;
  if (r.exit_code != 0 || !(text >> distance) || text >> rest)
    throw std::runtime_error("butteraugli failed (exit " + std::to_string(r.exit_code) +
                             "): " + log_tail(log));
  return distance;
}

struct Job {
  std::size_t image, codec, rate;
};

// Encodes, decodes and measures one job inside its own directory.
RdRecord run_job(const RdRun& run, const Job& job, const fs::path& work) {
  const BenchImage& img = run.images[job.image];
  const RdCodec& codec = *run.codecs[job.codec];
  RdRecord r;
  r.image = img.name, r.width = img.pixels.width, r.height = img.pixels.height,
  r.channels = img.pixels.channels;
  r.codec = codec.name(), r.kind = codec.kind(), r.target_bpp = run.bpps[job.rate];
  const fs::path dir = work / safe_name(img.name) / safe_name(codec.name()) / bpp_label(r.target_bpp);
  try {
    fs::create_directories(dir);
    const std::string pnm = img.pixels.channels == 1 ? ".pgm" : ".ppm";
    EncodeRequest q{work / (safe_name(img.name) + pnm),
                    dir / ("coded" + codec.extension()),
                    dir / "log.txt",
                    r.target_bpp,
                    r.width,
                    r.height,
                    r.channels};
    const EncodeOutcome e = codec.encode(q);
    r.bytes = e.bytes, r.encode_s = e.seconds, r.setting = e.setting;
    r.bpp = 8.0 * static_cast<double>(e.bytes) / static_cast<double>(r.width * r.height);
    const fs::path decoded = dir / ("decoded" + pnm);
    r.decode_s = codec.decode(q.output, decoded, q.log);
    Image out = cli::read_image(decoded);
    if (out.type != img.pixels.type) out = cli::convert_sample_type(out, img.pixels.type);
    const ImageError err = compare_images(img.pixels, out);
    r.psnr = err.overall.psnr;
    r.psnr_luma = err.has_luma ? err.luma.psnr : err.overall.psnr;
    r.max_error = err.overall.max_abs;
    r.ssim = ssim(img.pixels, out), r.ms_ssim = ms_ssim(img.pixels, out);
    if (!run.butteraugli.empty()) {
      const fs::path png = dir / "decoded.png";
      cli::write_image(out, png);
      r.butteraugli =
          butteraugli_distance(run.butteraugli, reference_png(work, img), png, dir / "butteraugli.txt");
    }
    r.ok = true;
  } catch (const std::exception& ex) {
    r.error = ex.what();
  }
  fs::remove_all(dir);  // decoded images of a full run would fill the disk otherwise
  return r;
}

// A fresh private directory for one run's temporary files.
fs::path make_work_dir(const fs::path& root) {
  for (int i = 0;; ++i) {
    fs::path dir = root / ("pupwave-bench-" + std::to_string(getpid()) + "-" + std::to_string(i));
    if (fs::create_directories(dir)) return dir;
  }
}

}  // namespace

std::vector<fs::path> expand_image_args(const std::vector<std::string>& args) {
  std::vector<fs::path> files;
  for (const std::string& a : args) {
    const fs::path p(a);
    if (fs::is_directory(p)) {
      std::vector<fs::path> found;
      for (const auto& entry : fs::directory_iterator(p))
        if (entry.is_regular_file() && is_image_extension(entry.path().extension().string()))
          found.push_back(entry.path());
      std::sort(found.begin(), found.end());
      files.insert(files.end(), found.begin(), found.end());
    } else if (fs::is_regular_file(p)) {
      files.push_back(p);
    } else {
      throw std::invalid_argument("--images: '" + a + "' is neither a file nor a directory");
    }
  }
  if (files.empty()) throw std::invalid_argument("--images: no image files found");
  return files;
}

BenchImage load_bench_image(const fs::path& path) {
  BenchImage b{path.stem().string(), path, cli::read_image(path)};
  if (b.pixels.type != SampleType::u8 || (b.pixels.channels != 1 && b.pixels.channels != 3))
    throw std::invalid_argument(path.string() + ": the harness takes 8-bit grey or RGB images (got " +
                                std::to_string(b.pixels.channels) + " channel(s), " +
                                to_string(b.pixels.type) + ")");
  return b;
}

std::vector<RdRecord> run_rd(const RdRun& run, const fs::path& work_root, std::ostream& log) {
  const fs::path work = make_work_dir(work_root);
  std::vector<Job> jobs;
  for (std::size_t i = 0; i < run.images.size(); ++i) {
    // Every codec reads the same 8-bit PPM/PGM (not PNG: gamma chunks would skew the anchors).
    const std::string pnm = run.images[i].pixels.channels == 1 ? ".pgm" : ".ppm";
    cli::write_image(run.images[i].pixels, work / (safe_name(run.images[i].name) + pnm));
    if (!run.butteraugli.empty()) cli::write_image(run.images[i].pixels, reference_png(work, run.images[i]));
    for (std::size_t c = 0; c < run.codecs.size(); ++c)
      for (std::size_t r = 0; r < run.bpps.size(); ++r) jobs.push_back({i, c, r});
  }
  std::vector<RdRecord> records(jobs.size());
  Progress progress(log, jobs.size(), "rd", run.terminal);
  make_pool_executor(std::max(1u, run.jobs))->run(jobs.size(), [&](std::size_t j) {
    records[j] = run_job(run, jobs[j], work);
    const RdRecord& r = records[j];
    char what[200];
    std::snprintf(what, sizeof what, "%s %s %g bpp: %s", r.image.c_str(), r.codec.c_str(), r.target_bpp,
                  r.ok ? (bpp_label(std::round(r.psnr * 100) / 100) + " dB").c_str() : "FAILED");
    if (!r.ok) progress.note("warning: " + std::string(what) + ": " + r.error);
    progress.step(what);
  });
  progress.finish();
  fs::remove_all(work);
  return records;
}

}  // namespace pupwave::bench
