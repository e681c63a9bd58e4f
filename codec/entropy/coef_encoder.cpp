#include "codec/entropy/coef_encoder.h"

#include <bit>
#include <stdexcept>

#include "codec/entropy/block_encoder.h"
#include "codec/entropy/coef_contexts.h"
#include "codec/entropy/coef_index.h"
#include "codec/entropy/range_encoder.h"

namespace pupwave {

CoefCodeword encode_coefficients(std::span<const std::uint32_t> index, std::span<const std::uint8_t> negative,
                                 const Extent& size) {
  if (index.size() != size[0] * size[1] * size[2] || negative.size() != index.size())
    throw std::invalid_argument("encode_coefficients: coefficient count does not match the block size");
  std::uint32_t all = 0;
  for (std::uint32_t q : index) all |= q;
  CoefCodeword out;
  out.bits = int(std::bit_width(all));
  if (out.bits > kCoefMaxBits)
    throw IndexRangeError("quantization index too large for the coefficient coder");
  if (out.bits == 0) return out;
  RangeEncoder enc;
  CoefModels models;
  CoefPlane plane(size);
  std::size_t i = 0;
  for (std::size_t z = 0; z < size[2]; ++z)
    for (std::size_t y = 0; y < size[1]; ++y) {
      std::size_t p = plane.at(0, y, z);
      for (std::size_t x = 0; x < size[0]; ++x, ++i, ++p) {
        const std::uint32_t q = index[i];
        const bool neg = negative[i] != 0;
        put_coef_index(enc, models, plane.context(p), plane.sign_context(p), q, neg);
        plane.set(p, q);
        plane.set_sign(p, q == 0 ? 0 : neg ? -1 : 1);
      }
    }
  out.bytes = enc.finish();
  return out;
}

}  // namespace pupwave
