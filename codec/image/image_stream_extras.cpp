#include "codec/image/image_stream_extras.h"

#include <cmath>
#include <cstring>

#include "codec/error.h"
#include "codec/format/byte_io.h"

namespace pupwave {
namespace {

void put_i32(ByteWriter& w, std::int32_t v) { w.u32(std::uint32_t(v)); }
std::int32_t get_i32(ByteReader& r) { return std::int32_t(r.u32()); }

void put_u64(ByteWriter& w, std::uint64_t v) {
  w.u32(std::uint32_t(v));
  w.u32(std::uint32_t(v >> 32));
}
std::uint64_t get_u64(ByteReader& r) {
  const std::uint64_t lo = r.u32();
  return lo | (std::uint64_t(r.u32()) << 32);
}

void put_f64(ByteWriter& w, double v) {
  std::uint64_t bits = 0;
  std::memcpy(&bits, &v, 8);
  put_u64(w, bits);
}
double get_f64(ByteReader& r) {
  const std::uint64_t bits = get_u64(r);
  double v = 0.0;
  std::memcpy(&v, &bits, 8);
  return v;
}

// Strings longer than a u16 length (attribute values only) are cut; names are bounded on read.
std::string clipped(const std::string& s) { return s.size() <= 65535 ? s : s.substr(0, 65535); }

float bits_to_float(std::uint32_t bits) {
  float v = 0.0f;
  std::memcpy(&v, &bits, 4);
  return v;
}

}  // namespace

std::vector<std::uint8_t> metadata_payload(const ImageMetadata& m) {
  std::vector<std::uint8_t> p;
  ByteWriter w(p);
  w.u8(std::uint32_t(m.channel_names.size()));
  for (const auto& n : m.channel_names) w.str16(clipped(n));
  put_i32(w, m.x);
  put_i32(w, m.y);
  put_i32(w, m.full_x);
  put_i32(w, m.full_y);
  w.u32(m.full_width);
  w.u32(m.full_height);
  w.u32(std::uint32_t(std::min(m.attributes.size(), kMaxAttributes)));
  for (std::size_t i = 0; i < m.attributes.size() && i < kMaxAttributes; ++i) {
    const ImageAttribute& a = m.attributes[i];
    w.str16(clipped(a.name));
    w.u8(std::uint32_t(a.kind));
    switch (a.kind) {
      case ImageAttribute::Kind::string: w.str16(clipped(a.text)); break;
      case ImageAttribute::Kind::integer: put_u64(w, std::uint64_t(a.integer)); break;
      case ImageAttribute::Kind::real: put_f64(w, a.real); break;
    }
  }
  return p;
}

ImageMetadata parse_metadata(std::span<const std::uint8_t> payload, std::uint32_t channels) {
  ByteReader r(payload, "META chunk");
  ImageMetadata m;
  const std::uint32_t names = r.u8();
  require_stream(names == 0 || names == channels, "META chunk: channel name count");
  for (std::uint32_t c = 0; c < names; ++c) m.channel_names.push_back(r.str16(kMaxNameLength));
  m.x = get_i32(r);
  m.y = get_i32(r);
  m.full_x = get_i32(r);
  m.full_y = get_i32(r);
  m.full_width = r.u32();
  m.full_height = r.u32();
  const std::uint32_t count = r.u32();
  require_stream(count <= kMaxAttributes, "META chunk: attribute count");
  for (std::uint32_t i = 0; i < count; ++i) {
    ImageAttribute a;
    a.name = r.str16(kMaxNameLength);
    const std::uint32_t kind = r.u8();
    require_stream(kind <= 2, "META chunk: attribute kind");
    a.kind = ImageAttribute::Kind(kind);
    if (a.kind == ImageAttribute::Kind::string) a.text = r.str16(65535);
    if (a.kind == ImageAttribute::Kind::integer) a.integer = std::int64_t(get_u64(r));
    if (a.kind == ImageAttribute::Kind::real) a.real = get_f64(r);
    m.attributes.push_back(std::move(a));
  }
  require_stream(r.remaining() == 0, "META chunk has trailing bytes");
  return m;
}

std::vector<std::uint8_t> nonfinite_payload(const std::vector<NonFiniteSample>& list) {
  std::vector<std::uint8_t> p;
  ByteWriter w(p);
  put_u64(w, list.size());
  for (const auto& s : list) {
    w.u8(s.channel);
    put_u64(w, s.index);
    w.u32(s.bits);
  }
  return p;
}

std::vector<NonFiniteSample> parse_nonfinite(std::span<const std::uint8_t> payload, const StreamHeader& h) {
  ByteReader r(payload, "NFIN chunk");
  const std::uint64_t count = get_u64(r);
  constexpr std::size_t kEntryBytes = 13;
  require_stream(count <= r.remaining() / kEntryBytes, "NFIN chunk truncated");
  const std::uint64_t plane = std::uint64_t(h.dims[0]) * h.dims[1] * h.dims[2];
  std::vector<NonFiniteSample> list(count);
  for (std::size_t i = 0; i < list.size(); ++i) {
    NonFiniteSample& s = list[i];
    s.channel = r.u8();
    s.index = get_u64(r);
    s.bits = r.u32();
    require_stream(s.channel < h.channels && s.index < plane, "NFIN chunk: sample outside the image");
    require_stream(!std::isfinite(bits_to_float(s.bits)), "NFIN chunk: finite value");
    const bool ordered =
        i == 0 || std::pair(list[i - 1].channel, list[i - 1].index) < std::pair(s.channel, s.index);
    require_stream(ordered, "NFIN chunk: entries out of order");
  }
  require_stream(r.remaining() == 0, "NFIN chunk has trailing bytes");
  return list;
}

}  // namespace pupwave
