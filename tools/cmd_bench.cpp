// `pupwave bench rd|coarse|all`: the PSNR comparison harness (rate-distortion against JPEG 2000,
// JPEG XL, AVIF, HEVC intra and WebP, and the coarse-band experiment of the PUPs multiresolution
// paper).
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "tools/bench/coarse.h"
#include "tools/bench/plots.h"
#include "tools/bench/process.h"
#include "tools/bench/progress.h"
#include "tools/bench/rd_report.h"
#include "tools/bench/rd_run.h"
#include "tools/cli_stdio.h"
#include "tools/commands.h"
#include "transforms/spec.h"

namespace pupwave::cli {
namespace {

namespace fs = std::filesystem;
using namespace pupwave::bench;

struct BenchOptions {
  std::vector<std::string> images;
  std::string transforms = "all";
  std::string bpps = "0.125,0.25,0.5,1,2";
  std::string anchors = "openjpeg,jxl,avif,hevc,webp";
  std::string levels = "1..5";
  unsigned jobs = std::max(1u, std::thread::hardware_concurrency());
  std::string out;
  std::string cli;               // pupwave binary driving our codec; default: this very program
  int effort = 1;                // pupwave compress --effort for every pupwave encode
  std::string entropy = "auto";  // comma list of entropy coders ("auto": no --entropy)
  std::string tunes = "psnr";    // comma list of compress --tune values, each its own curve
};

// Splits at commas outside parentheses, so custom specs such as
// "pups:cinpact-interp(c=9,sigma=5,l=16)" stay whole.
std::vector<std::string> split_list(const std::string& text) {
  std::vector<std::string> items;
  std::string item;
  int depth = 0;
  for (const char ch : text) {
    depth += ch == '(' ? 1 : ch == ')' ? -1 : 0;
    if (ch == ',' && depth <= 0) {
      if (!item.empty()) items.push_back(item);
      item.clear();
    } else {
      item += ch;
    }
  }
  if (!item.empty()) items.push_back(item);
  return items;
}

std::string join(const std::vector<std::string>& items, const std::string& sep) {
  std::string s;
  for (const auto& i : items) s += (s.empty() ? "" : sep) + i;
  return s;
}

// "all", "none" (anchors only) or a comma list; every spec is built once so a typo fails before
// any work is done.
std::vector<std::string> resolve_transforms(const std::string& text) {
  if (text == "none") return {};
  std::vector<std::string> specs = text == "all" ? transform_specs() : split_list(text);
  if (specs.empty()) throw std::invalid_argument("--transforms: no transform given");
  for (std::string& s : specs) s = make_transform(s)->spec();
  return specs;
}

std::vector<double> parse_bpps(const std::string& text) {
  std::vector<double> bpps;
  for (const std::string& item : split_list(text)) {
    std::size_t used = 0;
    double v = 0.0;
    try {
      v = std::stod(item, &used);
    } catch (const std::logic_error&) {
      used = 0;
    }
    if (used != item.size() || !(v > 0.0) || v > 64.0)
      throw std::invalid_argument("--bpp: '" + item + "' is not a rate in (0, 64] bits per pixel");
    bpps.push_back(v);
  }
  if (bpps.empty()) throw std::invalid_argument("--bpp: no rate given");
  std::sort(bpps.begin(), bpps.end());
  bpps.erase(std::unique(bpps.begin(), bpps.end()), bpps.end());
  return bpps;
}

// The images of the --images arguments. A file named on the command line that the harness cannot
// take is an error; one found in a named directory (a 16-bit photograph beside 8-bit ones) is
// skipped with a note, so that a folder of mixed images still runs.
std::vector<BenchImage> load_images(const std::vector<std::string>& args, std::vector<std::string>& notes) {
  std::vector<BenchImage> images;
  for (const std::string& a : args)
    for (const fs::path& p : expand_image_args({a})) {
      if (!fs::is_directory(a)) {
        images.push_back(load_bench_image(p));
        continue;
      }
      try {
        images.push_back(load_bench_image(p));
      } catch (const std::invalid_argument& e) {
        notes.push_back("skipped " + std::string(e.what()));
      }
    }
  if (images.empty()) throw std::invalid_argument("--images: no image the harness takes (8-bit grey or RGB)");
  return images;
}

std::string command_line(const std::string& sub, const BenchOptions& o, bool rd, bool coarse) {
  std::string c =
      "pupwave bench " + sub + " --images " + join(o.images, " ") + " --transforms " + o.transforms;
  if (rd)
    c += " --bpp " + o.bpps + " --anchors " + o.anchors +
         (o.effort != 1 ? " --effort " + std::to_string(o.effort) : "") +
         (o.entropy != "auto" ? " --entropy " + o.entropy : "") +
         (o.tunes != "psnr" ? " --tune " + o.tunes : "");
  if (coarse) c += " --levels " + o.levels;
  return c + " --jobs " + std::to_string(o.jobs) + " --out " + o.out;
}

std::string machine_paragraph(unsigned jobs) {
  const std::string tools = anchor_versions(environment_path());
  return describe_machine() + " Jobs run in parallel: " + std::to_string(jobs) +
         (tools.empty() ? "." : ". Anchor tools: " + tools + ".");
}

}  // namespace

namespace {

// Pupwave codecs for the transforms, then the anchors whose tools are installed.
std::vector<RdCodecPtr> build_codecs(const BenchOptions& o, const std::vector<std::string>& specs,
                                     std::vector<std::string>& notes) {
  const fs::path cli = o.cli.empty() ? fs::read_symlink("/proc/self/exe") : fs::path(o.cli);
  std::vector<RdCodecPtr> codecs;
  for (const std::string& spec : specs)
    for (const std::string& coder : split_list(o.entropy))
      for (const std::string& tune : split_list(o.tunes))
        codecs.push_back(make_pupwave_codec(cli, spec, o.effort, coder == "auto" ? "" : coder, tune));
  const auto anchors = o.anchors == "none" ? std::vector<std::string>{} : split_list(o.anchors);
  for (const std::string& name : anchors) {
    std::string missing;
    if (RdCodecPtr a = make_anchor(name, environment_path(), missing))
      codecs.push_back(a);
    else
      notes.push_back(missing);
  }
  return codecs;
}

// Runs the rd experiment into `dir`; returns the number of failed jobs (listed in summary.md).
std::size_t run_rd_into(const BenchOptions& o, const fs::path& dir, const std::string& command) {
  RdRun run;
  std::vector<std::string> notes;
  const auto specs = resolve_transforms(o.transforms);
  run.bpps = parse_bpps(o.bpps);
  run.codecs = build_codecs(o, specs, notes);
  if (const auto tool = find_tool("butteraugli", environment_path()))
    run.butteraugli = *tool;
  else
    notes.push_back("butteraugli not found in PATH (Debian package butteraugli): its column is empty");
  run.images = load_images(o.images, notes);
  for (const std::string& n : notes) std::cerr << "pupwave bench: " << n << '\n';
  run.jobs = o.jobs;
  run.terminal = Progress::is_terminal(2);
  fs::create_directories(dir);
  const auto records = run_rd(run, fs::temp_directory_path(), std::cerr);

  ReportContext ctx;
  ctx.command = command, ctx.machine = machine_paragraph(o.jobs), ctx.notes = notes, ctx.bpps = run.bpps;
  for (const RdCodecPtr& c : run.codecs) ctx.codecs.push_back(c->name());
  std::vector<std::string> names;
  for (const BenchImage& img : run.images) names.push_back(img.name);
  std::string plot_note;
  for (const auto& svgs :
       draw_rd_plots(records, names, ctx.codecs, dir / "plots", environment_path(), plot_note)) {
    ctx.plots.emplace_back();
    for (const fs::path& svg : svgs) ctx.plots.back().push_back(fs::relative(svg, dir).string());
  }
  if (!plot_note.empty()) ctx.notes.push_back(plot_note), std::cerr << "pupwave bench: " << plot_note << '\n';
  write_results_csv(records, dir / "results.csv");
  write_rd_summary(records, ctx, dir / "summary.md");
  const auto failed = std::count_if(records.begin(), records.end(), [](const RdRecord& r) { return !r.ok; });
  std::cout << "rd: " << records.size() << " measurements in " << (dir / "results.csv").string() << ", "
            << (dir / "summary.md").string() << '\n';
  if (failed)
    std::cerr << "pupwave bench: " << failed << " of " << records.size() << " rd jobs failed (listed in "
              << (dir / "summary.md").string() << ")\n";
  return static_cast<std::size_t>(failed);
}

// Runs the coarse experiment into `dir`; returns the number of failed reconstructions.
std::size_t run_coarse_into(const BenchOptions& o, const fs::path& dir, const std::string& command) {
  const auto specs = resolve_transforms(o.transforms);
  if (specs.empty()) throw std::invalid_argument("--transforms: the coarse experiment needs transforms");
  const auto levels = parse_levels(o.levels);
  std::vector<std::string> notes;
  const auto images = load_images(o.images, notes);
  for (const std::string& n : notes) std::cerr << "pupwave bench: " << n << '\n';
  fs::create_directories(dir);
  const auto records = run_coarse(images, specs, levels, o.jobs, Progress::is_terminal(2), std::cerr);
  write_coarse_report(records, levels, command, machine_paragraph(o.jobs), dir);
  std::cout << "coarse: " << records.size() << " reconstructions in " << (dir / "summary.md").string()
            << '\n';
  const auto failed =
      std::count_if(records.begin(), records.end(), [](const CoarseRecord& r) { return !r.ok; });
  if (failed) std::cerr << "pupwave bench: " << failed << " coarse reconstructions failed (see coarse.csv)\n";
  return static_cast<std::size_t>(failed);
}

// Failed jobs make the command fail, after every output has been written.
void fail_if(std::size_t failed) {
  if (failed)
    throw std::runtime_error(std::to_string(failed) + " job(s) failed; results and summaries list them");
}

void add_common(CLI::App* cmd, BenchOptions& o, bool rd, bool coarse) {
  cmd->add_option("--images", o.images, "image files, or directories of them (8-bit grey or RGB)")
      ->required()
      ->expected(1, -1);
  cmd->add_option("--transforms", o.transforms,
                  "'all', 'none' (rd: anchors only) or a comma list of transform specs")
      ->capture_default_str();
  if (rd) {
    cmd->add_option("--bpp", o.bpps, "comma list of target bits per pixel")->capture_default_str();
    cmd->add_option("--anchors", o.anchors,
                    "comma list of openjpeg, jxl, avif (libaom speed 4), avif-s6 (speed 6), hevc, webp, or "
                    "'none' (missing tools are skipped with a note)")
        ->capture_default_str();
    cmd->add_option("--cli", o.cli, "pupwave binary to drive (default: this program)");
    cmd->add_option("--effort", o.effort, "pupwave compress --effort for every pupwave encode (1 or 2)")
        ->capture_default_str()
        ->check(CLI::Range(1, 2));
    cmd->add_option(
           "--entropy", o.entropy,
           "comma list of pupwave entropy coders (compress --entropy names), each a curve per transform "
           "(SPEC+CODER): auto (the default choice), ebcot, pc, lc or ht")
        ->capture_default_str();
    cmd->add_option("--tune", o.tunes,
                    "comma list of pupwave compress --tune values (psnr, visual), each a curve per transform "
                    "and coder (SPEC+visual)")
        ->capture_default_str()
        ->each([](const std::string& list) {
          for (const std::string& t : split_list(list))
            if (t != "psnr" && t != "visual")
              throw CLI::ValidationError("unknown tune " + t + " (psnr or visual)");
        });
  }
  if (coarse) cmd->add_option("--levels", o.levels, "levels 'A..B' or a comma list")->capture_default_str();
  cmd->add_option("--jobs", o.jobs, "parallel jobs")->capture_default_str()->check(CLI::Range(1u, 256u));
  cmd->add_option("--out", o.out, "output directory")->required();
}

}  // namespace

void add_bench_command(CLI::App& app) {
  auto* bench = app.add_subcommand("bench",
                                   "PSNR comparison harness: rate-distortion against JPEG 2000 and JPEG XL, "
                                   "and the coarse-band experiment");
  bench->require_subcommand(1);
  auto opt = std::make_shared<BenchOptions>();
  auto* rd = bench->add_subcommand(
      "rd",
      "Compress/decompress every image x transform x rate (and the anchors); writes results.csv, "
      "summary.md (PSNR per rate, BD-PSNR/BD-rate vs OpenJPEG, SSIM, MS-SSIM and butteraugli when installed) "
      "and plots/ (gnuplot SVG) into --out");
  add_common(rd, *opt, true, false);
  add_report_verbosity_flags(*rd);
  rd->callback([opt] { fail_if(run_rd_into(*opt, opt->out, command_line("rd", *opt, true, false))); });
  auto* coarse = bench->add_subcommand(
      "coarse",
      "Reconstruct from the coarse band alone after L levels (details zeroed), luma PSNR per transform "
      "(Fig. 16 of the PUPs multiresolution paper); writes coarse.csv and summary.md into --out");
  add_common(coarse, *opt, false, true);
  add_report_verbosity_flags(*coarse);
  coarse->callback(
      [opt] { fail_if(run_coarse_into(*opt, opt->out, command_line("coarse", *opt, false, true))); });
  auto* all = bench->add_subcommand("all", "Both: rd into --out/rd and coarse into --out/coarse");
  add_common(all, *opt, true, true);
  add_report_verbosity_flags(*all);
  all->callback([opt] {
    const std::string command = command_line("all", *opt, true, true);
    const std::size_t failed = run_coarse_into(*opt, fs::path(opt->out) / "coarse", command);
    fail_if(failed + run_rd_into(*opt, fs::path(opt->out) / "rd", command));
  });
}

}  // namespace pupwave::cli
