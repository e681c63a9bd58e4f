// The image coders' names, shared by the C++ and C APIs, Python and the CLI.
#include "codec/api/api_coder.h"

#include <algorithm>
#include <array>
#include <cctype>

#include "codec/api/api_errors.h"

namespace pupwave::api {
namespace {

struct CoderRow {
  Coder coder;
  std::optional<EntropyCoder> entropy;  // nullopt: the default choice
};

// One row per coder, in the order of enum Coder (and of the C API's PUPWAVE_CODER_*); the names
// are the stream's (codec/entropy/coder_traits.h), and "auto" for the default choice.
constexpr std::array<CoderRow, 5> kCoders{{
    {Coder::automatic, std::nullopt},
    {Coder::ebcot, EntropyCoder::ebcot},
    {Coder::pc, EntropyCoder::pc},
    {Coder::lc, EntropyCoder::lc},
    {Coder::ht, EntropyCoder::ht},
}};

const CoderRow& row(Coder coder) {
  const auto i = std::size_t(coder);
  if (i >= kCoders.size()) detail::fail("unknown entropy coder " + std::to_string(i));
  return kCoders[i];
}

std::string_view name_of(const CoderRow& r) { return r.entropy ? to_string(*r.entropy) : "auto"; }

bool same_name(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
         });
}

}  // namespace

std::string_view coder_name(Coder coder) { return name_of(row(coder)); }

std::optional<Coder> coder_from_name(std::string_view name) {
  for (const CoderRow& r : kCoders)
    if (same_name(name_of(r), name)) return r.coder;
  return std::nullopt;
}

std::string coder_names() {
  std::string names;
  for (const CoderRow& r : kCoders) names += (names.empty() ? "" : ", ") + std::string(name_of(r));
  return names;
}

std::optional<EntropyCoder> entropy_coder(Coder coder) { return row(coder).entropy; }

}  // namespace pupwave::api
