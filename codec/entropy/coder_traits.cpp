#include "codec/entropy/coder_traits.h"

#include <array>

namespace pupwave {
namespace {

// Indexed by the coder's byte.
constexpr std::array<CoderTraits, 5> kCoders{{
    //  coder               name     lossy  lossless embedded alone  whole bands
    {EntropyCoder::ebcot, "ebcot", true, true, true, true, false},
    {EntropyCoder::zstd, "zstd", true, true, false, true, false},
    {EntropyCoder::ht, "ht", true, true, false, true, false},
    {EntropyCoder::lc, "lc", false, true, false, false, true},
    {EntropyCoder::pc, "pc", true, false, false, false, true},
}};

}  // namespace

const CoderTraits& coder_traits(EntropyCoder coder) { return kCoders[std::size_t(coder)]; }

std::optional<EntropyCoder> coder_from_byte(std::uint32_t byte) {
  if (byte >= kCoders.size()) return std::nullopt;
  return kCoders[byte].coder;
}

const char* to_string(EntropyCoder coder) {
  const auto byte = std::size_t(coder);
  return byte < kCoders.size() ? kCoders[byte].name : "unknown";
}

}  // namespace pupwave
