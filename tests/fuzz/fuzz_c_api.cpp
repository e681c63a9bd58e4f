// fuzz_c_api: the C API's decode entry points (codec/api/api_c.cpp), which the Python binding
// and the numcodecs codec reach too. The first byte picks the level (bits 0-1) and, for volume
// streams, whether pupwave_decompress_volume_into is called as well (bit 2); the rest is the
// stream. The C API takes no decode limit, so streams whose header is over the fuzzers' limit
// are skipped (checked with the codec's own parsers first). Invariants: no call returns
// PUPWAVE_ERROR_INTERNAL (the API's "a bug"); a failure has a message; a decoded image or
// volume has the level's extent of the described dims and the bytes they imply; decoding twice
// gives the same bytes; decoding into a buffer gives the same bytes as decoding.
#include <cstring>
#include <string>
#include <vector>

#include "codec/error.h"
#include "codec/format/chunks.h"
#include "codec/image/image_stream.h"
#include "codec/volume/volume_format.h"
#include "fuzz_check.h"
#include "pupwave/pupwave.h"
#include "transforms/separable.h"

using namespace pupwave;

namespace {

// Whether the stream's header is within the fuzzers' decode limit (and parses at all).
bool within_limit(std::span<const std::uint8_t> bytes, int level) {
  try {
    if (has_signature(bytes, kVolumeSignature)) return (parse_volume_stream(bytes, fuzz::kFuzzLimits), true);
    return (parse_container(bytes, level, fuzz::kFuzzLimits), true);
  } catch (const DecodeError&) {
    return false;
  } catch (const std::invalid_argument&) {
    return false;
  }
}

void check_status(pupwave_status s) {
  FUZZ_CHECK(s != PUPWAVE_ERROR_INTERNAL);
  FUZZ_CHECK(s == PUPWAVE_OK || std::string(pupwave_last_error()).size() > 0);
}

std::vector<std::uint8_t> bytes_of(const pupwave_decoded* d) {
  const auto* p = static_cast<const std::uint8_t*>(pupwave_decoded_data(d));
  return {p, p + pupwave_decoded_size(d)};
}

std::size_t type_bytes(pupwave_type t) {
  switch (t) {
    case PUPWAVE_U8: return 1;
    case PUPWAVE_U16: return 2;
    case PUPWAVE_F16: return 2;
    case PUPWAVE_F32: return 4;
    case PUPWAVE_F64: return 8;
  }
  return 0;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const int level = data[0] & 3;
  const bool into = (data[0] & 4) != 0;
  const auto bytes = fuzz::as_span(data + 1, size - 1);
  if (!within_limit(bytes, level)) return 0;
  int kind = -1, levels = 0;
  std::size_t dims[3] = {0, 0, 0};
  pupwave_type type = PUPWAVE_U8;
  const pupwave_status described =
      pupwave_describe_dims(bytes.data(), bytes.size(), &kind, dims, &type, &levels);
  check_status(described);
  if (described != PUPWAVE_OK) return 0;
  pupwave_decoded* first = nullptr;
  const pupwave_status s = kind == 1 ? pupwave_decompress_volume(bytes.data(), bytes.size(), level, 1, &first)
                                     : pupwave_decompress_image(bytes.data(), bytes.size(), level, 1, &first);
  check_status(s);
  if (s != PUPWAVE_OK) return 0;
  const Extent e = level_extent({dims[0], dims[1], dims[2]}, level);
  std::size_t count = pupwave_decoded_channels(first) > 0 ? pupwave_decoded_channels(first) : 1;
  for (int a = 0; a < 3; ++a) {
    FUZZ_CHECK(pupwave_decoded_dim(first, a) == e[std::size_t(a)]);
    count *= e[std::size_t(a)];
  }
  FUZZ_CHECK(pupwave_decoded_size(first) == count * type_bytes(pupwave_decoded_type(first)));
  const std::vector<std::uint8_t> decoded = bytes_of(first);
  pupwave_decoded_destroy(first);
  pupwave_decoded* again = nullptr;
  FUZZ_CHECK((kind == 1
                  ? pupwave_decompress_volume(bytes.data(), bytes.size(), level, 2, &again)
                  : pupwave_decompress_image(bytes.data(), bytes.size(), level, 2, &again)) == PUPWAVE_OK);
  FUZZ_CHECK(bytes_of(again) == decoded);
  pupwave_decoded_destroy(again);
  if (kind == 1 && into && !decoded.empty()) {
    std::vector<std::uint8_t> buffer(decoded.size());
    FUZZ_CHECK(pupwave_decompress_volume_into(bytes.data(), bytes.size(), level, 1, buffer.data(),
                                              buffer.size()) == PUPWAVE_OK);
    FUZZ_CHECK(buffer == decoded);
    // A buffer of the wrong size is refused, never written past.
    check_status(pupwave_decompress_volume_into(bytes.data(), bytes.size(), level, 1, buffer.data(),
                                                buffer.size() - 1));
  }
  return 0;
}
