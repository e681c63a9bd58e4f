#include "tools/bench/rd_report.h"

#include <sys/utsname.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <map>
#include <sstream>
#include <thread>

#include "tools/atomic_file.h"
#include "tools/bench/bd_metrics.h"

namespace pupwave::bench {
namespace {

namespace fs = std::filesystem;

constexpr const char* kReference = "openjpeg";
// The second reference: pupwave's default transform, so anchors read as gains or losses against it.
constexpr const char* kPupwaveReference = "cdf97";

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

std::string number(double v) {
  if (std::isnan(v)) return "";
  std::ostringstream s;
  s.precision(10);
  s << v;
  return s.str();
}

// The records of one image and codec, in rate order.
std::vector<const RdRecord*> curve_records(const std::vector<RdRecord>& records, const std::string& image,
                                           const std::string& codec) {
  std::vector<const RdRecord*> out;
  for (const RdRecord& r : records)
    if (r.image == image && r.codec == codec) out.push_back(&r);
  std::sort(out.begin(), out.end(), [](auto* a, auto* b) { return a->target_bpp < b->target_bpp; });
  return out;
}

// MS-SSIM on a dB scale, where the Bjontegaard fit treats it like PSNR (infinite at 1).
double ms_ssim_db(const RdRecord& r) { return -10.0 * std::log10(1.0 - r.ms_ssim); }

double psnr_of(const RdRecord& r) { return r.psnr; }

// The (achieved bpp, quality in dB) points of one image and codec; `quality` picks the measure.
std::vector<RdPoint> curve(const std::vector<RdRecord>& records, const std::string& image,
                           const std::string& codec, double (*quality)(const RdRecord&) = psnr_of) {
  std::vector<RdPoint> points;
  for (const RdRecord* r : curve_records(records, image, codec))
    if (r->ok) points.push_back({r->bpp, quality(*r)});
  return points;
}

const RdRecord* find(const std::vector<RdRecord>& records, const std::string& image, const std::string& codec,
                     double bpp) {
  for (const RdRecord& r : records)
    if (r.image == image && r.codec == codec && r.target_bpp == bpp) return &r;
  return nullptr;
}

std::vector<std::string> image_names(const std::vector<RdRecord>& records) {
  std::vector<std::string> names;
  for (const RdRecord& r : records)
    if (std::find(names.begin(), names.end(), r.image) == names.end()) names.push_back(r.image);
  return names;
}

// Per codec and image, the summary quantities.
struct CodecStats {
  std::vector<double> psnr;                        // per target rate (NaN when failed)
  std::vector<double> ssim, ms_ssim, butteraugli;  // per target rate (NaN when failed or not measured)
  double bd_psnr = NAN, bd_rate = NAN;
  double bd_rate_cdf97 = NAN;             // BD-rate against pupwave cdf97 (NaN when cdf97 did not run)
  double bd_rate_ms_ssim = NAN;           // BD-rate on MS-SSIM in dB, against the BD reference
  double worst_miss = 0.0;                // largest |achieved / target - 1| over the rates, in percent
  double encode_s = 0.0, decode_s = 0.0;  // totals over the rates
};

CodecStats stats_for(const std::vector<RdRecord>& records, const std::string& image, const std::string& codec,
                     const std::vector<double>& bpps, bool have_reference, bool have_cdf97) {
  CodecStats s;
  for (double bpp : bpps) {
    const RdRecord* r = find(records, image, codec, bpp);
    const bool ok = r && r->ok;
    s.psnr.push_back(ok ? r->psnr : NAN);
    s.ssim.push_back(ok ? r->ssim : NAN);
    s.ms_ssim.push_back(ok ? r->ms_ssim : NAN);
    s.butteraugli.push_back(ok ? r->butteraugli : NAN);
    if (!ok) continue;
    s.worst_miss = std::max(s.worst_miss, std::abs(r->bpp / r->target_bpp - 1.0) * 100.0);
    s.encode_s += r->encode_s, s.decode_s += r->decode_s;
  }
  if (std::all_of(s.psnr.begin(), s.psnr.end(), [](double p) { return std::isnan(p); }))
    s.worst_miss = s.encode_s = s.decode_s = NAN;  // nothing measured: no rate, no time
  if (have_reference) {
    const auto ref = curve(records, image, kReference);
    const auto mine = curve(records, image, codec);
    s.bd_psnr = bd_psnr(ref, mine), s.bd_rate = bd_rate(ref, mine);
    s.bd_rate_ms_ssim =
        bd_rate(curve(records, image, kReference, ms_ssim_db), curve(records, image, codec, ms_ssim_db));
  }
  if (have_cdf97)
    s.bd_rate_cdf97 = bd_rate(curve(records, image, kPupwaveReference), curve(records, image, codec));
  return s;
}

// A table header: the codec, one column per target rate, then `extra` columns (right-aligned).
std::string rate_table_header(const std::vector<double>& bpps, const std::vector<std::string>& extra) {
  std::ostringstream h, rule;
  h << "| codec |";
  rule << "|---|";
  for (double b : bpps) h << ' ' << number(b) << " bpp |", rule << "---:|";
  for (const std::string& column : extra) h << ' ' << column << " |", rule << "---:|";
  return h.str() + "\n" + rule.str() + "\n";
}

std::string table_header(const std::vector<double>& bpps) {
  return rate_table_header(bpps, {"BD-PSNR (dB)", "BD-rate (%)", "BD-rate vs cdf97 (%)",
                                  "MS-SSIM BD-rate (%)", "worst rate miss (%)", "encode (s)", "decode (s)"});
}

// The perceptual table has one "SSIM / MS-SSIM / butteraugli" cell per rate.
std::string perceptual_header(const std::vector<double>& bpps) { return rate_table_header(bpps, {}); }

std::string perceptual_row(const std::string& codec, const CodecStats& s) {
  std::ostringstream row;
  row << "| " << codec << " |";
  for (std::size_t k = 0; k < s.ssim.size(); ++k)
    row << ' ' << fixed(s.ssim[k], 4) << " / " << fixed(s.ms_ssim[k], 4) << " / "
        << fixed(s.butteraugli[k], 3) << " |";
  return row.str() + "\n";
}

std::string table_row(const std::string& codec, const CodecStats& s) {
  std::ostringstream row;
  row << "| " << codec << " |";
  for (double p : s.psnr) row << ' ' << fixed(p, 2) << " |";
  row << ' ' << fixed(s.bd_psnr, 2) << " | " << fixed(s.bd_rate, 1) << " | " << fixed(s.bd_rate_cdf97, 1)
      << " | " << fixed(s.bd_rate_ms_ssim, 1) << " | " << fixed(s.worst_miss, 1) << " | "
      << fixed(s.encode_s, 2) << " | " << fixed(s.decode_s, 2) << " |\n";
  return row.str();
}

// Mean of each field over the images (NaN propagates: a failed cell makes the mean n/a).
CodecStats mean_stats(const std::vector<CodecStats>& per_image) {
  CodecStats m = per_image.front();
  for (std::size_t i = 1; i < per_image.size(); ++i) {
    for (std::size_t k = 0; k < m.psnr.size(); ++k) {
      m.psnr[k] += per_image[i].psnr[k], m.ssim[k] += per_image[i].ssim[k];
      m.ms_ssim[k] += per_image[i].ms_ssim[k], m.butteraugli[k] += per_image[i].butteraugli[k];
    }
    m.bd_psnr += per_image[i].bd_psnr, m.bd_rate += per_image[i].bd_rate;
    m.bd_rate_cdf97 += per_image[i].bd_rate_cdf97, m.bd_rate_ms_ssim += per_image[i].bd_rate_ms_ssim;
    const double miss = per_image[i].worst_miss;
    m.worst_miss = std::isnan(m.worst_miss) || std::isnan(miss) ? NAN : std::max(m.worst_miss, miss);
    m.encode_s += per_image[i].encode_s, m.decode_s += per_image[i].decode_s;
  }
  const double n = static_cast<double>(per_image.size());
  for (auto* v : {&m.psnr, &m.ssim, &m.ms_ssim, &m.butteraugli})
    for (double& p : *v) p /= n;
  m.bd_psnr /= n, m.bd_rate /= n, m.bd_rate_cdf97 /= n, m.bd_rate_ms_ssim /= n;
  m.encode_s /= n, m.decode_s /= n;
  return m;
}

std::string failures(const std::vector<RdRecord>& records) {
  std::ostringstream f;
  for (const RdRecord& r : records)
    if (!r.ok)
      f << "- " << r.image << ", " << r.codec << ", " << number(r.target_bpp) << " bpp: " << r.error << '\n';
  return f.str();
}

}  // namespace

const std::vector<std::string>& results_csv_columns() {
  static const std::vector<std::string> columns = {
      "image",       "width",    "height",   "channels",     "codec",     "kind", "target_bpp",
      "bytes",       "bpp",      "psnr_db",  "psnr_luma_db", "max_error", "ssim", "ms_ssim",
      "butteraugli", "encode_s", "decode_s", "setting",      "status"};
  return columns;
}

void write_results_csv(const std::vector<RdRecord>& records, const fs::path& path) {
  std::ostringstream out;
  const auto& cols = results_csv_columns();
  for (std::size_t i = 0; i < cols.size(); ++i) out << (i ? "," : "") << cols[i];
  out << '\n';
  for (const RdRecord& r : records) {
    auto ok_number = [&](double v) { return r.ok ? number(v) : std::string(); };
    out << csv_field(r.image) << ',' << r.width << ',' << r.height << ',' << r.channels << ','
        << csv_field(r.codec) << ',' << r.kind << ',' << number(r.target_bpp) << ','
        << (r.ok ? std::to_string(r.bytes) : "") << ',' << ok_number(r.bpp) << ',' << ok_number(r.psnr) << ','
        << ok_number(r.psnr_luma) << ',' << ok_number(r.max_error) << ',' << ok_number(r.ssim) << ','
        << ok_number(r.ms_ssim) << ',' << ok_number(r.butteraugli) << ',' << ok_number(r.encode_s) << ','
        << ok_number(r.decode_s) << ',' << csv_field(r.setting) << ','
        << csv_field(r.ok ? "ok" : "failed: " + r.error) << '\n';
  }
  write_text_file(path, out.str());
}

void write_rd_summary(const std::vector<RdRecord>& records, const ReportContext& ctx, const fs::path& path) {
  const bool have_reference = std::find(ctx.codecs.begin(), ctx.codecs.end(), kReference) != ctx.codecs.end();
  const bool have_cdf97 =
      std::find(ctx.codecs.begin(), ctx.codecs.end(), kPupwaveReference) != ctx.codecs.end();
  const auto images = image_names(records);
  std::ostringstream md;
  md << "# Rate-distortion results\n\nMade by `" << ctx.command << "`.\n\nCodecs: ";
  for (std::size_t i = 0; i < ctx.codecs.size(); ++i) md << (i ? ", " : "") << ctx.codecs[i];
  md << ".\n\n" << ctx.machine << "\n\n";
  for (const std::string& note : ctx.notes) md << "> Note: " << note << "\n\n";
  md << "PSNR in dB over all channels (RGB for colour images, peak 255) at each target rate; achieved "
        "rates are in `results.csv` and the worst miss is shown. BD-PSNR and BD-rate (Bjontegaard, cubic fit "
        "in log rate over achieved rates) are against "
     << (have_reference
             ? "OpenJPEG (JPEG 2000, 9/7, 6 resolutions): positive BD-PSNR and negative BD-rate mean "
               "better than JPEG 2000."
             : "OpenJPEG, which did not run, so they are n/a.")
     << " BD-rate vs cdf97 is against pupwave's default transform (negative: smaller files than pupwave at "
        "equal PSNR). MS-SSIM BD-rate is the BD-rate on MS-SSIM in dB (-10 log10(1 - MS-SSIM)) against the "
        "same reference as BD-rate. The second table of each section gives SSIM / MS-SSIM (of luma) / "
        "butteraugli distance at each target rate (higher, higher, lower is better; n/a where not measured). "
        "Times are wall-clock per file summed over the rates, including process start (for the "
        "anchors that need it, the format conversion by ffmpeg is not counted).\n\n";
  std::map<std::string, std::vector<CodecStats>> per_codec;
  std::ostringstream detail;
  for (std::size_t i = 0; i < images.size(); ++i) {
    const RdRecord& first =
        *std::find_if(records.begin(), records.end(), [&](auto& r) { return r.image == images[i]; });
    detail << "### " << images[i] << " (" << first.width << "x" << first.height << ", "
           << (first.channels == 1 ? "grey" : "RGB") << ")\n\n"
           << table_header(ctx.bpps);
    for (const std::string& codec : ctx.codecs) {
      per_codec[codec].push_back(stats_for(records, images[i], codec, ctx.bpps, have_reference, have_cdf97));
      detail << table_row(codec, per_codec[codec].back());
    }
    detail << '\n' << perceptual_header(ctx.bpps);
    for (const std::string& codec : ctx.codecs) detail << perceptual_row(codec, per_codec[codec].back());
    if (i < ctx.plots.size())
      for (const std::string& plot : ctx.plots[i])
        detail << "\n![" << images[i] << ": " << plot << "](" << plot << ")\n";
    detail << '\n';
  }
  md << "## Mean over " << images.size() << " image(s)\n\n" << table_header(ctx.bpps);
  for (const std::string& codec : ctx.codecs)
    if (!per_codec[codec].empty()) md << table_row(codec, mean_stats(per_codec[codec]));
  md << '\n' << perceptual_header(ctx.bpps);
  for (const std::string& codec : ctx.codecs)
    if (!per_codec[codec].empty()) md << perceptual_row(codec, mean_stats(per_codec[codec]));
  md << "\n## Per image\n\n" << detail.str();
  const std::string failed = failures(records);
  if (!failed.empty()) md << "## Failed jobs\n\n" << failed;
  write_text_file(path, md.str());
}

std::string describe_machine() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line, model = "unknown CPU";
  while (std::getline(cpuinfo, line))
    if (line.rfind("model name", 0) == 0) {
      model = line.substr(line.find(':') + 2);
      break;
    }
  std::ifstream os_release("/etc/os-release");
  std::string os = "unknown OS";
  while (std::getline(os_release, line))
    if (line.rfind("PRETTY_NAME=", 0) == 0) os = line.substr(13, line.size() - 14);
  utsname u{};
  uname(&u);
  return "Machine: " + model + ", " + std::to_string(std::thread::hardware_concurrency()) +
         " logical cores, " + os + ", Linux " + u.release + ".";
}

void write_text_file(const fs::path& path, const std::string& text) {
  const auto* p = reinterpret_cast<const std::uint8_t*>(text.data());
  cli::write_output_bytes(path, {p, text.size()});
}

std::string fixed(double value, int decimals) {
  if (std::isnan(value)) return "n/a";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(decimals);
  s << value;
  return s.str();
}

}  // namespace pupwave::bench
