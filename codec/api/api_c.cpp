// The C API (pupwave/pupwave.h) over the C++ API: handles own C++ objects, every entry point
// catches everything and turns it into a status plus a thread-local message.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <new>
#include <optional>
#include <string>
#include <vector>

#include "codec/api/api_target_miss.h"
#include "pupwave/pupwave.h"
#include "pupwave/pupwave.hpp"

struct pupwave_options {
  pupwave_rate rate = PUPWAVE_RATE_PSNR;
  double target = 40.0;
  bool rate_set = false;  // unset: each kind's default (ImageOptions, VolumeOptions: automatic)
  std::string transform;
  int levels = -1;
  unsigned threads = 0;
  std::size_t brick = 64;
  pupwave_coder coder = PUPWAVE_CODER_AUTO;
  int effort = 1;
  std::optional<double> fill_value;
  pupwave_tune tune = PUPWAVE_TUNE_PSNR;
};

struct pupwave_stream {
  std::vector<std::uint8_t> bytes;
  pupwave::api::TargetOutcome outcome;  // of the rate target it was compressed for
  std::string miss;                     // api_target_miss.h's text for a missed target, "" when met
};

struct pupwave_decoded {
  pupwave_type type = PUPWAVE_U8;
  std::size_t dims[3] = {0, 0, 0};
  std::size_t channels = 1;
  std::vector<std::byte> data;
  std::int64_t origin[3] = {0, 0, 0};
  std::vector<std::uint8_t> active;  // sparse volumes only
};

namespace {

thread_local std::string last_error;

pupwave_status fail(pupwave_status status, const char* message) {
  try {
    last_error = message;
  } catch (...) {  // the message could not be stored: keep the code
  }
  return status;
}

// Runs f (which returns nothing), mapping every exception to a status and message.
template <class F>
pupwave_status guarded(F&& f) {
  try {
    f();
    return PUPWAVE_OK;
  } catch (const pupwave::api::Error& e) {
    switch (e.status()) {
      case pupwave::api::Status::invalid_argument: return fail(PUPWAVE_ERROR_ARGUMENT, e.what());
      case pupwave::api::Status::unsupported: return fail(PUPWAVE_ERROR_UNSUPPORTED, e.what());
      case pupwave::api::Status::corrupt_stream: return fail(PUPWAVE_ERROR_CORRUPT, e.what());
      case pupwave::api::Status::out_of_memory: return fail(PUPWAVE_ERROR_MEMORY, e.what());
      default: return fail(PUPWAVE_ERROR_INTERNAL, e.what());
    }
  } catch (const std::bad_alloc&) {
    return fail(PUPWAVE_ERROR_MEMORY, "out of memory");
  } catch (const std::exception& e) {
    return fail(PUPWAVE_ERROR_INTERNAL, e.what());
  } catch (...) {
    return fail(PUPWAVE_ERROR_INTERNAL, "unknown error");
  }
}

void require(bool condition, const std::string& message) {
  if (!condition) throw pupwave::api::Error(pupwave::api::Status::invalid_argument, message);
}

pupwave::api::SampleType image_type(pupwave_type type) {
  require(type == PUPWAVE_U8 || type == PUPWAVE_U16 || type == PUPWAVE_F16 || type == PUPWAVE_F32,
          "image sample type must be PUPWAVE_U8, PUPWAVE_U16, PUPWAVE_F16 or PUPWAVE_F32");
  return pupwave::api::SampleType(type);
}

pupwave::api::VoxelType voxel_type(pupwave_type type) {
  switch (type) {
    case PUPWAVE_U8: return pupwave::api::VoxelType::u8;
    case PUPWAVE_U16: return pupwave::api::VoxelType::u16;
    case PUPWAVE_F32: return pupwave::api::VoxelType::f32;
    case PUPWAVE_F64: return pupwave::api::VoxelType::f64;
    default: require(false, "volume voxel type must be PUPWAVE_U8, PUPWAVE_U16, PUPWAVE_F32 or PUPWAVE_F64");
  }
  return pupwave::api::VoxelType::f32;
}

pupwave_type c_type(pupwave::api::VoxelType type) {
  constexpr pupwave_type types[] = {PUPWAVE_U8, PUPWAVE_U16, PUPWAVE_F32, PUPWAVE_F64};
  return types[int(type) & 3];
}

pupwave::api::ImageOptions image_options(const pupwave_options* o) {
  pupwave::api::ImageOptions out;
  if (!o) return out;
  if (o->rate_set) {
    require(o->rate <= PUPWAVE_RATE_LOSSLESS,
            "volume rate mode (MAX_ERROR, MAX_ERROR_REL, BPV) given for an image");
    out.rate = pupwave::api::ImageRate(o->rate);
    out.target = o->target;
  }
  out.transform = o->transform;
  out.levels = o->levels;
  out.threads = o->threads;
  out.coder = pupwave::api::Coder(o->coder);
  out.effort = o->effort;
  out.tune = pupwave::api::Tune(o->tune);
  return out;
}

pupwave::api::VolumeOptions volume_options(const pupwave_options* o) {
  pupwave::api::VolumeOptions out;
  if (!o) return out;
  if (o->rate_set) {
    using R = pupwave::api::VolumeRate;
    constexpr R rates[] = {R::psnr,      R::max_error /*unused*/, R::step, R::lossless,
                           R::max_error, R::max_error_rel,        R::bpv};
    require(o->rate != PUPWAVE_RATE_BPP, "PUPWAVE_RATE_BPP is for images; volumes use PUPWAVE_RATE_BPV");
    out.rate = rates[o->rate];
    out.target = o->target;
  }
  // Volumes have their own coders: an image coder chosen for a volume is a mistake, said.
  require(o->coder == PUPWAVE_CODER_AUTO || o->coder == PUPWAVE_CODER_EBCOT,
          std::string("the ") + pupwave_coder_name(o->coder) + " entropy coder applies to images only");
  out.transform = o->transform;
  out.levels = o->levels;
  out.threads = o->threads;
  out.brick = o->brick;
  out.fill_value = o->fill_value;
  return out;
}

// The text of a volume stream's missed target (api_target_miss.h), "" when met.
std::string volume_miss(const pupwave::api::VolumeOptions& o, const pupwave_stream& stream) {
  return pupwave::api::volume_target_miss(o.rate, o.target, stream.outcome, stream.bytes.size(),
                                          "the stream");
}

pupwave::api::Volume single_grid(const void* stream, std::size_t size, int level, unsigned threads) {
  require(stream != nullptr, "stream is null");
  auto grids =
      pupwave::api::decompress_volume({static_cast<const std::uint8_t*>(stream), size}, level, threads);
  if (grids.size() != 1)
    throw pupwave::api::Error(
        pupwave::api::Status::unsupported,
        "the stream holds " + std::to_string(grids.size()) +
            " grids; the C API decodes single-grid streams (use the C++ API or the CLI)");
  return std::move(grids[0]);
}

// A decoded volume handed to C callers.
std::unique_ptr<pupwave_decoded> decoded_volume(pupwave::api::Volume&& v) {
  auto d = std::make_unique<pupwave_decoded>();
  d->type = c_type(v.type);
  std::copy(v.dims.begin(), v.dims.end(), d->dims);
  std::copy(v.origin.begin(), v.origin.end(), d->origin);
  d->data = std::move(v.data);
  d->active = std::move(v.active);
  return d;
}

}  // namespace

extern "C" {

const char* pupwave_last_error(void) { return last_error.c_str(); }
const char* pupwave_version(void) { return "pupwave " PUPWAVE_VERSION_STRING; }

pupwave_options* pupwave_options_create(void) { return new (std::nothrow) pupwave_options; }
void pupwave_options_destroy(pupwave_options* options) { delete options; }

pupwave_status pupwave_options_set_rate(pupwave_options* options, pupwave_rate rate, double target) {
  return guarded([&] {
    require(options != nullptr, "options is null");
    require(rate >= PUPWAVE_RATE_PSNR && rate <= PUPWAVE_RATE_BPV, "unknown rate mode");
    require(rate == PUPWAVE_RATE_LOSSLESS || (target > 0.0 && target <= 1e300),
            "rate target must be a positive finite number");
    options->rate = rate;
    options->target = target;
    options->rate_set = true;
  });
}

pupwave_status pupwave_options_set_transform(pupwave_options* options, const char* spec) {
  return guarded([&] {
    require(options != nullptr, "options is null");
    options->transform = spec ? spec : "";
  });
}

pupwave_status pupwave_options_set_levels(pupwave_options* options, int levels) {
  return guarded([&] {
    require(options != nullptr, "options is null");
    require(levels >= -1 && levels <= 32, "levels must be -1 (default) or 0..32");
    options->levels = levels;
  });
}

pupwave_status pupwave_options_set_threads(pupwave_options* options, unsigned threads) {
  return guarded([&] {
    require(options != nullptr, "options is null");
    options->threads = threads;
  });
}

pupwave_status pupwave_options_set_brick(pupwave_options* options, size_t brick) {
  return guarded([&] {
    require(options != nullptr, "options is null");
    options->brick = brick;
  });
}

pupwave_status pupwave_options_set_fill_value(pupwave_options* options, double fill_value) {
  return guarded([&] {
    require(options != nullptr, "options is null");
    require(std::isfinite(fill_value), "fill value must be finite (NaN and infinities are always missing)");
    options->fill_value = fill_value;
  });
}

pupwave_status pupwave_options_set_coder(pupwave_options* options, pupwave_coder coder) {
  return guarded([&] {
    require(options != nullptr, "options is null");
    require(pupwave_coder_name(coder) != nullptr, "unknown entropy coder " + std::to_string(int(coder)));
    options->coder = coder;
  });
}

pupwave_status pupwave_coder_from_name(const char* name, pupwave_coder* coder) {
  return guarded([&] {
    require(name != nullptr && coder != nullptr, "name or coder is null");
    const auto found = pupwave::api::coder_from_name(name);
    require(found.has_value(),
            "unknown entropy coder '" + std::string(name) + "' (one of " + pupwave::api::coder_names() + ")");
    *coder = pupwave_coder(*found);
  });
}

const char* pupwave_coder_name(pupwave_coder coder) {
  // The C enumerators are the C++ ones (static_asserts below); names are string literals.
  if (int(coder) < int(PUPWAVE_CODER_AUTO) || int(coder) > int(PUPWAVE_CODER_HT)) return nullptr;
  return pupwave::api::coder_name(pupwave::api::Coder(coder)).data();
}

static_assert(int(PUPWAVE_CODER_AUTO) == int(pupwave::api::Coder::automatic) &&
              int(PUPWAVE_CODER_EBCOT) == int(pupwave::api::Coder::ebcot) &&
              int(PUPWAVE_CODER_PC) == int(pupwave::api::Coder::pc) &&
              int(PUPWAVE_CODER_LC) == int(pupwave::api::Coder::lc) &&
              int(PUPWAVE_CODER_HT) == int(pupwave::api::Coder::ht));

pupwave_status pupwave_options_set_effort(pupwave_options* options, int effort) {
  return guarded([&] {
    require(options != nullptr, "options is null");
    require(effort == 1 || effort == 2, "effort must be 1 or 2");
    options->effort = effort;
  });
}

static_assert(int(PUPWAVE_TUNE_PSNR) == int(pupwave::api::Tune::psnr) &&
              int(PUPWAVE_TUNE_VISUAL) == int(pupwave::api::Tune::visual));

pupwave_status pupwave_options_set_tune(pupwave_options* options, pupwave_tune tune) {
  return guarded([&] {
    require(options != nullptr, "options is null");
    require(tune == PUPWAVE_TUNE_PSNR || tune == PUPWAVE_TUNE_VISUAL,
            "unknown tune " + std::to_string(int(tune)));
    options->tune = tune;
  });
}

const uint8_t* pupwave_stream_data(const pupwave_stream* stream) {
  return stream ? stream->bytes.data() : nullptr;
}
size_t pupwave_stream_size(const pupwave_stream* stream) { return stream ? stream->bytes.size() : 0; }
int pupwave_stream_target_met(const pupwave_stream* stream) { return stream && stream->outcome.met ? 1 : 0; }
double pupwave_stream_achieved(const pupwave_stream* stream) {
  return stream ? stream->outcome.achieved : std::numeric_limits<double>::quiet_NaN();
}
const char* pupwave_stream_target_miss(const pupwave_stream* stream) {
  return stream ? stream->miss.c_str() : "";
}
void pupwave_stream_destroy(pupwave_stream* stream) { delete stream; }

pupwave_status pupwave_compress_image(const pupwave_options* options, const void* data, pupwave_type type,
                                      size_t width, size_t height, size_t channels, ptrdiff_t channel_stride,
                                      ptrdiff_t pixel_stride, ptrdiff_t row_stride, pupwave_stream** out) {
  return guarded([&] {
    require(out != nullptr, "out is null");
    *out = nullptr;
    const pupwave::api::ImageView view{data,           width,        height,    channels, image_type(type),
                                       channel_stride, pixel_stride, row_stride};
    const pupwave::api::ImageOptions o = image_options(options);
    auto stream = std::make_unique<pupwave_stream>();
    stream->bytes = pupwave::api::compress_image(view, o, stream->outcome);
    stream->miss =
        pupwave::api::image_target_miss(o.rate, o.target, stream->outcome, stream->bytes, "the stream");
    *out = stream.release();
  });
}

pupwave_type pupwave_decoded_type(const pupwave_decoded* d) { return d ? d->type : PUPWAVE_U8; }
size_t pupwave_decoded_dim(const pupwave_decoded* d, int axis) {
  return d && axis >= 0 && axis < 3 ? d->dims[axis] : 0;
}
size_t pupwave_decoded_channels(const pupwave_decoded* d) { return d ? d->channels : 0; }
const void* pupwave_decoded_data(const pupwave_decoded* d) { return d ? d->data.data() : nullptr; }
size_t pupwave_decoded_size(const pupwave_decoded* d) { return d ? d->data.size() : 0; }
int64_t pupwave_decoded_origin(const pupwave_decoded* d, int axis) {
  return d && axis >= 0 && axis < 3 ? d->origin[axis] : 0;
}
const uint8_t* pupwave_decoded_active(const pupwave_decoded* d) {
  return d && !d->active.empty() ? d->active.data() : nullptr;
}
void pupwave_decoded_destroy(pupwave_decoded* d) { delete d; }

pupwave_status pupwave_decompress_image(const void* stream, size_t size, int level, unsigned threads,
                                        pupwave_decoded** out) {
  return guarded([&] {
    require(out != nullptr, "out is null");
    *out = nullptr;
    require(stream != nullptr, "stream is null");
    auto image =
        pupwave::api::decompress_image({static_cast<const std::uint8_t*>(stream), size}, level, threads);
    auto d = std::make_unique<pupwave_decoded>();
    d->type = pupwave_type(image.type);
    d->dims[0] = image.width;
    d->dims[1] = image.height;
    d->dims[2] = 1;
    d->channels = image.channels;
    d->data = std::move(image.data);
    *out = d.release();
  });
}

pupwave_status pupwave_compress_volume(const pupwave_options* options, const void* data, pupwave_type type,
                                       size_t nx, size_t ny, size_t nz, pupwave_stream** out) {
  return guarded([&] {
    require(out != nullptr, "out is null");
    *out = nullptr;
    const pupwave::api::VolumeView view{data, {nx, ny, nz}, voxel_type(type)};
    const pupwave::api::VolumeOptions o = volume_options(options);
    auto stream = std::make_unique<pupwave_stream>();
    stream->bytes = pupwave::api::compress_volume(view, o, stream->outcome);
    stream->miss = volume_miss(o, *stream);
    *out = stream.release();
  });
}

pupwave_status pupwave_compress_sparse_volume(const pupwave_options* options, const pupwave_brick* bricks,
                                              size_t count, pupwave_type type, double background,
                                              pupwave_stream** out) {
  return guarded([&] {
    require(out != nullptr, "out is null");
    *out = nullptr;
    require(bricks != nullptr || count == 0, "bricks is null");
    const pupwave::api::VoxelType vt = voxel_type(type);
    std::vector<pupwave::api::BrickView> views(count);
    for (std::size_t i = 0; i < count; ++i) {
      const pupwave_brick& b = bricks[i];
      views[i] = {
          {b.origin[0], b.origin[1], b.origin[2]}, {b.data, {b.dims[0], b.dims[1], b.dims[2]}, vt}, b.active};
    }
    const pupwave::api::VolumeOptions o = volume_options(options);
    auto stream = std::make_unique<pupwave_stream>();
    stream->bytes = pupwave::api::compress_sparse_volume(views, background, o, stream->outcome);
    stream->miss = volume_miss(o, *stream);
    *out = stream.release();
  });
}

pupwave_status pupwave_decompress_volume(const void* stream, size_t size, int level, unsigned threads,
                                         pupwave_decoded** out) {
  return guarded([&] {
    require(out != nullptr, "out is null");
    *out = nullptr;
    *out = decoded_volume(single_grid(stream, size, level, threads)).release();
  });
}

pupwave_status pupwave_decompress_volume_box(const void* stream, size_t size, const size_t lo[3],
                                             const size_t hi[3], int level, unsigned threads,
                                             pupwave_decoded** out) {
  return guarded([&] {
    require(out != nullptr, "out is null");
    *out = nullptr;
    require(stream != nullptr, "stream is null");
    require(lo != nullptr && hi != nullptr, "box is null");
    const pupwave::api::VoxelBox box{{lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}};
    *out = decoded_volume(pupwave::api::decompress_volume_box(
                              {static_cast<const std::uint8_t*>(stream), size}, box, level, threads))
               .release();
  });
}

pupwave_status pupwave_decompress_volume_into(const void* stream, size_t size, int level, unsigned threads,
                                              void* buffer, size_t capacity) {
  return guarded([&] {
    require(buffer != nullptr, "buffer is null");
    const pupwave::api::Volume v = single_grid(stream, size, level, threads);
    if (v.data.size() != capacity)
      throw pupwave::api::Error(pupwave::api::Status::invalid_argument,
                                "buffer holds " + std::to_string(capacity) + " bytes, the decoded grid " +
                                    std::to_string(v.data.size()));
    std::memcpy(buffer, v.data.data(), capacity);
  });
}

pupwave_status pupwave_describe_dims(const void* stream, size_t size, int* kind, size_t dims[3],
                                     pupwave_type* type, int* levels) {
  return guarded([&] {
    require(stream != nullptr, "stream is null");
    const auto info = pupwave::api::info({static_cast<const std::uint8_t*>(stream), size});
    if (kind) *kind = info.volume ? 1 : 0;
    if (dims) std::copy(info.dims.begin(), info.dims.end(), dims);
    if (levels) *levels = info.levels;
    if (type) {
      const char* names[] = {"u8", "u16", "f16", "f32", "f64"};
      for (int t = 0; t < 5; ++t)
        if (info.type == names[t]) *type = pupwave_type(t);
    }
  });
}

pupwave_status pupwave_describe(const void* stream, size_t size, char* buffer, size_t capacity,
                                size_t* length) {
  return guarded([&] {
    require(stream != nullptr, "stream is null");
    require(buffer != nullptr || capacity == 0, "buffer is null");
    const auto info = pupwave::api::info({static_cast<const std::uint8_t*>(stream), size});
    if (length) *length = info.description.size();
    if (capacity == 0) return;
    const std::size_t n = std::min(capacity - 1, info.description.size());
    std::memcpy(buffer, info.description.data(), n);
    buffer[n] = '\0';
  });
}

}  // extern "C"
