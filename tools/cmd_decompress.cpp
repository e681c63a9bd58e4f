// `pupwave decompress IN.pw OUT`: decode a stream (optionally at reduced resolution) and
// write the image in the format OUT's extension (or --format) names, decided before decoding;
// a volume stream is written as .vdb (all grids) or as a dense raw file of its stored type;
// --box decodes only a box of a volume grid, from the bricks it touches.
#include <charconv>
#include <chrono>
#include <cstdio>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "codec/image/image_codec.h"
#include "codec/image/image_strips.h"
#include "codec/volume/volume_codec.h"
#include "tools/atomic_file.h"
#include "tools/cli_errors.h"
#include "tools/cli_numbers.h"
#include "tools/cli_stdio.h"
#include "tools/commands.h"
#include "tools/image_io.h"
#include "tools/mapped_file.h"
#include "tools/png_io.h"
#include "tools/pnm_io.h"
#include "tools/volume_io.h"
#include "tools/volume_raw.h"
#include "transforms/separable.h"

namespace pupwave::cli {
namespace {

struct DecompressOptions {
  std::string input;
  std::string output;
  int level = 0;
  unsigned threads = 0;
  std::string grid;
  std::string box;                  // --box x0,y0,z0:x1,y1,z1; empty: the whole grid
  std::string format;               // --format: overrides OUT's extension
  std::filesystem::path format_as;  // the name whose extension picks the output format
  DecodeLimits limits;              // --max-pixels
  Verbosity verbosity;
};

bool wants_vdb(const DecompressOptions& opt) { return is_vdb_path(opt.format_as); }

// --box "x0,y0,z0:x1,y1,z1" (full-resolution voxels, half-open); what decode_volume_box checks
// against the grid is left to it.
VoxelBox parse_box(const std::string& text) {
  const auto bad = [&] {
    return std::invalid_argument("invalid --box '" + text +
                                 "' (expected x0,y0,z0:x1,y1,z1 with non-negative integers, the upper "
                                 "corner excluded)");
  };
  VoxelBox box;
  const char* at = text.data();
  const char* const end = text.data() + text.size();
  for (std::size_t i = 0; i < 6; ++i) {
    Extent& corner = i < 3 ? box.lo : box.hi;
    const auto [next, ec] = std::from_chars(at, end, corner[i % 3]);
    const char separator = i == 2 ? ':' : ',';
    if (ec != std::errc() || (i < 5 && (next == end || *next != separator))) throw bad();
    at = i < 5 ? next + 1 : next;
  }
  if (at != end) throw bad();
  return box;
}

// Refuses --box for an image stream.
void check_no_box(const DecompressOptions& opt) {
  if (!opt.box.empty())
    throw std::invalid_argument(opt.input +
                                ": --box applies to volume streams only, and this is an image stream");
}

// Grids of a volume stream to .vdb, or one grid (--grid, or the only one) to raw.
void write_volume_output(std::vector<VolumeGrid> grids, const DecompressOptions& opt) {
  if (!opt.grid.empty()) {
    std::erase_if(grids, [&](const VolumeGrid& g) { return g.name != opt.grid; });
    if (grids.empty()) throw std::invalid_argument("the stream has no grid named '" + opt.grid + "'");
  }
  if (wants_vdb(opt)) return write_vdb(grids, opt.output);
  if (grids.size() != 1)
    throw std::invalid_argument("the stream holds " + std::to_string(grids.size()) +
                                " grids; choose one with --grid NAME for raw output, or write .vdb");
  make_dense_box(grids[0], kMaxVdbBoxVoxels);  // raw output is the dense active bounding box
  write_raw_volume(grids[0].volume, opt.output);
}

// VolumeOutput::done_slabs for an output file mapped by MappedOutput: finished planes leave
// resident memory, so a decode holds about the slabs in flight, not the whole grid.
void release_planes(const void* context, const VolumeOutput& out, std::size_t z0, std::size_t z1) {
  const std::size_t plane = std::size_t(out.strides[2]) * bytes_per_voxel(out.storage);
  static_cast<const MappedOutput*>(context)->release(z0 * plane, (z1 - z0) * plane);
}

// One box grid to raw, decoded brick by brick into a buffer of its stored type (never held as
// double). False, having written nothing, when the grid needs decode_volumes (see
// decode_volume_into) or the output is .vdb.
bool decompress_raw_in_place(const std::vector<std::uint8_t>& bytes, const DecompressOptions& opt) {
  if (wants_vdb(opt)) return false;
  const auto start = std::chrono::steady_clock::now();
  std::optional<VolumeGrid> grid;
  // decode_volume_into asks for the output once it knows the grid's dims (never for the forms it
  // leaves to decode_volumes, when it returns nullopt having written nothing).
  const auto decode = [&](const std::function<VolumeOutput(const VolumeGrid&)>& allocate) {
    ElapsedLine line("pupwave: decompressing " + opt.input, !opt.verbosity.quiet);
    grid = decode_volume_into(bytes, opt.grid, opt.level, *make_pool_executor(opt.threads), opt.limits,
                              allocate);
  };
  // Decoded straight into the output file, mapped under its temporary name (write_output).
  struct NotInPlace {};
  try {
    write_output(opt.output, [&](const std::filesystem::path& tmp) {
      std::unique_ptr<MappedOutput> file;
      decode([&](const VolumeGrid& g) {
        file = std::make_unique<MappedOutput>(tmp, g.volume.count() * bytes_per_voxel(g.volume.type),
                                              opt.output);
        VolumeOutput out = contiguous_output(file->bytes().data(), g.volume.dims, g.volume.type);
        out.done_context = file.get();
        out.done_slabs = release_planes;
        return out;
      });
      if (!grid) throw NotInPlace{};  // nothing was created
      swap_to_little_endian(file->bytes(), grid->volume.type);
      file->finish();
    });
  } catch (const NotInPlace&) {
    return false;
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (std::FILE* status = opt.verbosity.stream())
    std::fprintf(status, "%s: grid '%s' %zux%zux%zu, %s, decoded in %.3f s\n", opt.output.c_str(),
                 grid->name.c_str(), grid->volume.dims[0], grid->volume.dims[1], grid->volume.dims[2],
                 to_string(grid->volume.type).c_str(), seconds);
  return true;
}

// --box: only the box of one grid (--grid, or the only one): raw output decoded straight into the
// output file mapped under its temporary name (write_output), in its stored type; .vdb through a
// VolumeGrid.
void decompress_volume_box(const std::vector<std::uint8_t>& bytes, const DecompressOptions& opt) {
  const VoxelBox box = parse_box(opt.box);
  const auto start = std::chrono::steady_clock::now();
  std::vector<VolumeGrid> grids(1);
  const auto ex = make_pool_executor(opt.threads);
  const auto decode_raw = [&](const std::filesystem::path& tmp) {
    std::unique_ptr<MappedOutput> file;
    grids[0] =
        decode_volume_box_into(bytes, opt.grid, box, opt.level, *ex, opt.limits, [&](const VolumeGrid& g) {
          file = std::make_unique<MappedOutput>(tmp, g.volume.count() * bytes_per_voxel(g.volume.type),
                                                opt.output);
          return contiguous_output(file->bytes().data(), g.volume.dims, g.volume.type);
        });
    swap_to_little_endian(file->bytes(), grids[0].volume.type);
    file->finish();
  };
  try {
    ElapsedLine line("pupwave: decompressing " + opt.input, !opt.verbosity.quiet);
    if (wants_vdb(opt))
      grids[0] = decode_volume_box(bytes, opt.grid, box, opt.level, *ex, opt.limits);
    else
      write_output(opt.output, decode_raw);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(opt.input + ": " + e.what());
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const VolumeGrid& g = grids[0];
  const std::string line = "grid '" + g.name + "' box " + to_string(box) + " at level " +
                           std::to_string(opt.level) + ", " + std::to_string(g.volume.dims[0]) + "x" +
                           std::to_string(g.volume.dims[1]) + "x" + std::to_string(g.volume.dims[2]) + ", " +
                           to_string(g.volume.type);
  if (wants_vdb(opt)) write_volume_output(std::move(grids), opt);
  if (std::FILE* status = opt.verbosity.stream())
    std::fprintf(status, "%s: %s, decoded in %.3f s\n", opt.output.c_str(), line.c_str(), seconds);
}

void run_decompress_volume(const std::vector<std::uint8_t>& bytes, const DecompressOptions& opt) {
  if (!opt.box.empty()) return decompress_volume_box(bytes, opt);
  if (decompress_raw_in_place(bytes, opt)) return;
  const auto start = std::chrono::steady_clock::now();
  auto grids = [&] {
    ElapsedLine line("pupwave: decompressing " + opt.input, !opt.verbosity.quiet);
    // .vdb is sparse: a sparse box grid comes as blocks of its non-empty bricks (docs/bitstream.md).
    const SparseBoxForm form = wants_vdb(opt) ? SparseBoxForm::blocks : SparseBoxForm::box;
    return decode_volumes(bytes, opt.level, *make_pool_executor(opt.threads), opt.limits, form);
  }();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  write_volume_output(grids, opt);
  std::FILE* status = opt.verbosity.stream();
  if (status == nullptr) return;
  for (const VolumeGrid& g : grids)
    std::fprintf(status, "%s: grid '%s' %zux%zux%zu, %s, decoded in %.3f s\n", opt.output.c_str(),
                 g.name.c_str(), g.volume.dims[0], g.volume.dims[1], g.volume.dims[2],
                 to_string(g.volume.type).c_str(), seconds);
}

// Rows per strip written: a strip is held three times (component rows, finished samples,
// packed bytes), so a few rows keep that small next to the pipeline's own buffers.
constexpr std::size_t kStripRows = 16;

// An integer image to binary PGM/PPM or PNG, decoded and written strip by strip, so neither
// the image nor its coefficients are ever whole in memory. False, having written nothing, when
// the stream or the output needs the whole image (decode_image and write_image then).
bool decompress_strips(std::span<const std::uint8_t> bytes, const DecompressOptions& opt) {
  const bool pnm = has_pnm_extension(opt.format_as), png = has_png_extension(opt.format_as);
  if (!opt.grid.empty() || is_volume_stream(bytes) || !(pnm || png)) return false;
  const auto start = std::chrono::steady_clock::now();
  const auto ex = make_pool_executor(opt.threads);
  const auto decoder = ImageStripDecoder::open(bytes, opt.level, *ex, opt.limits);
  if (!decoder) return false;
  const ImageMetadata metadata = decoder->metadata();
  if (pnm ? !binary_pnm_writable(opt.format_as, decoder->channels(), decoder->type())
          : !png_writable(opt.format_as, decoder->channels(), decoder->type(), metadata))
    return false;
  {
    ElapsedLine line("pupwave: decompressing " + opt.input, !opt.verbosity.quiet);
    write_output(opt.output, [&](const std::filesystem::path& tmp) {
      const auto next = [&] { return decoder->next(kStripRows); };
      if (pnm)
        write_binary_pnm_rows(tmp, decoder->width(), decoder->height(), decoder->channels(), decoder->type(),
                              next);
      else
        write_png_rows(tmp, decoder->width(), decoder->height(), decoder->channels(), decoder->type(),
                       metadata, next);
    });
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (std::FILE* status = opt.verbosity.stream())
    std::fprintf(status, "%s: %zux%zu, %zu channel(s), %s, decoded in %.3f s\n", opt.output.c_str(),
                 decoder->width(), decoder->height(), decoder->channels(), to_string(decoder->type()).c_str(),
                 seconds);
  return true;
}

// Refuses an image output whose format cannot be told before anything is decoded.
void check_image_output(const DecompressOptions& opt) {
  if (opt.format_as.empty()) return;  // stdout without --format: stdout_image_format
  check_image_format(opt.output, opt.format_as);
}

void run_decompress(const DecompressOptions& opt) {
  check_output_path(opt.output);
  std::error_code ec;
  const bool mappable = !is_stdio(opt.input) && std::filesystem::is_regular_file(opt.input, ec);
  if (mappable) {
    const MappedFile input(opt.input);  // the strip decoder reads only the pages it needs
    if (!is_volume_stream(input.bytes())) {
      check_no_box(opt);
      check_image_output(opt);
    }
    if (decompress_strips(input.bytes(), opt)) return;
  }
  // stdin, a FIFO or a device is read to its end.
  const auto bytes = read_file_bytes(opt.input);
  if (is_volume_stream(bytes)) return run_decompress_volume(bytes, opt);
  if (!opt.grid.empty()) throw std::invalid_argument("--grid applies to volume streams only");
  check_no_box(opt);
  check_image_output(opt);
  const auto start = std::chrono::steady_clock::now();
  const Image image = [&] {
    ElapsedLine line("pupwave: decompressing " + opt.input, !opt.verbosity.quiet);
    return decode_image(bytes, opt.level, *make_pool_executor(opt.threads), opt.limits);
  }();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  SampleType stored = image.type;
  write_image(image, opt.output, &stored,
              opt.format_as.empty() ? stdout_image_format(image.type) : opt.format_as);
  std::FILE* status = opt.verbosity.stream();
  if (status == nullptr) return;
  std::fprintf(status, "%s: %zux%zu, %zu channel(s), %s, decoded in %.3f s\n", opt.output.c_str(),
               image.width, image.height, image.channels, to_string(stored).c_str(), seconds);
}

}  // namespace

void add_decompress_command(CLI::App& app) {
  auto opt = std::make_shared<DecompressOptions>();
  auto* cmd = app.add_subcommand("decompress",
                                 "Decompress a .pw stream to an image file, or a volume stream to "
                                 ".vdb (all grids) or raw (dense, stored type)");
  cmd->add_option("IN", opt->input, "input .pw file, or - for stdin")
      ->required()
      ->check(existing_file_or_stdin());
  cmd->add_option("OUT", opt->output,
                  "output image; the format follows the extension; - for stdout (PNG, EXR for float "
                  "images, raw for a volume grid; status then goes to stderr)")
      ->required();
  cmd->add_option("--level", opt->level, "decode at 1/2^k resolution, reading only what it needs")
      ->check(non_negative_number());
  cmd->add_option("--threads", opt->threads, "worker threads (0: all cores)");
  cmd->add_option("--grid", opt->grid, "volume streams: only the grids of this name");
  cmd->add_option("--box", opt->box,
                  "volume streams: decode only the voxels [x0,x1) x [y0,y1) x [z0,z1) (full-resolution "
                  "coordinates, given as x0,y0,z0:x1,y1,z1) of one grid, from the bricks they touch; with "
                  "--level k, the level-k voxels whose footprint meets the box");
  cmd->add_option("--max-pixels", opt->limits.max_pixels,
                  "refuse a stream whose decoded pixels (images, at --level) or voxels (volumes, all grids) "
                  "exceed this (default 2^28)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--format", opt->format,
                  "output format, overriding OUT's extension (png, tif, exr, ppm, pgm, jpg, ...; vdb or raw "
                  "for volume streams): for outputs whose name tells none, as /dev/stdout or a FIFO");
  add_verbosity_flags(*cmd, opt->verbosity);
  cmd->callback([opt] {
    DecompressOptions o = *opt;
    o.verbosity.to_stderr = is_stdio(o.output);
    // The format is decided from the name (or --format) before anything is decoded.
    if (!o.format.empty() || !is_stdio(o.output)) o.format_as = format_name_path(o.output, o.format);
    naming_stream(o.input, [&] { run_decompress(o); });
  });
}

}  // namespace pupwave::cli
