#include "tools/volume_io.h"

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "tools/atomic_file.h"
#include "tools/vdb_module.h"

namespace pupwave::cli {
namespace fs = std::filesystem;

// ---------------------------------------------------------------------------------------------
// Raw volumes

Extent parse_dims(std::string_view text) {
  Extent dims{1, 1, 1};
  std::size_t axis = 0;
  std::string_view rest = text;
  while (true) {
    const std::size_t comma = rest.find(',');
    const std::string_view field = rest.substr(0, comma);
    std::size_t value = 0;
    const auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), value);
    if (axis >= 3 || field.empty() || ec != std::errc() || end != field.data() + field.size() || value == 0)
      throw std::invalid_argument("invalid --dims '" + std::string(text) +
                                  "' (expected X,Y,Z with positive integers)");
    dims[axis++] = value;
    if (comma == std::string_view::npos) break;
    rest = rest.substr(comma + 1);
  }
  return dims;
}

// Byte order of raw files is little endian; swap on big-endian hosts.
template <class U>
U to_little_endian(U v) {
  if constexpr (std::endian::native == std::endian::big) {
    U r = 0;
    for (std::size_t i = 0; i < sizeof(U); ++i) r = static_cast<U>((r << 8) | ((v >> (8 * i)) & 0xFF));
    return r;
  }
  return v;
}

template <class T, class U>
void decode_samples(const std::uint8_t* bytes, std::vector<double>& out) {
  static_assert(sizeof(T) == sizeof(U));
  for (std::size_t i = 0; i < out.size(); ++i) {
    U raw;
    std::memcpy(&raw, bytes + i * sizeof(U), sizeof(U));
    raw = to_little_endian(raw);
    T value;
    std::memcpy(&value, &raw, sizeof(T));
    out[i] = static_cast<double>(value);
  }
}

template <class T, class U>
void encode_samples(const std::vector<double>& in, std::uint8_t* bytes) {
  for (std::size_t i = 0; i < in.size(); ++i) {
    T value;
    if constexpr (std::is_integral_v<T>) {
      const double v = std::isnan(in[i]) ? 0.0 : in[i];
      value = static_cast<T>(std::clamp(std::round(v), 0.0, double(std::numeric_limits<T>::max())));
    } else {
      value = static_cast<T>(in[i]);
    }
    U raw;
    std::memcpy(&raw, &value, sizeof(U));
    raw = to_little_endian(raw);
    std::memcpy(bytes + i * sizeof(U), &raw, sizeof(U));
  }
}

// Voxel count of dims, or 0 when the product does not fit (treated as absurd by callers).
static std::size_t checked_count(const Extent& dims) {
  std::size_t n = 1;
  for (std::size_t d : dims) {
    if (d == 0 || n > std::numeric_limits<std::size_t>::max() / d) return 0;
    n *= d;
  }
  return n;
}

static std::string dims_text(const Extent& d) {
  return std::to_string(d[0]) + "," + std::to_string(d[1]) + "," + std::to_string(d[2]);
}

std::size_t raw_file_size(const fs::path& path, const Extent& dims, VoxelType type, std::size_t max_voxels) {
  const std::string what = "cannot read " + path.string() + ": ";
  const std::size_t count = checked_count(dims);
  if (count == 0 || count > max_voxels)
    throw std::runtime_error(what + "--dims " + dims_text(dims) + " is too large (at most " +
                             std::to_string(max_voxels) + " voxels)");
  const std::uintmax_t expected = std::uintmax_t(count) * bytes_per_voxel(type);
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw std::runtime_error(what + "no such file");
  const std::uintmax_t actual = fs::file_size(path, ec);
  if (ec) throw std::runtime_error(what + ec.message());
  if (actual != expected)
    throw std::runtime_error(what + "file has " + std::to_string(actual) + " bytes but --dims " +
                             dims_text(dims) + " --dtype " + to_string(type) + " needs " +
                             std::to_string(expected));
  return std::size_t(expected);
}

Volume read_raw_volume(const fs::path& path, const Extent& dims, VoxelType type, std::size_t max_voxels) {
  const std::size_t expected = raw_file_size(path, dims, type, max_voxels);
  const std::vector<std::uint8_t> bytes = read_file_bytes(path, expected);
  Volume volume(dims, type);
  switch (type) {
    case VoxelType::u8: decode_samples<std::uint8_t, std::uint8_t>(bytes.data(), volume.samples); break;
    case VoxelType::u16: decode_samples<std::uint16_t, std::uint16_t>(bytes.data(), volume.samples); break;
    case VoxelType::f32: decode_samples<float, std::uint32_t>(bytes.data(), volume.samples); break;
    case VoxelType::f64: decode_samples<double, std::uint64_t>(bytes.data(), volume.samples); break;
  }
  return volume;
}

void write_raw_volume(const Volume& volume, const fs::path& path) {
  if (volume.samples.size() != volume.count())
    throw std::invalid_argument("write_raw_volume: sample count does not match dims");
  std::vector<std::uint8_t> bytes(volume.samples.size() * bytes_per_voxel(volume.type));
  switch (volume.type) {
    case VoxelType::u8: encode_samples<std::uint8_t, std::uint8_t>(volume.samples, bytes.data()); break;
    case VoxelType::u16: encode_samples<std::uint16_t, std::uint16_t>(volume.samples, bytes.data()); break;
    case VoxelType::f32: encode_samples<float, std::uint32_t>(volume.samples, bytes.data()); break;
    case VoxelType::f64: encode_samples<double, std::uint64_t>(volume.samples, bytes.data()); break;
  }
  write_output_bytes(path, bytes);
}

// ---------------------------------------------------------------------------------------------
// OpenVDB

bool is_vdb_path(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext == ".vdb";
}

std::vector<VolumeGrid> read_vdb_dense(const fs::path& path, std::string_view grid_name,
                                       std::vector<std::string>* skipped, std::size_t max_box_voxels) {
  std::vector<VolumeGrid> grids = read_vdb(path, grid_name, skipped);
  for (VolumeGrid& g : grids) try {
      if (!g.is_opaque()) make_dense_box(g, max_box_voxels);
    } catch (const std::runtime_error& e) {
      throw std::runtime_error("cannot read " + path.string() + ": " + e.what());
    }
  return grids;
}

std::vector<VolumeGrid> read_vdb(const fs::path& path, std::string_view grid_name,
                                 std::vector<std::string>* skipped) {
  return vdb_module().read(path, grid_name, skipped);
}

std::string describe_vdb_file(const fs::path& path) { return vdb_module().describe(path); }

void write_vdb(const std::vector<VolumeGrid>& grids, const fs::path& path) {
  vdb_module().write(grids, path);
}

}  // namespace pupwave::cli
