#include "codec/entropy/coef_decoder.h"

#include <bit>

#include "codec/entropy/coef_contexts.h"
#include "codec/entropy/coef_index.h"
#include "codec/entropy/range_decoder.h"
#include "codec/error.h"

namespace pupwave {

void decode_coefficients(std::span<const std::uint8_t> codeword, int bits, const Extent& size,
                         std::span<std::int32_t> out) {
  require_stream(bits >= 1 && bits <= kCoefMaxBits, "coefficient coder: index bit width out of range");
  require_stream(out.size() == size[0] * size[1] * size[2], "coefficient coder: block size");
  const std::uint64_t limit = (std::uint64_t(1) << bits) - 1;
  RangeDecoder dec(codeword);
  CoefModels models;
  CoefPlane plane(size);
  std::size_t i = 0;
  for (std::size_t z = 0; z < size[2]; ++z)
    for (std::size_t y = 0; y < size[1]; ++y) {
      std::size_t p = plane.at(0, y, z);
      for (std::size_t x = 0; x < size[0]; ++x, ++i, ++p) {
        bool negative = false;
        const std::uint32_t q =
            get_coef_index(dec, models, plane.context(p), plane.sign_context(p), limit, negative);
        const std::int32_t v = negative ? -std::int32_t(q) : std::int32_t(q);
        out[i] = v;
        plane.set(p, q);
        plane.set_sign(p, v == 0 ? 0 : v < 0 ? -1 : 1);
      }
    }
}

}  // namespace pupwave
