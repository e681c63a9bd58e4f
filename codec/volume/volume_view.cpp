#include "codec/volume/volume_view.h"

#include "codec/volume/volume_missing.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace pupwave {
namespace {

// Calls f(T{}) with the C++ type of a storage.
template <class F>
decltype(auto) with_storage(VoxelType storage, F&& f) {
  switch (storage) {
    case VoxelType::u8: return f(std::uint8_t{});
    case VoxelType::u16: return f(std::uint16_t{});
    case VoxelType::f32: return f(float{});
    case VoxelType::f64: break;
  }
  return f(double{});
}

// Whether every value of `type` is exactly an element of `storage`.
bool holds(VoxelType storage, VoxelType type) {
  switch (storage) {
    case VoxelType::u8: return type == VoxelType::u8;
    case VoxelType::u16: return type == VoxelType::u8 || type == VoxelType::u16;
    case VoxelType::f32: return type != VoxelType::f64;
    case VoxelType::f64: return true;
  }
  return false;
}

}  // namespace

double VolumeView::at(std::size_t x, std::size_t y, std::size_t z) const {
  return with_storage(storage, [&](auto t) {
    using T = decltype(t);
    return double(static_cast<const T*>(data)[offset(x, y, z)]);
  });
}

void VolumeView::read_row(std::size_t x0, std::size_t y, std::size_t z, std::size_t n, double* out) const {
  with_storage(storage, [&](auto t) {
    using T = decltype(t);
    const T* row = static_cast<const T*>(data) + offset(x0, y, z);
    if (strides[0] == 1) {
      for (std::size_t x = 0; x < n; ++x) out[x] = double(row[x]);
    } else {
      for (std::size_t x = 0; x < n; ++x) out[x] = double(row[std::ptrdiff_t(x) * strides[0]]);
    }
  });
}

VolumeView contiguous_view(const void* data, const Extent& dims, VoxelType type) {
  VolumeView v;
  v.data = data;
  v.dims = dims;
  v.strides = {1, std::ptrdiff_t(dims[0]), std::ptrdiff_t(dims[0] * dims[1])};
  v.type = type;
  v.storage = type;
  return v;
}

VolumeView view_of(const Volume& volume) {
  if (volume.samples.size() != volume.count() ||
      (volume.is_sparse() && volume.active.size() != volume.count()))
    throw std::invalid_argument("volume sample or mask count does not match its dims");
  VolumeView v = contiguous_view(volume.samples.data(), volume.dims, VoxelType::f64);
  v.type = volume.type;
  v.active = volume.is_sparse() ? volume.active.data() : nullptr;
  v.background = volume.background;
  return v;
}

VolumeView sub_view(const VolumeView& view, const Extent& offset, const Extent& size) {
  for (int a = 0; a < 3; ++a)
    if (offset[a] + size[a] > view.dims[a]) throw std::invalid_argument("sub-box exceeds the view");
  VolumeView v = view;
  const std::ptrdiff_t at = view.offset(offset[0], offset[1], offset[2]);
  v.dims = size;
  with_storage(view.storage, [&](auto t) {
    using T = decltype(t);
    v.data = static_cast<const T*>(view.data) + at;
  });
  if (view.active != nullptr) v.active = view.active + at;
  return v;
}

void check_view(const VolumeView& view) {
  if (view.data == nullptr) throw std::invalid_argument("volume view has no data");
  for (std::size_t d : view.dims)
    if (d == 0) throw std::invalid_argument("volume view has an empty extent");
  if (!holds(view.storage, view.type))
    throw std::invalid_argument("volume view: " + to_string(view.storage) + " elements cannot hold " +
                                to_string(view.type) + " voxels");
  for (int a = 0; a < 3; ++a)
    if (view.dims[a] > 1 && view.strides[a] == 0)
      throw std::invalid_argument("volume view: zero stride along axis " + std::to_string(a));
}

template <class S>
bool sample_type_holds(VoxelType storage) {
  return with_storage(storage, [](auto t) {
    using T = decltype(t);
    if constexpr (std::is_same_v<S, double> || std::is_same_v<S, T>) return true;
    // float holds every u8 and u16 (24-bit significand); u16 holds every u8.
    return std::is_same_v<S, float> ? std::is_integral_v<T>
                                    : std::is_same_v<S, std::uint16_t> && sizeof(T) == 1;
  });
}

template <class S>
void gather_box(const VolumeView& view, const Extent& offset, const Extent& size, std::vector<S>& samples,
                std::vector<std::uint8_t>& active) {
  if (!sample_type_holds<S>(view.storage))
    throw std::invalid_argument("gather_box: samples cannot hold " + to_string(view.storage) + " elements");
  samples.resize(size[0] * size[1] * size[2]);
  active.clear();
  with_storage(view.storage, [&](auto t) {
    using T = decltype(t);
    // Only the pairs sample_type_holds accepts are instantiated (no narrowing conversion).
    if constexpr (std::is_same_v<S, double> || std::is_same_v<S, T> ||
                  (std::is_same_v<S, float> && std::is_integral_v<T>) ||
                  (std::is_same_v<S, std::uint16_t> && sizeof(T) == 1)) {
      std::size_t k = 0;
      for (std::size_t z = 0; z < size[2]; ++z)
        for (std::size_t y = 0; y < size[1]; ++y, k += size[0]) {
          const T* row =
              static_cast<const T*>(view.data) + view.offset(offset[0], offset[1] + y, offset[2] + z);
          S* out = samples.data() + k;
          if (view.strides[0] == 1) {
            for (std::size_t x = 0; x < size[0]; ++x) out[x] = S(row[x]);
          } else {
            for (std::size_t x = 0; x < size[0]; ++x) out[x] = S(row[std::ptrdiff_t(x) * view.strides[0]]);
          }
        }
    }
  });
  if (view.active == nullptr) return;
  active.reserve(samples.size());
  for (std::size_t z = 0; z < size[2]; ++z)
    for (std::size_t y = 0; y < size[1]; ++y)
      for (std::size_t x = 0; x < size[0]; ++x)
        active.push_back(view.active[view.offset(offset[0] + x, offset[1] + y, offset[2] + z)]);
}

template bool sample_type_holds<std::uint8_t>(VoxelType);
template bool sample_type_holds<std::uint16_t>(VoxelType);
template bool sample_type_holds<float>(VoxelType);
template bool sample_type_holds<double>(VoxelType);
template void gather_box(const VolumeView&, const Extent&, const Extent&, std::vector<std::uint8_t>&,
                         std::vector<std::uint8_t>&);
template void gather_box(const VolumeView&, const Extent&, const Extent&, std::vector<std::uint16_t>&,
                         std::vector<std::uint8_t>&);
template void gather_box(const VolumeView&, const Extent&, const Extent&, std::vector<float>&,
                         std::vector<std::uint8_t>&);
template void gather_box(const VolumeView&, const Extent&, const Extent&, std::vector<double>&,
                         std::vector<std::uint8_t>&);

namespace {

// Min, max and finiteness of a dense row of one storage type, in four interleaved chains (one
// chain per row waits on every previous comparison; four keep the core busy).
template <class T>
struct RowRange {
  T lo[4], hi[4];
  T nan_sum[4] = {T(0), T(0), T(0), T(0)};  // x - x is 0 for finite x, NaN otherwise
  RowRange() {                              // NaNs never enter lo and hi, as with std::min and std::max
    for (int k = 0; k < 4; ++k) {
      lo[k] = std::numeric_limits<T>::has_infinity ? std::numeric_limits<T>::infinity()
                                                   : std::numeric_limits<T>::max();
      hi[k] = std::numeric_limits<T>::has_infinity ? -std::numeric_limits<T>::infinity()
                                                   : std::numeric_limits<T>::lowest();
    }
  }
  void add(const T* row, std::size_t n) {
    std::size_t x = 0;
    for (; x + 4 <= n; x += 4)
      for (int k = 0; k < 4; ++k) take(k, row[x + std::size_t(k)]);
    for (; x < n; ++x) take(0, row[x]);
  }
  void take(int k, T v) {
    lo[k] = v < lo[k] ? v : lo[k];
    hi[k] = v > hi[k] ? v : hi[k];
    if constexpr (std::is_floating_point_v<T>) nan_sum[k] += v - v;
  }
  void finish(ValueSummary& s) const {
    for (int k = 0; k < 4; ++k) {
      s.lo = std::min(s.lo, double(lo[k]));
      s.hi = std::max(s.hi, double(hi[k]));
      s.finite = s.finite && nan_sum[k] == T(0);
    }
  }
};

}  // namespace

ValueSummary summarize_values(const VolumeView& view, const std::optional<double>& fill) {
  ValueSummary s;
  s.lo = std::numeric_limits<double>::infinity();
  s.hi = -s.lo;
  if (view.count() == 0) return s;
  if (view.active == nullptr && view.strides[0] == 1 && !fill) {  // the usual case: typed rows, no mask
    with_storage(view.storage, [&](auto t) {
      using T = decltype(t);
      const T* data = static_cast<const T*>(view.data);
      RowRange<T> r;
      for (std::size_t z = 0; z < view.dims[2]; ++z) {
        for (std::size_t y = 0; y < view.dims[1]; ++y) r.add(data + view.offset(0, y, z), view.dims[0]);
        view.drop(z, z + 1);
      }
      r.finish(s);
    });
    if (s.finite) {
      s.largest = std::max(std::fabs(s.lo), std::fabs(s.hi));
      return s;
    }
    s = ValueSummary{std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  }
  for_each_voxel(view, [&](double v, bool active) {  // missing values: a second, per-voxel pass
    s.finite = s.finite && std::isfinite(v);
    if (is_missing(v, fill)) {
      s.missing += active ? 1 : 0;
      return;
    }
    s.largest = std::max(s.largest, std::fabs(v));
    if (active) s.lo = std::min(s.lo, v), s.hi = std::max(s.hi, v);
  });
  view.drop(0, view.dims[2]);  // masked or strided views: at the end (the raw CLI input is neither)
  return s;
}

std::size_t active_count(const VolumeView& view) {
  if (view.active == nullptr) return view.count();
  std::size_t n = 0;
  for (std::size_t z = 0; z < view.dims[2]; ++z)
    for (std::size_t y = 0; y < view.dims[1]; ++y)
      for (std::size_t x = 0; x < view.dims[0]; ++x) n += view.active[view.offset(x, y, z)] != 0 ? 1 : 0;
  return n;
}

void VolumeOutput::set(std::size_t x, std::size_t y, std::size_t z, double value) const {
  with_storage(storage, [&](auto t) {
    using T = decltype(t);
    static_cast<T*>(data)[offset(x, y, z)] = T(value);
  });
}

void VolumeOutput::set_row(std::size_t x, std::size_t y, std::size_t z, const double* values,
                           std::size_t n) const {
  with_storage(storage, [&](auto t) {
    using T = decltype(t);
    T* row = static_cast<T*>(data) + offset(x, y, z);
    if (strides[0] == 1) {
      for (std::size_t i = 0; i < n; ++i) row[i] = T(values[i]);
    } else {
      for (std::size_t i = 0; i < n; ++i) row[std::ptrdiff_t(i) * strides[0]] = T(values[i]);
    }
  });
}

VolumeOutput contiguous_output(void* data, const Extent& dims, VoxelType storage) {
  VolumeOutput out;
  out.data = data;
  out.dims = dims;
  out.strides = {1, std::ptrdiff_t(dims[0]), std::ptrdiff_t(dims[0] * dims[1])};
  out.storage = storage;
  return out;
}

}  // namespace pupwave
