// pupwave::api::info: the header fields of an image or volume stream, after the same full
// validation `pupwave info` does (every checksum verified).
#include "codec/api/api_attributes.h"
#include "codec/api/api_errors.h"
#include "codec/image/image_stream.h"
#include "codec/volume/volume_codec.h"
#include "codec/volume/volume_format.h"
#include "pupwave/pupwave.hpp"

namespace pupwave::api {

StreamInfo info(std::span<const std::uint8_t> stream) {
  return detail::translate_errors([&] {
    StreamInfo out;
    if (is_volume_stream(stream)) {
      const ParsedVolumeStream s = parse_volume_stream(stream, {}, SparseBoxCount::content);
      const VolumeStreamHeader& h = s.header;
      if (h.grids.empty()) throw DecodeError("volume stream holds no grid");
      const pupwave::Volume& v = h.grids[0].volume;
      out.volume = true;
      out.dims = {v.dims[0], v.dims[1], v.dims[2]};
      out.channels = h.grids.size();
      out.type = to_string(v.type);
      out.levels = h.levels;
      out.transform = h.spec;
      out.lossless = h.reversible;
      out.max_error = h.max_error;
      out.sparse = v.is_sparse();
      out.description = describe_volume_stream(stream);
      out.attributes = detail::text_attributes(h.grids[0].metadata);
      return out;
    }
    const ParsedStream s = parse_container(stream, 0);
    const StreamHeader& h = s.header;
    out.dims = {h.dims[0], h.dims[1], 1};
    out.channels = h.channels;
    static const char* const names[] = {"u8", "u16", "f16", "f32"};
    out.type = names[int(h.type) & 3];
    out.levels = h.levels;
    out.transform = h.spec;
    out.lossless = h.reversible;
    out.description = describe_stream(stream);
    out.attributes = detail::text_attributes(h.metadata);
    return out;
  });
}

}  // namespace pupwave::api
