// pupwave._pupwave: numpy bindings over the public C++ API (pupwave/pupwave.hpp). Arrays of the
// stored dtypes are handed to the codec as strided views (no copy); the GIL is released while
// coding; the library's errors become ValueError, other dtypes and non-arrays TypeError. The
// package (pupwave/__init__.py) converts other dtypes (pupwave/dtypes.py) and passes the text
// attributes that record them: compress* take `attributes` (dict), decompress* return
// (array, attributes). Every call takes `threads` (None or 0: all cores, 1: the calling thread);
// compress* return (bytes, miss), miss the library's text for a missed rate target
// (codec/api/api_target_miss.h, the CLI's `warning:` text; '' when met), which the package turns
// into a warning or, with strict=True, an error.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "codec/api/api_target_miss.h"
#include "codec/api/api_volume_options.h"
#include "pupwave/pupwave.hpp"

namespace py = pybind11;
namespace api = pupwave::api;

namespace {

// A contiguous read-only view of a bytes-like object, released on scope exit.
class ByteView {
 public:
  explicit ByteView(const py::object& obj) {
    if (PyObject_GetBuffer(obj.ptr(), &view_, PyBUF_SIMPLE) != 0) {
      PyErr_Clear();
      throw py::type_error("expected a bytes-like object (bytes, bytearray, contiguous memoryview)");
    }
  }
  ~ByteView() { PyBuffer_Release(&view_); }
  ByteView(const ByteView&) = delete;
  ByteView& operator=(const ByteView&) = delete;
  std::span<const std::uint8_t> bytes() const {
    return {static_cast<const std::uint8_t*>(view_.buf), std::size_t(view_.len)};
  }

 private:
  Py_buffer view_{};
};

py::array as_array(const py::object& obj) {
  if (!py::isinstance<py::array>(obj))
    throw py::type_error("expected a numpy.ndarray, got " +
                         obj.get_type().attr("__name__").cast<std::string>());
  return py::reinterpret_borrow<py::array>(obj);
}

api::SampleType image_type(const py::array& a) {
  const py::dtype dt = a.dtype();
  if (dt.equal(py::dtype("uint8"))) return api::SampleType::u8;
  if (dt.equal(py::dtype("uint16"))) return api::SampleType::u16;
  if (dt.equal(py::dtype("float16"))) return api::SampleType::f16;
  if (dt.equal(py::dtype("float32"))) return api::SampleType::f32;
  throw py::type_error("unsupported image dtype " + dt.attr("name").cast<std::string>() +
                       "; expected uint8, uint16, float16 or float32");
}

api::VoxelType voxel_type(const py::array& a) {
  const py::dtype dt = a.dtype();
  if (dt.equal(py::dtype("uint8"))) return api::VoxelType::u8;
  if (dt.equal(py::dtype("uint16"))) return api::VoxelType::u16;
  if (dt.equal(py::dtype("float32"))) return api::VoxelType::f32;
  if (dt.equal(py::dtype("float64"))) return api::VoxelType::f64;
  throw py::type_error("unsupported volume dtype " + dt.attr("name").cast<std::string>() +
                       "; expected float32, float64, uint8 or uint16");
}

// `a` itself when the codec can read it in place through its strides (whole elements, none zero
// along an axis longer than 1), else its C-contiguous copy, made once: record fields (strides
// that are not whole elements) and broadcast views (stride 0), which the library refuses.
py::array readable_in_place(const py::array& a) {
  for (int d = 0; d < a.ndim(); ++d)
    if (a.strides(d) % a.itemsize() != 0 || (a.strides(d) == 0 && a.shape(d) > 1))
      return py::module_::import("numpy").attr("ascontiguousarray")(a).cast<py::array>();
  return a;
}

// Element stride of axis `axis` (numpy strides are bytes; readable_in_place made them whole).
std::ptrdiff_t element_stride(const py::array& a, int axis) {
  return a.strides(axis) / std::ptrdiff_t(a.itemsize());
}

py::dtype numpy_dtype(const std::string& name) { return py::dtype(name); }

const char* dtype_name(api::SampleType t) {
  constexpr const char* names[] = {"uint8", "uint16", "float16", "float32"};
  return names[int(t) & 3];
}
const char* dtype_name(api::VoxelType t) {
  constexpr const char* names[] = {"uint8", "uint16", "float32", "float64"};
  return names[int(t) & 3];
}

// A numpy array owning `data` (moved to the heap, freed with the array).
py::array owning_array(std::vector<std::byte>&& data, const std::string& dtype,
                       std::vector<py::ssize_t> shape) {
  auto* owner = new std::vector<std::byte>(std::move(data));
  py::capsule free_owner(owner, [](void* p) { delete static_cast<std::vector<std::byte>*>(p); });
  return py::array(numpy_dtype(dtype), shape, owner->data(), free_owner);
}

py::bytes to_bytes(const std::vector<std::uint8_t>& v) {
  return py::bytes(reinterpret_cast<const char*>(v.data()), v.size());
}

std::vector<api::Attribute> to_attributes(const std::map<std::string, std::string>& attributes) {
  std::vector<api::Attribute> out;
  for (const auto& [name, value] : attributes) out.push_back({name, value});
  return out;
}

py::dict to_dict(const std::vector<api::Attribute>& attributes) {
  py::dict d;
  for (const api::Attribute& a : attributes) d[py::str(a.name)] = py::str(a.value);
  return d;
}

// The `threads` argument as the API's (None or 0: all cores, 1: the calling thread).
unsigned thread_count(std::optional<int> threads) {
  if (threads && *threads < 0)
    throw py::value_error("threads must be None or an integer >= 0, got " + std::to_string(*threads));
  return unsigned(threads.value_or(0));
}

int count_set(std::initializer_list<bool> flags) {
  int n = 0;
  for (bool f : flags) n += f ? 1 : 0;
  return n;
}

py::tuple compress(const py::object& obj, std::optional<double> bpp, std::optional<double> psnr,
                   std::optional<double> step, bool lossless, const std::optional<std::string>& transform,
                   std::optional<int> levels, int effort, const std::string& entropy, const std::string& tune,
                   const std::map<std::string, std::string>& attributes, std::optional<int> threads) {
  const py::array given = as_array(obj);
  // The dtype first: readable_in_place divides by its (then nonzero) item size.
  const api::SampleType type = image_type(given);
  const py::array a = readable_in_place(given);
  if (a.ndim() != 2 && a.ndim() != 3)
    throw py::value_error("expected a 2-D (height, width) or 3-D (height, width, channels) array, got " +
                          std::to_string(a.ndim()) + "-D");
  api::ImageView view;
  view.data = a.data();
  view.type = type;
  view.height = std::size_t(a.shape(0));
  view.width = std::size_t(a.shape(1));
  view.channels = a.ndim() == 3 ? std::size_t(a.shape(2)) : 1;
  view.row_stride = element_stride(a, 0);
  view.pixel_stride = element_stride(a, 1);
  view.channel_stride = a.ndim() == 3 ? element_stride(a, 2) : 0;
  if (count_set({bpp.has_value(), psnr.has_value(), step.has_value(), lossless}) > 1)
    throw py::value_error("give at most one of bpp, psnr, step and lossless");
  api::ImageOptions options;
  if (bpp) options.rate = api::ImageRate::bpp, options.target = *bpp;
  if (psnr) options.rate = api::ImageRate::psnr, options.target = *psnr;
  if (step) options.rate = api::ImageRate::step, options.target = *step;
  if (lossless) options.rate = api::ImageRate::lossless;
  options.transform = transform.value_or("");  // none: the library's default (cdf53 for lossless)
  options.levels = levels.value_or(-1);
  options.effort = effort;
  options.attributes = to_attributes(attributes);
  const auto coder = api::coder_from_name(entropy);
  if (!coder) throw py::value_error("entropy must be one of " + api::coder_names() + ", got " + entropy);
  options.coder = *coder;
  const auto tuned = api::tune_from_name(tune);
  if (!tuned) throw py::value_error("tune must be psnr or visual, got " + tune);
  options.tune = *tuned;
  options.threads = thread_count(threads);
  std::vector<std::uint8_t> out;
  api::TargetOutcome outcome;
  {
    py::gil_scoped_release release;
    out = api::compress_image(view, options, outcome);
  }
  return py::make_tuple(to_bytes(out),
                        api::image_target_miss(options.rate, options.target, outcome, out, "the stream"));
}

py::tuple decompress(const py::object& data, int level, std::optional<int> threads) {
  const unsigned workers = thread_count(threads);
  api::Image image;
  {
    const ByteView bytes(data);
    py::gil_scoped_release release;
    image = api::decompress_image(bytes.bytes(), level, workers);
  }
  std::vector<py::ssize_t> shape{py::ssize_t(image.height), py::ssize_t(image.width)};
  if (image.channels > 1) shape.push_back(py::ssize_t(image.channels));
  return py::make_tuple(owning_array(std::move(image.data), dtype_name(image.type), shape),
                        to_dict(image.attributes));
}

// The volume rate of compress_volume's arguments (at most one given; none: automatic, the
// library's default, as the CLI's).
void set_volume_rate(api::VolumeOptions& options, std::optional<double> max_error,
                     std::optional<double> max_error_rel, std::optional<double> bpv,
                     std::optional<double> psnr, std::optional<double> step, bool lossless) {
  if (count_set({max_error.has_value(), max_error_rel.has_value(), bpv.has_value(), psnr.has_value(),
                 step.has_value(), lossless}) > 1)
    throw py::value_error("give at most one of max_error, max_error_rel, bpv, psnr, step and lossless");
  const std::pair<const std::optional<double>&, api::VolumeRate> targets[] = {
      {max_error, api::VolumeRate::max_error},
      {max_error_rel, api::VolumeRate::max_error_rel},
      {bpv, api::VolumeRate::bpv},
      {psnr, api::VolumeRate::psnr},
      {step, api::VolumeRate::step}};
  for (const auto& [target, rate] : targets)
    if (target) options.rate = rate, options.target = *target;
  if (lossless) options.rate = api::VolumeRate::lossless;
}

py::tuple compress_volume(const py::object& obj, std::optional<double> max_error,
                          std::optional<double> max_error_rel, std::optional<double> bpv,
                          std::optional<double> psnr, std::optional<double> step, bool lossless,
                          const std::optional<std::string>& transform, std::optional<int> levels,
                          std::optional<std::size_t> brick,
                          const std::map<std::string, std::string>& attributes, std::optional<int> threads,
                          std::optional<double> fill_value) {
  const py::array given = as_array(obj);
  // The dtype first: readable_in_place divides by its (then nonzero) item size.
  const api::VoxelType type = voxel_type(given);
  const py::array a = readable_in_place(given);
  if (a.ndim() != 3)
    throw py::value_error("expected a 3-D (z, y, x) array, got " + std::to_string(a.ndim()) + "-D");
  api::VolumeOptions options;
  set_volume_rate(options, max_error, max_error_rel, bpv, psnr, step, lossless);
  options.transform = transform.value_or("");  // none: the library's default for the rate
  options.levels = levels.value_or(-1);
  if (brick) options.brick = *brick;  // none: the library's default edge
  options.attributes = to_attributes(attributes);
  options.threads = thread_count(threads);
  options.fill_value = fill_value;
  api::VolumeView view{
      a.data(), {std::size_t(a.shape(2)), std::size_t(a.shape(1)), std::size_t(a.shape(0))}, type};
  for (int d = 0; d < 3; ++d) view.strides[std::size_t(2 - d)] = element_stride(a, d);  // (z, y, x)
  std::vector<std::uint8_t> out;
  api::TargetOutcome outcome;
  {
    py::gil_scoped_release release;
    out = api::compress_volume(view, options, outcome);
  }
  const std::string miss =
      api::volume_target_miss(options.rate, options.target, outcome, out.size(), "the stream");
  return py::make_tuple(to_bytes(out), miss);
}

// box: x0, y0, z0, x1, y1, z1 (the package turns the array-order pairs it is given into these).
py::tuple decompress_volume(const py::object& data, int level, std::optional<int> threads,
                            std::optional<std::array<std::size_t, 6>> box) {
  const unsigned workers = thread_count(threads);
  std::vector<api::Volume> grids;
  {
    const ByteView bytes(data);
    py::gil_scoped_release release;
    if (box)
      grids.push_back(api::decompress_volume_box(
          bytes.bytes(), {{(*box)[0], (*box)[1], (*box)[2]}, {(*box)[3], (*box)[4], (*box)[5]}}, level,
          workers));
    else
      grids = api::decompress_volume(bytes.bytes(), level, workers);
  }
  if (grids.size() != 1)
    throw py::value_error("the stream holds " + std::to_string(grids.size()) +
                          " grids; decompress_volume returns single-grid streams (use `pupwave decompress`)");
  api::Volume& v = grids[0];
  return py::make_tuple(
      owning_array(std::move(v.data), dtype_name(v.type),
                   {py::ssize_t(v.dims[2]), py::ssize_t(v.dims[1]), py::ssize_t(v.dims[0])}),
      to_dict(v.attributes));
}

py::dict info(const py::object& data) {
  api::StreamInfo s;
  std::size_t size = 0;
  {
    const ByteView bytes(data);
    size = bytes.bytes().size();
    py::gil_scoped_release release;
    s = api::info(bytes.bytes());
  }
  static const std::map<std::string, std::string> numpy_names{
      {"u8", "uint8"}, {"u16", "uint16"}, {"f16", "float16"}, {"f32", "float32"}, {"f64", "float64"}};
  py::dict d;
  d["kind"] = s.volume ? "volume" : "image";
  d["dtype"] = numpy_names.at(s.type);
  if (s.volume) {
    d["shape"] = py::make_tuple(s.dims[2], s.dims[1], s.dims[0]);
    d["grids"] = s.channels;
    d["max_error"] = s.max_error;
    d["sparse"] = s.sparse;
  } else {
    d["width"] = s.dims[0];
    d["height"] = s.dims[1];
    d["channels"] = s.channels;
    d["shape"] = s.channels > 1 ? py::make_tuple(s.dims[1], s.dims[0], s.channels)
                                : py::make_tuple(s.dims[1], s.dims[0]);
  }
  d["levels"] = s.levels;
  d["transform"] = s.transform;
  d["lossless"] = s.lossless;
  d["bytes"] = size;
  d["description"] = s.description;
  d["attributes"] = to_dict(s.attributes);
  return d;
}

}  // namespace

PYBIND11_MODULE(_pupwave, m) {
  m.doc() = "Pupwave wavelet codec (compiled part; use the pupwave package)";
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const api::Error& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    }
  });
  m.attr("__version__") = PUPWAVE_VERSION_STRING;
  // The fraction of the value range that bounds a float volume's error when no rate is given:
  // the package tightens it for float16 input.
  m.attr("DEFAULT_MAX_ERROR_REL") = api::kDefaultRelativeError;
  // Docstrings are the package's (pupwave/__init__.py); these say what differs from it.
  m.def("compress", &compress, py::arg("array"), py::arg("bpp") = py::none(), py::arg("psnr") = py::none(),
        py::arg("step") = py::none(), py::arg("lossless") = false, py::arg("transform") = py::none(),
        py::arg("levels") = py::none(), py::arg("effort") = 1, py::arg("entropy") = "auto",
        py::arg("tune") = "psnr", py::arg("attributes") = std::map<std::string, std::string>{},
        py::arg("threads") = py::none(),
        "pupwave.compress on a uint8/uint16/float16/float32 array; attributes (str -> str) are stored "
        "in the stream. Returns (bytes, miss): miss is the CLI's warning text for a missed bpp or psnr "
        "target, '' when it is met.");
  m.def("decompress", &decompress, py::arg("data"), py::arg("level") = 0, py::arg("threads") = py::none(),
        "(array of the stored dtype, the stream's text attributes as a dict).");
  m.def("compress_volume", &compress_volume, py::arg("array3d"), py::arg("max_error") = py::none(),
        py::arg("max_error_rel") = py::none(), py::arg("bpv") = py::none(), py::arg("psnr") = py::none(),
        py::arg("step") = py::none(), py::arg("lossless") = false, py::arg("transform") = py::none(),
        py::arg("levels") = py::none(), py::arg("brick") = py::none(),
        py::arg("attributes") = std::map<std::string, std::string>{}, py::arg("threads") = py::none(),
        py::arg("fill_value") = py::none(),
        "pupwave.compress_volume on a uint8/uint16/float32/float64 array; attributes (str -> str) are "
        "stored as the grid's metadata; fill_value: voxels equal to it are missing values (as NaN and "
        "infinities), kept exactly. Returns (bytes, miss) as compress does.");
  m.def("decompress_volume", &decompress_volume, py::arg("data"), py::arg("level") = 0,
        py::arg("threads") = py::none(), py::arg("box") = py::none(),
        "(array of the stored dtype, the grid's text attributes as a dict); box: (x0, y0, z0, x1, y1, z1).");
  m.def("info", &info, py::arg("data"), "Describe .pw bytes (every checksum verified) as a dict.");
}
