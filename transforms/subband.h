#pragma once
// Geometry of the subbands of a separable Mallat decomposition, shared by engine and codec.

#include <array>
#include <cstddef>
#include <vector>

namespace pupwave {

// Dimensions of an array of up to 3 axes; axis 0 varies fastest (x, then y, then z).
// Unused axes have extent 1.
using Extent = std::array<std::size_t, 3>;

// One subband of an L-level decomposition stored in place (Mallat layout): the coarse band
// of each level occupies the low corner [0, coarse) of every axis it was split along.
struct Subband {
  int level = 0;             // 1 = finest details ... L; the final coarse band has level L
  unsigned orientation = 0;  // bit a set = high-pass along axis a; 0 = the coarse (LL/LLL) band
  Extent offset{0, 0, 0};    // first sample of the band in the in-place array
  Extent size{1, 1, 1};      // extent of the band
  std::size_t count() const { return size[0] * size[1] * size[2]; }
};

}  // namespace pupwave
