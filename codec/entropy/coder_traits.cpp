#include "codec/entropy/coder_traits.h"

#include <algorithm>
#include <array>

namespace pupwave {
namespace {

constexpr std::array<CoderTraits, 4> kCoders{{
    //  coder               name     lossy  lossless embedded alone  whole bands
    {EntropyCoder::ebcot, "ebcot", true, true, true, true, false},
    {EntropyCoder::ht, "ht", true, true, false, true, false},
    {EntropyCoder::lc, "lc", false, true, false, false, true},
    {EntropyCoder::pc, "pc", true, false, false, false, true},
}};

// The row of the coder with this byte, or nullptr.
const CoderTraits* row_of(std::uint32_t byte) {
  const auto* row = std::find_if(kCoders.begin(), kCoders.end(),
                                 [byte](const CoderTraits& t) { return std::uint32_t(t.coder) == byte; });
  return row == kCoders.end() ? nullptr : row;
}

}  // namespace

const CoderTraits& coder_traits(EntropyCoder coder) { return *row_of(std::uint32_t(coder)); }

std::optional<EntropyCoder> coder_from_byte(std::uint32_t byte) {
  const CoderTraits* row = row_of(byte);
  if (row == nullptr) return std::nullopt;
  return row->coder;
}

const char* retired_coder_name(std::uint32_t byte) { return byte == 1 ? "zstd" : nullptr; }

const char* to_string(EntropyCoder coder) {
  const CoderTraits* row = row_of(std::uint32_t(coder));
  return row != nullptr ? row->name : "unknown";
}

}  // namespace pupwave
