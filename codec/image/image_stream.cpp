#include "codec/image/image_stream.h"

#include <cmath>
#include <cstring>
#include <sstream>
#include <stdexcept>

#include "codec/error.h"
#include "codec/format/byte_io.h"
#include "codec/format/chunks.h"
#include "codec/image/image_stream_extras.h"
#include "transforms/separable.h"
#include "transforms/spec.h"

namespace pupwave {
namespace {

constexpr ChunkTag kSignature = "PUPW";
constexpr int kMaxStreamLevels = 32;

std::vector<std::uint8_t> header_payload(const StreamHeader& h) {
  std::vector<std::uint8_t> p;
  ByteWriter w(p);
  for (std::size_t d : h.dims) w.u32(std::uint32_t(d));
  w.u8(h.channels);
  w.u8(std::uint8_t(h.type));
  w.u8(std::uint8_t(h.colour));
  w.u8(std::uint8_t(h.entropy));
  w.u8(h.reversible ? 1 : 0);
  w.u8(std::uint32_t(h.levels));
  for (std::size_t k : h.block_log2) w.u8(std::uint32_t(k));
  w.u16(std::uint32_t(std::lround(h.delta * 65536.0)));
  w.str16(h.spec);
  w.u32(std::uint32_t(h.steps.size()));
  for (float s : h.steps) w.f32(s);
  w.u8(std::uint8_t(h.transfer));
  w.u8(h.nonnegative ? 1 : 0);
  // Only log2_adaptive carries its offset, so streams of the other transfers parse as before.
  if (h.transfer == Transfer::log2_adaptive) w.u8(std::uint32_t(h.transfer_offset_log2 - kLogOffsetLog2));
  return p;
}

void validate_shape(const StreamHeader& h) {
  for (std::size_t d : h.dims)
    require_stream(d >= 1 && d <= kMaxAxisExtent,
                   [&] { return "dimension " + std::to_string(d) + " outside [1, 65536]"; });
  require_stream(h.channels >= 1 && h.channels <= kMaxChannels,
                 [&] { return "channel count " + std::to_string(h.channels); });
  require_stream(h.dims[0] * h.dims[1] * h.dims[2] * h.channels <= kMaxTotalSamples,
                 "image too large (over 2^31 samples)");
}

void validate_coding(const StreamHeader& h) {
  require_stream(h.colour == ColourTransform::none || h.channels >= 3, "colour transform needs 3 channels");
  require_stream(h.colour != ColourTransform::ict || !h.reversible, "ICT in a reversible stream");
  require_stream(h.colour != ColourTransform::rct || h.reversible, "RCT in an irreversible stream");
  require_stream(!h.reversible || is_integer(h.type), "reversible coding of float samples");
  const CoderTraits& coder = coder_traits(h.entropy);
  require_stream(coder.lossy || h.reversible,
                 [&] { return std::string(coder.name) + " coder in an irreversible stream"; });
  require_stream(coder.lossless || !h.reversible,
                 [&] { return std::string(coder.name) + " coder in a reversible stream"; });
  require_stream(h.transfer == Transfer::linear || !is_integer(h.type), "transfer on integer samples");
  require_stream(h.levels >= 0 && h.levels <= kMaxStreamLevels,
                 [&] { return "level count " + std::to_string(h.levels); });
  std::size_t block = 1;
  for (int a = 0; a < 3; ++a) {
    require_stream(h.block_log2[a] <= 10, "code-block extent");
    block <<= h.block_log2[a];
  }
  // Blocks of at least 1024 samples bound the index size by the image size.
  require_stream(block >= 1024 && block <= (std::size_t(1) << 20),
                 [&] { return "code-block size " + std::to_string(block); });
  require_stream(h.delta >= 0.0 && h.delta < 1.0, "reconstruction offset");
  for (float s : h.steps)
    require_stream(std::isfinite(s) && s > 0.0f && s < 1e30f && (!h.reversible || s == 1.0f),
                   "quantizer step");
}

StreamHeader parse_header(std::span<const std::uint8_t> payload) {
  ByteReader r(payload, "HEAD chunk");
  StreamHeader h;
  for (auto& d : h.dims) d = r.u32();
  h.channels = r.u8();
  validate_shape(h);
  const std::uint32_t type = r.u8(), colour = r.u8(), entropy = r.u8(), reversible = r.u8();
  if (const char* retired = retired_coder_name(entropy))
    throw DecodeError("entropy coder " + std::to_string(entropy) + " (" + retired +
                      ") is not supported: it was retired from the format and no decoder reads it");
  const auto coder = coder_from_byte(entropy);
  require_stream(type <= 3 && colour <= 2 && coder && reversible <= 1, "sample type, colour or coder field");
  h.type = SampleType(type);
  h.colour = ColourTransform(colour);
  h.entropy = *coder;
  h.reversible = reversible != 0;
  h.levels = int(r.u8());
  for (auto& k : h.block_log2) k = r.u8();
  h.delta = double(r.u16()) / 65536.0;
  h.spec = r.str16(kMaxSpecLength);
  const std::uint32_t step_count = r.u32();
  require_stream(step_count <= h.channels * (7u * kMaxStreamLevels + 1u), "step count");
  h.steps.resize(step_count);
  for (auto& s : h.steps) s = r.f32();
  const std::uint32_t transfer = r.u8(), nonnegative = r.u8();
  require_stream(transfer <= 2 && nonnegative <= 1, "transfer or flags field");
  h.transfer = Transfer(transfer);
  h.nonnegative = nonnegative != 0;
  if (h.transfer == Transfer::log2_adaptive) {
    h.transfer_offset_log2 = kLogOffsetLog2 + int(r.u8());
    require_stream(h.transfer_offset_log2 <= kMaxAdaptiveOffsetLog2, "transfer offset exponent");
  }
  require_stream(r.remaining() == 0, "HEAD chunk has trailing bytes");
  validate_coding(h);
  return h;
}

// Checks the transform spec (bounded, nothing designed: docs/bitstream.md, Decoder bounds)
// and returns the subbands it implies.
std::vector<Subband> header_bands(const StreamHeader& h) {
  try {
    check_stream_spec(h.spec);
  } catch (const std::invalid_argument& e) {
    throw DecodeError(std::string("corrupt or unsupported stream: transform spec: ") + e.what());
  }
  auto bands = subbands(h.dims, h.levels);
  require_stream(h.steps.size() == bands.size() * h.channels, "step count does not match the subbands");
  return bands;
}

// Blocks partition_blocks would make, counted without making them.
std::size_t block_count(const std::vector<Subband>& bands, std::size_t channels, const Extent& block) {
  std::size_t n = 0;
  for (const Subband& b : bands)
    n += ((b.size[0] + block[0] - 1) / block[0]) * ((b.size[1] + block[1] - 1) / block[1]) *
         ((b.size[2] + block[2] - 1) / block[2]);
  return n * channels;
}

// The bands of resolutions 0..last: a prefix of subbands() (coarse band first, then levels
// from coarsest to finest), so their blocks are the prefix of the full partition.
std::vector<Subband> bands_up_to(const std::vector<Subband>& bands, int levels, int last) {
  std::vector<Subband> kept;
  for (const Subband& b : bands)
    if (band_resolution(b, levels) <= last) kept.push_back(b);
  return kept;
}

// Offsets of every codeword in its DATA payload; the lengths of a resolution must add up to
// exactly its payload size.
void locate_codewords(ParsedStream& s) {
  std::vector<std::size_t> used(std::size_t(s.header.levels) + 1, 0);
  s.offsets.resize(s.blocks.size());
  for (std::size_t i = 0; i < s.blocks.size(); ++i) {
    const auto r = std::size_t(s.blocks[i].resolution);
    s.offsets[i] = used[r];
    used[r] += s.index[i].length;
  }
  for (std::size_t r = 0; r < s.resolution_data.size(); ++r)
    require_stream(used[r] == s.resolution_data[r].size(), [&] {
      return "DATA chunk " + std::to_string(r) + " size does not match its code-block lengths";
    });
}

}  // namespace

namespace {

// The signature and every chunk before the DATA payloads, in a buffer sized for the whole
// stream (grown by doubling, the last reallocation would hold up to three times the stream).
std::vector<std::uint8_t> container_head(const StreamHeader& header, std::span<const BlockEntry> index,
                                         std::size_t data_bytes) {
  const auto coded = encode_index(index);
  std::vector<std::uint8_t> out;
  out.reserve(container_size(header, coded.size(), data_bytes));
  write_signature(out, kSignature, kStreamVersion);
  write_chunk(out, "HEAD", header_payload(header));
  if (!header.metadata.empty()) write_chunk(out, "META", metadata_payload(header.metadata));
  if (!header.nonfinite.empty()) write_chunk(out, "NFIN", nonfinite_payload(header.nonfinite));
  std::vector<std::uint8_t> index_payload;
  index_payload.reserve(4 + coded.size());
  ByteWriter iw(index_payload);
  iw.u32(std::uint32_t(index.size()));
  iw.bytes(coded);
  write_chunk(out, "INDX", index_payload);
  return out;
}

}  // namespace

std::vector<std::uint8_t> write_container(const StreamHeader& header, std::span<const BlockEntry> index,
                                          const std::vector<std::vector<std::uint8_t>>& resolution_data) {
  std::size_t data_bytes = 0;
  for (const auto& data : resolution_data) data_bytes += data.size();
  auto out = container_head(header, index, data_bytes);
  for (const auto& data : resolution_data) write_chunk(out, "DATA", data);
  return out;
}

std::vector<std::uint8_t> write_container(const StreamHeader& header, std::span<const BlockEntry> index,
                                          std::span<const std::size_t> resolution_sizes,
                                          const PayloadWriter& append) {
  std::size_t data_bytes = 0;
  for (std::size_t size : resolution_sizes) data_bytes += size;
  auto out = container_head(header, index, data_bytes);
  for (std::size_t r = 0; r < resolution_sizes.size(); ++r) {
    const std::size_t start = begin_chunk(out, "DATA", resolution_sizes[r]);
    append(r, out);
    end_chunk(out, start);
  }
  return out;
}

std::size_t container_size(const StreamHeader& header, std::size_t index_bytes, std::size_t data_bytes) {
  const std::size_t chunks = 2 + std::size_t(header.levels) + 1;
  std::size_t extras = 0;
  if (!header.metadata.empty()) extras += kChunkOverhead + metadata_payload(header.metadata).size();
  if (!header.nonfinite.empty()) extras += kChunkOverhead + nonfinite_payload(header.nonfinite).size();
  return kSignatureBytes + chunks * kChunkOverhead + header_payload(header).size() + 4 + index_bytes +
         data_bytes + extras;
}

ParsedStream parse_container(std::span<const std::uint8_t> bytes, int drop_levels,
                             const DecodeLimits& limits) {
  ChunkReader chunks(bytes, kSignature, kStreamVersion, "image stream", kOldestStreamVersion);
  ParsedStream s;
  s.header = parse_header(chunks.expect("HEAD").payload);
  const StreamHeader& h = s.header;
  require_stream(chunks.version() == kStreamVersion || h.entropy != EntropyCoder::pc, [&] {
    return "image stream: version " + std::to_string(chunks.version()) +
           " with entropy coder 4 (pc), whose coding changed in version " + std::to_string(kStreamVersion) +
           ": decode it with the pupwave build that wrote it";
  });
  s.bands = header_bands(h);
  if (drop_levels < 0 || drop_levels > h.levels)
    throw std::invalid_argument(
        "level " + std::to_string(drop_levels) + " outside [0, " + std::to_string(h.levels) +
        "] (the stream's levels" +
        // The lossless default (lc) predicts samples without a wavelet: say how to get levels.
        (h.levels == 0 ? "; it was coded without wavelet levels, as lossless is by default: compress with "
                         "--levels N for reduced-resolution decoding)"
                       : ")"));
  const Extent out = level_extent(h.dims, drop_levels);
  check_decode_limit(out[0] * out[1] * out[2], limits, "pupwave stream: decoded size in pixels");
  const int resolutions = h.levels + 1;
  const int last = resolutions - 1 - drop_levels;
  require_stream(!chunks.at_end(), "pupwave stream: missing chunk INDX");
  Chunk next = chunks.next();
  if (next.is("META")) {
    s.header.metadata = parse_metadata(next.payload, s.header.channels);
    require_stream(!chunks.at_end(), "pupwave stream: missing chunk INDX");
    next = chunks.next();
  }
  if (next.is("NFIN")) {
    require_stream(!is_integer(s.header.type), "NFIN chunk in an integer stream");
    s.header.nonfinite = parse_nonfinite(next.payload, s.header);
    require_stream(!chunks.at_end(), "pupwave stream: missing chunk INDX");
    next = chunks.next();
  }
  require_stream(next.is("INDX"), [&] { return "expected chunk INDX, found " + next.name(); });
  // Only the blocks of the resolutions read are laid out and indexed: a reduced decode costs
  // memory in proportion to its output (the index is a prefix, ordered by resolution).
  const auto index_chunk = next.payload;
  ByteReader ir(index_chunk, "INDX chunk");
  require_stream(ir.u32() == block_count(s.bands, h.channels, h.block_size()),
                 "block count does not match the image geometry");
  s.blocks = partition_blocks(bands_up_to(s.bands, h.levels, last), h.levels, h.channels, h.block_size());
  s.index = decode_index(index_chunk.subspan(4), s.blocks.size());
  for (int r = 0; r <= last; ++r) s.resolution_data.push_back(chunks.expect("DATA").payload);
  if (last == resolutions - 1) require_stream(chunks.at_end(), "trailing bytes after the last chunk");
  locate_codewords(s);
  return s;
}

Transform1DPtr make_stream_transform(const StreamHeader& h) {
  try {
    auto t = make_transform(h.spec);
    require_stream(!h.reversible || t->is_reversible(),
                   [&] { return "transform " + h.spec + " is not reversible"; });
    return t;
  } catch (const std::invalid_argument& e) {
    throw DecodeError(std::string("corrupt or unsupported stream: transform spec: ") + e.what());
  }
}

}  // namespace pupwave
