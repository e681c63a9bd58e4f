#include "codec/format/chunks.h"

#include <cstring>
#include <limits>
#include <stdexcept>

#include "codec/error.h"
#include "codec/format/byte_io.h"
#include "codec/format/crc32.h"

namespace pupwave {

bool Chunk::is(const ChunkTag& t) const { return std::memcmp(tag.data(), t, 4) == 0; }

void write_signature(std::vector<std::uint8_t>& out, const ChunkTag& magic, std::uint8_t version) {
  out.insert(out.end(), magic, magic + 4);
  out.push_back(version);
}

void write_chunk(std::vector<std::uint8_t>& out, const ChunkTag& tag, std::span<const std::uint8_t> payload) {
  if (payload.size() > std::numeric_limits<std::uint32_t>::max())
    throw EncodeError("chunk " + std::string(tag, 4) + " exceeds 4 GiB");
  const std::size_t start = out.size();
  ByteWriter w(out);
  w.bytes({reinterpret_cast<const std::uint8_t*>(tag), 4});
  w.u32(std::uint32_t(payload.size()));
  w.bytes(payload);
  w.u32(crc32(std::span<const std::uint8_t>(out).subspan(start)));
}

std::size_t begin_chunk(std::vector<std::uint8_t>& out, const ChunkTag& tag, std::size_t size) {
  if (size > std::numeric_limits<std::uint32_t>::max())
    throw EncodeError("chunk " + std::string(tag, 4) + " exceeds 4 GiB");
  const std::size_t start = out.size();
  ByteWriter w(out);
  w.bytes({reinterpret_cast<const std::uint8_t*>(tag), 4});
  w.u32(std::uint32_t(size));
  return start;
}

void end_chunk(std::vector<std::uint8_t>& out, std::size_t start) {
  std::uint32_t size = 0;
  for (int k = 0; k < 4; ++k) size |= std::uint32_t(out[start + 4 + std::size_t(k)]) << (8 * k);
  if (out.size() != start + 8 + size) throw std::logic_error("end_chunk: the payload is not the size begun");
  ByteWriter(out).u32(crc32(std::span<const std::uint8_t>(out).subspan(start)));
}

bool has_signature(std::span<const std::uint8_t> bytes, const ChunkTag& magic) {
  return bytes.size() >= 4 && std::memcmp(bytes.data(), magic, 4) == 0;
}

ChunkReader::ChunkReader(std::span<const std::uint8_t> bytes, const ChunkTag& magic, std::uint8_t version,
                         const char* what, std::uint8_t oldest)
    : bytes_(bytes), what_(what) {
  if (oldest == 0) oldest = version;
  require_stream(bytes.size() >= kSignatureBytes && has_signature(bytes, magic),
                 [&] { return std::string("not a pupwave ") + what + " (bad signature)"; });
  require_stream(bytes[4] >= oldest && bytes[4] <= version, [&] {
    return std::string(what) + ": unsupported version " + std::to_string(bytes[4]) + " (this build reads " +
           (oldest == version ? std::to_string(version)
                              : std::to_string(oldest) + " to " + std::to_string(version)) +
           ")";
  });
}

Chunk ChunkReader::next() {
  ByteReader r(bytes_.subspan(pos_), what_);
  Chunk c;
  std::memcpy(c.tag.data(), r.bytes(4).data(), 4);
  const std::uint32_t length = r.u32();
  c.payload = r.bytes(length);
  const std::uint32_t stored = r.u32();
#ifdef FUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION
  // Fuzzing builds only (docs/fuzzing.md): no CRC check, so mutations reach the parsers.
  static_cast<void>(stored);
#else
  require_stream(stored == crc32(bytes_.subspan(pos_, 8 + std::size_t(length))),
                 [&] { return std::string(what_) + ": checksum mismatch in chunk " + c.name(); });
#endif
  pos_ += r.position();
  return c;
}

Chunk ChunkReader::expect(const ChunkTag& tag) {
  require_stream(!at_end(), [&] { return std::string(what_) + ": missing chunk " + std::string(tag, 4); });
  const Chunk c = next();
  require_stream(c.is(tag), [&] {
    return std::string(what_) + ": expected chunk " + std::string(tag, 4) + ", found " + c.name();
  });
  return c;
}

}  // namespace pupwave
