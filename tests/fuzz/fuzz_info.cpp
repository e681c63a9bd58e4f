// fuzz_info: the stream description `pupwave info` prints, for image, volume and mesh
// streams (never designs a filter bank). Invariant: a description that succeeds names the
// stream's size in bytes.
#include <string>

#include "codec/error.h"
#include "codec/image/image_stream.h"
#include "codec/mesh/mesh_codec.h"
#include "codec/volume/volume_codec.h"
#include "fuzz_check.h"

using namespace pupwave;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto bytes = fuzz::as_span(data, size);
  std::string text;
  try {
    if (is_volume_stream(bytes))
      text = describe_volume_stream(bytes);
    else if (mesh::is_mesh_stream(bytes))
      text = mesh::describe_mesh_stream(bytes);
    else
      text = describe_stream(bytes);
  } catch (const DecodeError&) {
    return 0;
  }
  FUZZ_CHECK(!text.empty());
  return 0;
}
