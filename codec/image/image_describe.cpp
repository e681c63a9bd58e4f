// describe_stream: a readable summary of a .pw file for `pupwave info`.
#include <cstdint>
#include <sstream>
#include <string>

#include "codec/error.h"
#include "codec/image/image_stream.h"

namespace pupwave {
namespace {

// Per-resolution totals of the coded blocks.
struct ResolutionSummary {
  std::size_t blocks = 0;
  std::size_t coded = 0;
  std::size_t bytes = 0;
};

std::string to_string(Transfer t, int offset_log2) {
  switch (t) {
    case Transfer::linear: return "linear";
    case Transfer::log2:
      return "log2 (coded as log2(1 + |x| / 2^-14), signed; targets in log-PSNR, peak 1 stop)";
    case Transfer::log2_adaptive:
      return "log2 adaptive (coded as log2(1 + |x| / 2^" + std::to_string(offset_log2) +
             "), signed; targets in adaptive log-PSNR, peak 1 stop)";
  }
  return "unknown";
}

// The META chunk: channel names, windows, attributes.
void describe_metadata(std::ostringstream& out, const ImageMetadata& m, const Extent& dims) {
  if (!m.channel_names.empty()) {
    out << "  channels    ";
    for (std::size_t c = 0; c < m.channel_names.size(); ++c) out << (c ? "," : "") << m.channel_names[c];
    out << "\n";
  }
  if (m.x != 0 || m.y != 0 || m.full_width > 0)
    out << "  data window " << dims[0] << "x" << dims[1] << (m.x < 0 ? "" : "+") << m.x
        << (m.y < 0 ? "" : "+") << m.y << "\n";
  if (m.full_width > 0)
    out << "  display window " << m.full_width << "x" << m.full_height << (m.full_x < 0 ? "" : "+")
        << m.full_x << (m.full_y < 0 ? "" : "+") << m.full_y << "\n";
  for (const ImageAttribute& a : m.attributes) {
    out << "  attribute   " << a.name << " = ";
    if (a.kind == ImageAttribute::Kind::string) out << '"' << a.text << "\" (string)\n";
    if (a.kind == ImageAttribute::Kind::integer) out << a.integer << " (int)\n";
    if (a.kind == ImageAttribute::Kind::real) out << a.real << " (float)\n";
  }
}

}  // namespace

std::string describe_stream(std::span<const std::uint8_t> bytes) {
  // No output is made, so no decode limit; the transform spec is checked, never designed.
  const ParsedStream s = parse_container(bytes, 0, DecodeLimits{SIZE_MAX});
  const StreamHeader& h = s.header;
  std::ostringstream out;
  out << "pupwave stream, version " << int(bytes[4]) << ", " << bytes.size() << " bytes\n";
  out << "  size        " << h.dims[0] << " x " << h.dims[1];
  if (h.dims[2] > 1) out << " x " << h.dims[2];
  out << ", " << h.channels << " channel(s), " << to_string(h.type) << "\n";
  out << "  colour      " << to_string(h.colour) << "\n";
  if (!is_integer(h.type))
    out << "  transfer    " << to_string(h.transfer, h.transfer_offset_log2)
        << (h.nonnegative ? ", non-negative input" : "") << "\n";
  if (!h.nonfinite.empty())
    out << "  non-finite  " << h.nonfinite.size() << " sample(s) kept exactly (NFIN)\n";
  describe_metadata(out, h.metadata, h.dims);
  out << "  transform   " << h.spec << ", " << h.levels << " level(s), " << s.bands.size() << " subbands\n";
  out << "  coding      " << (h.reversible ? "reversible (lossless)" : "irreversible (lossy)") << ", entropy "
      << to_string(h.entropy) << ", code-blocks " << h.block_size()[0] << "x" << h.block_size()[1];
  if (h.block_size()[2] > 1) out << "x" << h.block_size()[2];
  out << ", reconstruction offset " << h.delta << "\n";
  if (!h.reversible && !h.steps.empty()) {
    out << "  steps       coarse band";
    for (std::uint32_t c = 0; c < h.channels; ++c) out << " " << h.steps[c * s.bands.size()];
    out << "; finest details";
    for (std::uint32_t c = 0; c < h.channels; ++c) out << " " << h.steps[(c + 1) * s.bands.size() - 1];
    out << "\n";
  }
  std::vector<ResolutionSummary> res(s.resolution_data.size());
  for (std::size_t i = 0; i < s.blocks.size(); ++i) {
    auto& r = res[std::size_t(s.blocks[i].resolution)];
    ++r.blocks;
    r.coded += s.index[i].passes > 0;
    r.bytes += s.index[i].length;
  }
  out << "  chunks      HEAD, " << (h.metadata.empty() ? "" : "META, ")
      << (h.nonfinite.empty() ? "" : "NFIN, ") << "INDX (" << s.blocks.size() << " code-blocks), DATA x "
      << res.size() << "\n";
  for (std::size_t r = 0; r < res.size(); ++r)
    out << "    DATA " << r << (r == 0 ? " (coarse band)" : "") << ": " << res[r].bytes << " bytes, "
        << res[r].coded << " of " << res[r].blocks << " blocks coded\n";
  return out.str();
}

}  // namespace pupwave
