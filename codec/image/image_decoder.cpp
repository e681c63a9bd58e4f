// decode_image: parse and validate the container, decode the code-blocks a resolution needs
// in parallel, dequantize, inverse wavelet transform (stopping early for reduced
// resolution), inverse colour transform.
#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>

#include "codec/entropy/block_decoder.h"
#include "codec/entropy/ht_blocks.h"
#include "codec/entropy/lc_blocks.h"
#include "codec/error.h"
#include "codec/image/image_codec.h"
#include "codec/image/image_components.h"
#include "codec/image/image_plan.h"
#include "codec/image/image_stream.h"
#include "codec/image/image_strips.h"
#include "codec/image/lc_parent.h"
#include "codec/image/pc_decoder.h"
#include "codec/image/transfer.h"
#include "transforms/separable.h"
#include "transforms/spec.h"

namespace pupwave {
namespace {

// Signed index-unit values of block i (reconstruction points inside their bins).
template <class T>
std::vector<T> block_values(const ParsedStream& s, std::size_t i) {
  const CodeBlock& b = s.blocks[i];
  const BlockEntry& e = s.index[i];
  const StreamHeader& h = s.header;
  std::vector<T> values(b.count(), T(0));
  if (e.passes == 0) return values;
  // lc and pc blocks read their parent band: their band decoders decode them, never one at a time here.
  if (!coder_traits(h.entropy).blocks_alone)
    throw std::logic_error(std::string(to_string(h.entropy)) + " blocks decode with their parent bands");
  if (h.entropy != EntropyCoder::ebcot) {
    std::vector<std::int32_t> q(b.count());
    ht_decode_block(s.codeword(i), b.size[0], b.size[1], e.planes, q.data());
    for (std::size_t k = 0; k < q.size(); ++k) {
      const double offset = (h.reversible || q[k] == 0) ? 0.0 : (q[k] < 0 ? -h.delta : h.delta);
      values[k] = T(double(q[k]) + offset);
    }
    return values;
  }
  const DecodedBlock d = decode_block(s.codeword(i), e.planes, e.passes, b.size, b.orientation);
  for (std::size_t k = 0; k < values.size(); ++k) values[k] = T(reconstruct(d, k, h.delta, h.reversible));
  return values;
}

// reconstruct()'s offset for every bit-plane a coefficient can end on (255: insignificant, 0),
// so the loop below needs no variable shift or branch per sample.
struct PlaneOffsets {
  double value[256];
  PlaneOffsets(double delta, bool exact) {
    for (unsigned p = 0; p < 256; ++p)
      value[p] = p == 255 || (exact && p == 0) ? 0.0 : delta * double(1u << (p < 32 ? p : 0));
  }
};

// Bit-plane block i reconstructed, dequantized and written straight into its place: row y of
// the block starts at first + y * stride. The same float value as reconstruct() times the
// step, sample for sample: |known| + offset rounded to float, the sign applied after (rounding
// is symmetric), zero where insignificant.
template <class T>
void dequantize_into(const ParsedStream& s, std::size_t i, T* first, std::size_t stride) {
  const CodeBlock& b = s.blocks[i];
  const BlockEntry& e = s.index[i];
  const StreamHeader& h = s.header;
  const DecodedBlock d = decode_block(s.codeword(i), e.planes, e.passes, b.size, b.orientation);
  const float step = h.steps[b.component * s.bands.size() + b.band];
  const PlaneOffsets offsets(h.delta, h.reversible);
  const std::int32_t* known = d.known.data();
  const std::uint8_t* plane = d.low_plane.data();
  for (std::size_t y = 0; y < b.size[1]; ++y, known += b.size[0], plane += b.size[0]) {
    T* row = first + y * stride;
    for (std::size_t x = 0; x < b.size[0]; ++x) {
      // Without branches (significance and sign are coin tosses): an insignificant sample
      // has known 0 and offset 0, so it comes out +0 as before; the sign goes on as a bit.
      const std::int32_t v = known[x];
      const float r = float(double(std::abs(std::int64_t(v))) + offsets.value[plane[x]]);
      const float signed_r =
          std::bit_cast<float>(std::bit_cast<std::uint32_t>(r) ^ (std::uint32_t(v) & 0x80000000u));
      row[x] = T(signed_r) * step;
    }
  }
}

// ht block i decoded, dequantized and written into its place (as dequantize_into).
template <class T>
void ht_dequantize_into(const ParsedStream& s, std::size_t i, T* first, std::size_t stride) {
  const CodeBlock& b = s.blocks[i];
  const StreamHeader& h = s.header;
  thread_local std::vector<std::int32_t> q;
  q.resize(b.count());
  ht_decode_block(s.codeword(i), b.size[0], b.size[1], s.index[i].planes, q.data());
  const float step = h.steps[b.component * s.bands.size() + b.band];
  const T delta = T(h.delta);
  for (std::size_t y = 0; y < b.size[1]; ++y) {
    T* row = first + y * stride;
    const std::int32_t* in = q.data() + y * b.size[0];
    for (std::size_t x = 0; x < b.size[0]; ++x) {
      const std::int32_t v = in[x];
      const T offset = v == 0 ? T(0) : (v < 0 ? -delta : delta);
      row[x] = (T(v) + offset) * step;
    }
  }
}

}  // namespace

template <class T>
void decode_block_at(const ParsedStream& s, std::size_t i, T* first, std::size_t stride) {
  const CodeBlock& b = s.blocks[i];
  if (s.index[i].passes == 0) {  // all zero
    for (std::size_t y = 0; y < b.size[1]; ++y) std::fill_n(first + y * stride, b.size[0], T(0));
    return;
  }
  if constexpr (std::is_floating_point_v<T>) {
    if (s.header.entropy == EntropyCoder::ebcot) return dequantize_into(s, i, first, stride);
    if (s.header.entropy == EntropyCoder::ht) return ht_dequantize_into(s, i, first, stride);
  }
  std::vector<T> values = block_values<T>(s, i);
  if constexpr (std::is_floating_point_v<T>) {
    const float step = s.header.steps[b.component * s.bands.size() + b.band];
    for (T& v : values) v *= step;
  }
  for (std::size_t y = 0; y < b.size[1]; ++y)
    std::copy_n(values.data() + y * b.size[0], b.size[0], first + y * stride);
}
template void decode_block_at<float>(const ParsedStream&, std::size_t, float*, std::size_t);
template void decode_block_at<std::int32_t>(const ParsedStream&, std::size_t, std::int32_t*, std::size_t);

namespace {

// decode_into for the lc coder: one resolution and component at a time (the blocks of each in
// parallel), so every block's parent band and guides (the first and the previous component)
// are decoded before the block.
void decode_lc_into(const ParsedStream& s, const Extent& region, const Executor& ex,
                    const std::vector<std::int32_t*>& planes) {
  const auto group = [&](std::size_t i) {
    return std::size_t(s.blocks[i].resolution) * 65 + s.blocks[i].component;
  };
  std::size_t first = 0;
  while (first < s.blocks.size()) {
    std::size_t end = first;
    while (end < s.blocks.size() && group(end) == group(first)) ++end;
    ex.run(end - first, [&](std::size_t k) {
      const std::size_t i = first + k;
      const CodeBlock& b = s.blocks[i];
      if (s.index[i].passes == 0) return;  // all zero: the planes start zeroed
      std::int32_t* plane = planes[b.component];
      lc_decode_block(s.codeword(i), b.size[0], b.size[1], b.orientation == 0,
                      lc_parent(s.bands, b, plane, region[0], planes[0],
                                b.component > 0 ? planes[b.component - 1] : nullptr),
                      s.index[i].planes, plane + b.offset[0] + region[0] * b.offset[1], region[0]);
    });
    first = end;
  }
}

// Decodes every block of the read resolutions into the component planes at planes[c] (each
// `region`-sized and zeroed: the low corner of the Mallat layout that holds those resolutions).
template <class T>
void decode_into(const ParsedStream& s, const Extent& region, const Executor& ex,
                 const std::vector<T*>& planes) {
  if constexpr (std::is_same_v<T, std::int32_t>)
    if (s.header.entropy == EntropyCoder::lc) return decode_lc_into(s, region, ex, planes);
  if constexpr (std::is_same_v<T, float>)
    if (s.header.entropy == EntropyCoder::pc) return decode_pc_into(s, region, ex, planes);
  ex.run(s.blocks.size(), [&](std::size_t i) {
    const CodeBlock& b = s.blocks[i];
    if (s.index[i].passes == 0) return;  // all zero: the planes start zeroed
    decode_block_at(s, i, planes[b.component] + b.offset[0] + region[0] * b.offset[1], region[0]);
  });
}

// Decodes every block of the read resolutions into `region`-sized component planes of type T.
template <class T>
std::vector<std::vector<T>> decode_planes(const ParsedStream& s, const Extent& region, const Executor& ex) {
  std::vector<std::vector<T>> planes(s.header.channels,
                                     std::vector<T>(region[0] * region[1] * region[2], T(0)));
  std::vector<T*> pointers;
  for (auto& p : planes) pointers.push_back(p.data());
  decode_into(s, region, ex, pointers);
  return planes;
}

// Full-resolution lossy decode straight into the output image's samples: the component
// planes are the image's planes, so no second full-size copy is made.
Image decode_full_float(const ParsedStream& s, const Transform1D& t, const Executor& ex) {
  const StreamHeader& h = s.header;
  Image out(h.dims[0], h.dims[1], h.channels, h.type);
  std::vector<float*> planes;
  for (std::size_t c = 0; c < h.channels; ++c) planes.push_back(out.plane(c));
  decode_into(s, h.dims, ex, planes);
  for (float* p : planes) inverse(t, p, h.dims, h.levels, 0, ex);
  finish_image_in_place(out, h.colour, ex);
  return out;
}

// The decoded image in sample units with what the stream keeps besides the samples: the
// inverse transfer and non-finite samples of float images, channel names, windows, attributes.
Image finish_decoded(Image image, const StreamHeader& h, int level) {
  if (!is_integer(h.type)) from_coded_domain(image, h, level == 0);
  image.metadata = decoded_metadata(h, level);
  return image;
}

Image decode_in_domain(const ParsedStream& s, int level, const Executor& ex) {
  const StreamHeader& h = s.header;
  require_stream(h.dims[2] == 1, "a volume stream, not an image");
  const auto t = make_stream_transform(h);
  const Extent size = level_extent(h.dims, level);
  const int levels = h.levels - level;
  if (h.reversible) {
    auto planes = decode_planes<std::int32_t>(s, size, ex);
    for (auto& p : planes) inverse(*t, p.data(), size, levels, 0, ex);
    return image_from_components(planes, size, size, h.type, h.colour);
  }
  if (level == 0) return decode_full_float(s, *t, ex);
  auto planes = decode_planes<float>(s, size, ex);
  for (auto& p : planes) inverse(*t, p.data(), size, levels, 0, ex);
  return image_from_components(planes, size, size, h.type, h.colour, coarse_gain(*t, h.dims, level));
}

}  // namespace

Image decode_image(std::span<const std::uint8_t> bytes, int level, const Executor& ex) {
  return decode_image(bytes, level, ex, DecodeLimits{});
}

// A reduced decode works on planes of the level's extent only: the resolutions it reads fill
// the low corner of the Mallat layout, whose inverse is that of a level-sized image with
// (levels - level) levels (the same lines in the same order, so the same samples).
Image decode_image(std::span<const std::uint8_t> bytes, int level, const Executor& ex,
                   const DecodeLimits& limits) {
  const ParsedStream s = parse_container(bytes, level, limits);
  return finish_decoded(decode_in_domain(s, level, ex), s.header, level);
}

double full_planes_psnr(const ImageView& image, const ParsedStream& s, const Executor& ex) {
  const StreamHeader& h = s.header;
  const auto t = make_transform(h.spec);
  if (h.reversible) {
    auto planes = decode_planes<std::int32_t>(s, h.dims, ex);
    for (auto& p : planes) inverse(*t, p.data(), h.dims, h.levels, 0, ex);
    return components_psnr(image, planes, h.colour);
  }
  auto planes = decode_planes<float>(s, h.dims, ex);
  for (auto& p : planes) inverse(*t, p.data(), h.dims, h.levels, 0, ex);
  return components_psnr(image, planes, h.colour, h.nonnegative);
}

// The encoder's check of a stream: decodes it at full resolution and compares it with the
// input without building the decoded image, by strips where the stream allows.
double measure_psnr(const ImageView& image, std::span<const std::uint8_t> bytes, const Executor& ex) {
  // The encoder's own stream: bounded by the image it was made from, not the decode limit.
  const ParsedStream s = parse_container(bytes, 0, DecodeLimits{SIZE_MAX});
  const StreamHeader& h = s.header;
  require_stream(h.dims[2] == 1, "a volume stream, not an image");
  if (h.dims[0] != image.width || h.dims[1] != image.height || h.channels != image.channels ||
      h.type != image.type)
    throw std::invalid_argument("measure_psnr: the stream does not hold an image of the reference's shape");
  if (const auto psnr = strip_psnr(image, s, ex)) return *psnr;
  return full_planes_psnr(image, s, ex);  // lc/pc blocks need whole parent bands: no strips
}

ImageMetadata decoded_metadata(const StreamHeader& h, int level) {
  ImageMetadata m = h.metadata;
  if (level > 0) {  // windows are those of the full-size image
    m.x = m.y = m.full_x = m.full_y = 0;
    m.full_width = m.full_height = 0;
  }
  return m;
}

}  // namespace pupwave
