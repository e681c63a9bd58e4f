#include "codec/volume/volume_missing.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>

namespace pupwave {
namespace {

// Sweeps of the 6-neighbour mean over missing voxels after the pull-push fill: they round off
// the steps the piecewise-constant push leaves at cell edges near the valid voxels.
constexpr int kSmoothingSweeps = 6;

struct Level {
  Extent dims{0, 0, 0};
  std::vector<double> value;
  std::vector<std::uint8_t> known;
  std::size_t index(std::size_t x, std::size_t y, std::size_t z) const {
    return x + dims[0] * (y + dims[1] * z);
  }
};

// The next coarser level: each cell the mean of its known children, known when any child is.
Level pull(const Level& fine) {
  Level c;
  for (std::size_t a = 0; a < 3; ++a) c.dims[a] = (fine.dims[a] + 1) / 2;
  const std::size_t n = c.dims[0] * c.dims[1] * c.dims[2];
  c.value.assign(n, 0.0);
  c.known.assign(n, 0);
  std::vector<std::uint32_t> count(n, 0);
  for (std::size_t z = 0; z < fine.dims[2]; ++z)
    for (std::size_t y = 0; y < fine.dims[1]; ++y)
      for (std::size_t x = 0; x < fine.dims[0]; ++x) {
        const std::size_t i = fine.index(x, y, z);
        if (!fine.known[i]) continue;
        const std::size_t k = c.index(x / 2, y / 2, z / 2);
        c.value[k] += fine.value[i];
        ++count[k];
      }
  for (std::size_t k = 0; k < n; ++k)
    if (count[k] > 0) c.value[k] /= double(count[k]), c.known[k] = 1;
  return c;
}

// Unknown cells of `fine` take their parent's value.
void push(Level& fine, const Level& coarse) {
  for (std::size_t z = 0; z < fine.dims[2]; ++z)
    for (std::size_t y = 0; y < fine.dims[1]; ++y)
      for (std::size_t x = 0; x < fine.dims[0]; ++x) {
        const std::size_t i = fine.index(x, y, z);
        if (!fine.known[i]) fine.value[i] = coarse.value[coarse.index(x / 2, y / 2, z / 2)];
      }
}

// Gauss-Seidel sweeps of the 6-neighbour mean over the voxels not originally known.
void smooth(Level& l, const std::vector<std::uint8_t>& known) {
  const Extent& d = l.dims;
  const std::ptrdiff_t sx = 1, sy = std::ptrdiff_t(d[0]), sz = std::ptrdiff_t(d[0] * d[1]);
  for (int sweep = 0; sweep < kSmoothingSweeps; ++sweep)
    for (std::size_t z = 0; z < d[2]; ++z)
      for (std::size_t y = 0; y < d[1]; ++y)
        for (std::size_t x = 0; x < d[0]; ++x) {
          const std::size_t i = l.index(x, y, z);
          if (known[i]) continue;
          double sum = 0.0;
          int n = 0;
          const auto add = [&](bool inside, std::ptrdiff_t step) {
            if (inside) sum += l.value[std::size_t(std::ptrdiff_t(i) + step)], ++n;
          };
          add(x > 0, -sx), add(x + 1 < d[0], sx);
          add(y > 0, -sy), add(y + 1 < d[1], sy);
          add(z > 0, -sz), add(z + 1 < d[2], sz);
          if (n > 0) l.value[i] = sum / n;
        }
}

template <class S>
S stored_as(double v) {
  if constexpr (std::is_integral_v<S>) {
    const double top = double(std::numeric_limits<S>::max());
    return S(std::clamp(std::round(v), 0.0, top));
  } else {
    return S(v);
  }
}

}  // namespace

const std::uint8_t* missing_value_mask(const VolumeView& view, const std::optional<double>& fill,
                                       std::vector<std::uint8_t>& bytes) {
  std::ptrdiff_t lo = 0, hi = 0;  // the element offsets the view spans
  for (std::size_t a = 0; a < 3; ++a) {
    const std::ptrdiff_t end = std::ptrdiff_t(view.dims[a] - 1) * view.strides[a];
    lo += std::min<std::ptrdiff_t>(end, 0), hi += std::max<std::ptrdiff_t>(end, 0);
  }
  bytes.assign(std::size_t(hi - lo + 1), 0);
  std::uint8_t* mask = bytes.data() - lo;
  std::vector<double> row(view.dims[0]);
  for (std::size_t z = 0; z < view.dims[2]; ++z)
    for (std::size_t y = 0; y < view.dims[1]; ++y) {
      view.read_row(0, y, z, view.dims[0], row.data());
      for (std::size_t x = 0; x < view.dims[0]; ++x)
        mask[view.offset(x, y, z)] = is_missing(row[x], fill) ? 0 : 1;
    }
  return mask;
}

template <class S>
void fill_missing(std::vector<S>& samples, const std::vector<std::uint8_t>& active, const Extent& size) {
  std::vector<Level> pyramid(1);
  Level& base = pyramid[0];
  base.dims = size;
  base.value.assign(samples.size(), 0.0);
  base.known.assign(active.begin(), active.end());
  for (std::size_t i = 0; i < samples.size(); ++i)
    if (base.known[i]) base.value[i] = double(samples[i]);
  while (pyramid.back().dims[0] * pyramid.back().dims[1] * pyramid.back().dims[2] > 1)
    pyramid.push_back(pull(pyramid.back()));
  for (std::size_t k = pyramid.size() - 1; k-- > 0;) push(pyramid[k], pyramid[k + 1]);
  smooth(pyramid[0], active);
  for (std::size_t i = 0; i < samples.size(); ++i)
    if (!active[i]) samples[i] = stored_as<S>(pyramid[0].value[i]);
}

template void fill_missing(std::vector<std::uint8_t>&, const std::vector<std::uint8_t>&, const Extent&);
template void fill_missing(std::vector<std::uint16_t>&, const std::vector<std::uint8_t>&, const Extent&);
template void fill_missing(std::vector<float>&, const std::vector<std::uint8_t>&, const Extent&);
template void fill_missing(std::vector<double>&, const std::vector<std::uint8_t>&, const Extent&);

}  // namespace pupwave
