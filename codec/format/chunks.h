#pragma once
// The one chunk layer of every pupwave stream (images "PUPW", volumes "PUPV"): a 4-byte
// signature and a version byte, then chunks until the end of the stream, each framed as
//   tag (4 ASCII bytes) | length (u32 LE) | payload | CRC-32 of tag, length and payload.
// docs/bitstream.md describes the framing once; each stream kind defines its own chunks.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace pupwave {

// Bytes a chunk adds to its payload (tag, length, CRC).
inline constexpr std::size_t kChunkOverhead = 12;
// Bytes of the signature and version in front of the first chunk.
inline constexpr std::size_t kSignatureBytes = 5;

using ChunkTag = char[5];  // four characters and the literal's terminator: "HEAD"

// A chunk located in a stream whose CRC has been checked.
struct Chunk {
  std::array<char, 4> tag{};
  std::span<const std::uint8_t> payload;

  bool is(const ChunkTag& t) const;
  std::string name() const { return std::string(tag.begin(), tag.end()); }
};

// Appends the signature and version that open a stream.
void write_signature(std::vector<std::uint8_t>& out, const ChunkTag& magic, std::uint8_t version);

// Appends one framed chunk. Throws EncodeError for a payload of 4 GiB or more.
void write_chunk(std::vector<std::uint8_t>& out, const ChunkTag& tag, std::span<const std::uint8_t> payload);

// One framed chunk written in place, for payloads too large to hold twice: begin_chunk
// appends the tag and length, the caller then appends exactly `size` payload bytes, and
// end_chunk (given begin_chunk's result) appends the CRC. Throws EncodeError as write_chunk.
std::size_t begin_chunk(std::vector<std::uint8_t>& out, const ChunkTag& tag, std::size_t size);
void end_chunk(std::vector<std::uint8_t>& out, std::size_t start);

// True when bytes start with `magic` (the version and chunks are not looked at).
bool has_signature(std::span<const std::uint8_t> bytes, const ChunkTag& magic);

// Reads the chunks of a stream in order, checking each CRC before handing out its payload.
// Every failure throws DecodeError naming the stream kind (`what`, a string literal).
class ChunkReader {
 public:
  // Checks the signature and that the version byte is in [oldest, version] (oldest defaults to
  // version: only streams whose syntax is unchanged since `oldest` may widen the range).
  ChunkReader(std::span<const std::uint8_t> bytes, const ChunkTag& magic, std::uint8_t version,
              const char* what, std::uint8_t oldest = 0);

  bool at_end() const { return pos_ == bytes_.size(); }
  std::size_t position() const { return pos_; }
  Chunk next();
  // next(), which must carry `tag`.
  Chunk expect(const ChunkTag& tag);
  // The stream's version byte.
  std::uint8_t version() const { return bytes_[4]; }

 private:
  std::span<const std::uint8_t> bytes_;
  const char* what_;
  std::size_t pos_ = kSignatureBytes;
};

}  // namespace pupwave
