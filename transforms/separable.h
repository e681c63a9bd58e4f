#pragma once
// Separable N-D wavelet engine: any Transform1D along each axis of a 1-D, 2-D or 3-D array,
// Mallat style (the coarse band is transformed again at the next level), in place.
//
// Layout: samples are stored with axis 0 contiguous, then axis 1, then axis 2
// (index = x + dims[0] * (y + dims[1] * z)). Level l (1-based) splits every axis whose
// level-(l-1) coarse extent is > 1 into ceil(m/2) coarse | floor(m/2) detail samples, within
// the low corner holding the level-(l-1) coarse band. Axes of extent 1 are never transformed.
// Forward processes axes 0, 1, 2 per level; inverse undoes them in reverse order (needed for
// bit-exact integer 5/3, whose rounding does not commute between axes).
// Lines run as tasks of the executor passed in (serial unless the caller gives one); results
// do not depend on the executor or its thread count.

#include <cstdint>
#include <vector>

#include "transforms/executor.h"
#include "transforms/subband.h"
#include "transforms/transform1d.h"

namespace pupwave {

// Most levels any engine function accepts (enough to reduce any 64-bit extent to 1).
inline constexpr int kMaxLevels = 64;

// Default number of levels: add levels until the coarse band is under 16 samples along its
// shortest transformed axis (extent > 1), at most 8, at least 1; 0 when all extents are 1.
int default_levels(const Extent& dims);

// Extent of the coarse band after `level` levels (level 0 = dims); each axis of extent > 1 is
// ceil-halved per level. Throws std::invalid_argument for level outside [0, kMaxLevels].
Extent level_extent(const Extent& dims, int level);

// Subbands of a `levels`-level decomposition: the coarse band first (level = levels,
// orientation 0), then the detail bands of level `levels` down to 1, orientations ascending.
// A level has one band per non-empty subset of the axes it splits (so no band is empty); the
// bands tile the array exactly.
std::vector<Subband> subbands(const Extent& dims, int levels);

// In-place forward transform of data (dims[0] * dims[1] * dims[2] samples), `levels` levels.
// T is float, double or int32_t; int32_t needs t.is_reversible() (else std::logic_error).
// Throws std::invalid_argument for a null pointer, a zero extent or levels outside
// [0, kMaxLevels].
template <class T>
void forward(const Transform1D& t, T* data, const Extent& dims, int levels,
             const Executor& ex = serial_executor());

// In-place inverse of forward with the same t, dims and levels. stop_level k > 0 undoes only
// levels `levels`..k+1, leaving the level-k coarse band (extent level_extent(dims, k))
// reconstructed in the low corner, for reduced-resolution decoding; samples outside that
// corner are left as they are. Requires 0 <= stop_level <= levels.
template <class T>
void inverse(const Transform1D& t, T* data, const Extent& dims, int levels, int stop_level = 0,
             const Executor& ex = serial_executor());

}  // namespace pupwave
