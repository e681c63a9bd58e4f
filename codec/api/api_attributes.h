#pragma once
// Internal to codec/api: the public text attributes (api::Attribute) mapped onto what the
// streams hold, an image's META chunk attributes and a volume grid's metadata.

#include <map>
#include <set>
#include <string>
#include <vector>

#include "codec/api/api_errors.h"
#include "codec/image/image.h"
#include "codec/image/image_stream_extras.h"
#include "codec/volume/volume.h"
#include "pupwave/pupwave.hpp"

namespace pupwave::api::detail {

// Refuses a list the stream could not hold as given (the writers would clip or reject it).
inline void check_attributes(const std::vector<Attribute>& list) {
  if (list.size() > kMaxAttributes) fail("at most " + std::to_string(kMaxAttributes) + " attributes");
  std::set<std::string> names;
  for (const Attribute& a : list) {
    if (a.name.empty() || a.name.size() > kMaxNameLength)
      fail("attribute names must have 1 to " + std::to_string(kMaxNameLength) + " bytes");
    if (a.value.size() > 65535) fail("attribute '" + a.name + "': values have at most 65535 bytes");
    if (!names.insert(a.name).second) fail("attribute '" + a.name + "' is given twice");
  }
}

inline ImageMetadata image_metadata(const std::vector<Attribute>& list) {
  ImageMetadata m;
  for (const Attribute& a : list)
    m.attributes.push_back({a.name, ImageAttribute::Kind::string, a.value, 0, 0.0});
  return m;
}

inline std::vector<Attribute> text_attributes(const ImageMetadata& m) {
  std::vector<Attribute> out;
  for (const ImageAttribute& a : m.attributes)
    if (a.kind == ImageAttribute::Kind::string) out.push_back({a.name, a.text});
  return out;
}

inline std::map<std::string, MetaValue> grid_metadata(const std::vector<Attribute>& list) {
  std::map<std::string, MetaValue> m;
  for (const Attribute& a : list) m[a.name] = MetaValue{MetaValue::Kind::string, a.value, 0, {0, 0, 0}};
  return m;
}

inline std::vector<Attribute> text_attributes(const std::map<std::string, MetaValue>& m) {
  std::vector<Attribute> out;
  for (const auto& [name, value] : m)
    if (value.kind == MetaValue::Kind::string) out.push_back({name, value.text});
  return out;
}

}  // namespace pupwave::api::detail
