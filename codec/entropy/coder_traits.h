#pragma once
// The block coders a stream may name (its HEAD's entropy byte) and what the container, the
// encoder and the decoders need to know of each: one row per coder in coder_traits.cpp, so a
// rule about coders reads a trait instead of listing coders.

#include <cstdint>
#include <optional>

namespace pupwave {

// ebcot: bit-plane (block_encoder.h); ht: high-throughput (ht_blocks.h); lc: lossless context
// coder (lc_blocks.h); pc: parent-context coefficient coder (pc_blocks.h). Byte 1 is retired
// (retired_coder_name): no coder takes it, so no stream can mean two things.
enum class EntropyCoder : std::uint8_t { ebcot = 0, ht = 2, lc = 3, pc = 4 };

struct CoderTraits {
  EntropyCoder coder;
  const char* name;   // as streams, `pupwave info` and --entropy name it
  bool lossy;         // codes quantised coefficients (irreversible streams)
  bool lossless;      // codes a reversible transform's integers (lossless streams)
  bool embedded;      // bit-plane passes the rate engine truncates (PCRD) rather than a step search
  bool blocks_alone;  // each block decodes on its own; false: after its parent band (no strip decoding)
  bool whole_bands;   // codes each band of up to 1024 x 1024 as one block (its models learn over it)
};

// The row of a coder.
const CoderTraits& coder_traits(EntropyCoder coder);
// The coder a stream's entropy byte names, or nullopt for a byte no coder has.
std::optional<EntropyCoder> coder_from_byte(std::uint32_t byte);
// The name of the retired coder an entropy byte named ("zstd" for 1), or nullptr for any other byte.
const char* retired_coder_name(std::uint32_t byte);
const char* to_string(EntropyCoder coder);

}  // namespace pupwave
