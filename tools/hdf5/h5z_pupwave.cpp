// The HDF5 filter plugin (H5Z_class2_t behind H5PLget_plugin_info). can_apply refuses types and
// parameters the codec cannot serve; set_local records the element type and chunk shape in
// cd_values (layout in h5z_pupwave.h) so that the filter itself needs no HDF5 call.

#include <H5PLextern.h>

#include <array>
#include <cstring>
#include <stdexcept>
#include <string>

#include "tools/hdf5/chunk_codec.h"
#include "tools/hdf5/h5z_pupwave.h"
#include "tools/hdf5/hdf5_api.h"

namespace pupwave::h5 {
namespace {

double bound_from_words(unsigned lo, unsigned hi) {
  const std::uint64_t bits = std::uint64_t(lo) | (std::uint64_t(hi) << 32);
  double v;
  std::memcpy(&v, &bits, sizeof v);
  return v;
}

// Element type of an HDF5 datatype, or a message saying why the filter cannot take it.
ChunkType chunk_type(const Hdf5Api& api, hid_t type_id) {
  const H5T_class_t cls = api.Tget_class(type_id);
  const std::size_t size = api.Tget_size(type_id);
  if (api.Tget_order(type_id) != H5T_ORDER_LE)
    throw std::invalid_argument("only little-endian datatypes are supported");
  if (cls == H5T_FLOAT && size == 4) return ChunkType::f32;
  if (cls == H5T_FLOAT && size == 8) return ChunkType::f64;
  if (cls == H5T_INTEGER && (size == 1 || size == 2)) {
    const bool is_signed = api.Tget_sign(type_id) == H5T_SGN_2;
    if (size == 1) return is_signed ? ChunkType::i8 : ChunkType::u8;
    return is_signed ? ChunkType::i16 : ChunkType::u16;
  }
  throw std::invalid_argument("datatype must be float32, float64 or an 8/16-bit integer (class " +
                              std::to_string(int(cls)) + ", " + std::to_string(size) + " bytes)");
}

struct UserValues {
  unsigned flags = 0;
  std::array<unsigned, H5Z_PUPWAVE_CD_MAX> cd{};
  std::size_t count = 0;
};

UserValues user_values(const Hdf5Api& api, hid_t dcpl) {
  UserValues u;
  u.count = u.cd.size();
  if (api.Pget_filter_by_id2(dcpl, H5Z_FILTER_PUPWAVE, &u.flags, &u.count, u.cd.data(), 0, nullptr, nullptr) <
      0)
    throw std::invalid_argument("filter not found in the dataset creation property list");
  if (u.count < 1) throw std::invalid_argument("cd_values must give at least the mode (cd_values[0])");
  if (u.count < H5Z_PUPWAVE_CD_USER && u.cd[0] != H5Z_PUPWAVE_MODE_LOSSLESS)
    throw std::invalid_argument("cd_values must give mode and bound (3 values: mode, bound low/high words)");
  return u;
}

// Shared checks of can_apply and set_local; returns the element type.
ChunkType check(const Hdf5Api& api, hid_t dcpl, hid_t type_id, const UserValues& u) {
  const ChunkType type = chunk_type(api, type_id);
  const double bound = bound_from_words(u.cd[1], u.cd[2]);
  if (const std::string why = check_params(u.cd[0], bound, type); !why.empty())
    throw std::invalid_argument(why);
  std::array<hsize_t, 32> dims{};
  const int rank = api.Pget_chunk(dcpl, int(dims.size()), dims.data());
  if (rank < 1) throw std::invalid_argument("dataset is not chunked");
  extent_from_shape(std::span<const hsize_t>(dims.data(), std::size_t(rank)));
  return type;
}

htri_t can_apply(hid_t dcpl, hid_t type_id, hid_t) {
  const Hdf5Api* api = hdf5_api();
  if (api == nullptr) return -1;
  try {
    check(*api, dcpl, type_id, user_values(*api, dcpl));
    return 1;
  } catch (const std::exception& e) {
    push_error(api, api->CANAPPLY, "pupwave can_apply", e.what());
    return -1;
  }
}

herr_t set_local(hid_t dcpl, hid_t type_id, hid_t) {
  const Hdf5Api* api = hdf5_api();
  if (api == nullptr) return -1;
  try {
    UserValues u = user_values(*api, dcpl);
    const ChunkType type = check(*api, dcpl, type_id, u);
    std::array<hsize_t, 32> dims{};
    const int rank = api->Pget_chunk(dcpl, int(dims.size()), dims.data());
    u.cd[H5Z_PUPWAVE_CD_TYPE] = unsigned(type);
    std::size_t kept = 0;
    for (int i = 0; i < rank; ++i)
      if (dims[i] > 1) u.cd[H5Z_PUPWAVE_CD_DIMS + kept++] = unsigned(dims[i]);
    if (kept == 0) u.cd[H5Z_PUPWAVE_CD_DIMS + kept++] = 1;  // a chunk of one element
    u.cd[H5Z_PUPWAVE_CD_RANK] = unsigned(kept);
    return api->Pmodify_filter(dcpl, H5Z_FILTER_PUPWAVE, u.flags, H5Z_PUPWAVE_CD_DIMS + kept, u.cd.data());
  } catch (const std::exception& e) {
    push_error(api, api->SETLOCAL, "pupwave set_local", e.what());
    return -1;
  }
}

ChunkParams params_from_cd(std::size_t n, const unsigned cd[]) {
  if (n < H5Z_PUPWAVE_CD_DIMS + 1 || n < H5Z_PUPWAVE_CD_DIMS + std::size_t(cd[H5Z_PUPWAVE_CD_RANK]) ||
      cd[H5Z_PUPWAVE_CD_RANK] < 1 || cd[H5Z_PUPWAVE_CD_RANK] > 3 || !is_valid_type(cd[H5Z_PUPWAVE_CD_TYPE]))
    throw std::invalid_argument("incomplete cd_values (" + std::to_string(n) +
                                " values; set_local did not run?)");
  ChunkParams p;
  p.mode = Mode(cd[0]);
  p.bound = bound_from_words(cd[1], cd[2]);
  p.type = ChunkType(cd[H5Z_PUPWAVE_CD_TYPE]);
  std::array<unsigned long long, 3> dims{};
  for (unsigned i = 0; i < cd[H5Z_PUPWAVE_CD_RANK]; ++i) dims[i] = cd[H5Z_PUPWAVE_CD_DIMS + i];
  p.dims = extent_from_shape(std::span<const unsigned long long>(dims.data(), cd[H5Z_PUPWAVE_CD_RANK]));
  return p;
}

// Replaces HDF5's buffer with `bytes`, allocated the way HDF5 frees it.
std::size_t hand_over(const Hdf5Api* api, const std::vector<std::uint8_t>& bytes, std::size_t* buf_size,
                      void** buf) {
  void* out = api != nullptr ? api->allocate_memory(bytes.size(), false) : std::malloc(bytes.size());
  if (out == nullptr) throw std::bad_alloc();
  std::memcpy(out, bytes.data(), bytes.size());
  api != nullptr ? (void)api->free_memory(*buf) : std::free(*buf);
  *buf = out;
  *buf_size = bytes.size();
  return bytes.size();
}

std::size_t filter(unsigned flags, std::size_t cd_nelmts, const unsigned cd_values[], std::size_t nbytes,
                   std::size_t* buf_size, void** buf) {
  const Hdf5Api* api = hdf5_api();
  const bool reverse = (flags & H5Z_FLAG_REVERSE) != 0;
  try {
    const ChunkParams p = params_from_cd(cd_nelmts, cd_values);
    const std::size_t expected = p.count() * element_size(p.type);
    const std::span<const std::uint8_t> in(static_cast<const std::uint8_t*>(*buf), nbytes);
    if (!reverse) {
      if (nbytes != expected)
        throw std::invalid_argument("chunk of " + std::to_string(nbytes) + " bytes, expected " +
                                    std::to_string(expected));
      return hand_over(api, encode_chunk(p, in), buf_size, buf);
    }
    const DecodedChunk d = decode_chunk(in);
    if (d.type != p.type || d.bytes.size() != expected)
      throw std::invalid_argument("chunk decodes to " + std::to_string(d.bytes.size()) + " bytes of type " +
                                  std::to_string(int(d.type)) + ", dataset expects " +
                                  std::to_string(expected));
    return hand_over(api, d.bytes, buf_size, buf);
  } catch (const std::exception& e) {
    push_error(api, api != nullptr ? api->CANTFILTER : nullptr, "pupwave filter",
               std::string(reverse ? "cannot decode chunk: " : "cannot encode chunk: ") + e.what());
    return 0;
  }
}

const H5Z_class2_t kFilterClass = {
    H5Z_CLASS_T_VERS,
    H5Z_filter_t(H5Z_FILTER_PUPWAVE),
    1,
    1,
    "pupwave (error-bounded wavelet volumes)",
    can_apply,
    set_local,
    filter,
};

}  // namespace
}  // namespace pupwave::h5

extern "C" {
H5PL_type_t H5PLget_plugin_type(void) { return H5PL_TYPE_FILTER; }
const void* H5PLget_plugin_info(void) { return &pupwave::h5::kFilterClass; }
}
