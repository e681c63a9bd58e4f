#pragma once
// Image files <-> the library's planar Image: binary PGM/PPM (pnm_io.h), PNG (png_io.h), OpenEXR
// (exr_io.h), TIFF (tiff_io.h) and JPEG (jpeg_io.h) directly, for the kinds of file each of those
// headers names, giving what OpenImageIO gives for them; every other file through OpenImageIO
// (the module of oiio_module.h). The one entry point the CLI uses for image file formats.

#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "codec/image/image.h"

namespace pupwave::cli {

// Largest image accepted on read (samples over all channels), so a hostile header cannot make
// us allocate without bound.
inline constexpr std::size_t kMaxImageSamples = std::size_t(1) << 31;
// Most channels an image file may have (the codec's limit, kMaxChannels).
inline constexpr int kMaxImageChannels = 64;

// Reads the first subimage of an image file (PNG, JPEG, TIFF, PNM, EXR and whatever else
// OpenImageIO reads) exactly: 8/16-bit integer, half and float samples, 1 to 64 channels,
// with channel names, data/display windows and string/int/float attributes (Image::metadata).
// Alpha is kept unassociated (as stored). CMYK files are refused (never converted to RGB). Throws
// std::runtime_error with the reason.
Image read_image(const std::filesystem::path& path);

// An image file's rows, top to bottom, a strip at a time: read_image's samples and metadata
// without the whole image in memory where the file allows it.
class ImageRowReader {
 public:
  virtual ~ImageRowReader() = default;
  virtual std::size_t width() const = 0;
  virtual std::size_t height() const = 0;
  virtual std::size_t channels() const = 0;
  virtual SampleType type() const = 0;
  virtual const ImageMetadata& metadata() const = 0;
  // The next rows (at most `rows`, at least 1 until the end) as an image of width() columns;
  // height 0 at the end. Throws std::runtime_error naming the file for a bad one.
  virtual Image next(std::size_t rows) = 0;
};

// The rows of an image file (as read_image reads it): a binary 8-bit PGM/PPM mapped and read in
// place, a PNG, EXR, TIFF or JPEG through its library and another scanline file through
// OpenImageIO a strip at a time; a 16-bit PGM/PPM or a tiled file OpenImageIO reads is read
// whole first (a tiled EXR read natively comes through the OpenEXR library's row of tiles).
std::unique_ptr<ImageRowReader> open_image_rows(const std::filesystem::path& path);

// Describes an image file without decoding its pixels (format, size, channels, type); the natively
// read formats without loading OpenImageIO.
std::string describe_image_file(const std::filesystem::path& path);

// The name whose extension picks an output's format: `path` itself, or with a format name
// (--format png) a name ending in that extension, for outputs whose own name says nothing
// (stdout, /dev/stdout, a FIFO).
std::filesystem::path format_name_path(const std::filesystem::path& path, const std::string& format);

// The format an image goes to stdout in without --format: PNG for integer samples, EXR (which
// keeps their values) for float ones. A name for write_image's format_as.
std::filesystem::path stdout_image_format(SampleType type);

// Throws std::runtime_error naming `path` unless an image format can be written under
// `format_as`'s extension; called before decoding, so an unwritable name costs nothing.
void check_image_format(const std::filesystem::path& path, const std::filesystem::path& format_as);

// Writes an image to `path` (see write_output: a file atomically, a stream in place), in the
// format `format_as`'s extension names (default: path's). When the format cannot store the
// image's sample type (float to PNG, 16-bit to JPEG...) samples are converted to the closest
// type it can store, mapping the nominal range (integer max <-> 1.0) with rounding and
// clamping; `stored_as`, if given, receives the type written.
void write_image(const Image& image, const std::filesystem::path& path, SampleType* stored_as = nullptr,
                 const std::filesystem::path& format_as = {});

// write_image of the rows of `rows` (as they come, a strip at a time, so neither the input nor
// the output is whole in memory): returns the sample type stored.
SampleType write_image_rows(ImageRowReader& rows, const std::filesystem::path& path,
                            const std::filesystem::path& format_as = {});

// The sample type `write_image` would store `type` as in a file with this path's extension.
SampleType storable_type(const std::filesystem::path& path, SampleType type);

// Converts samples between types through the nominal range (255 <-> 65535 <-> 1.0), with
// rounding and clamping for integer targets, in place. Identity when the types match.
Image convert_sample_type(Image image, SampleType target);

}  // namespace pupwave::cli
