#include "codec/image/image.h"

namespace pupwave {

std::string to_string(SampleType type) {
  switch (type) {
    case SampleType::u8: return "uint8";
    case SampleType::u16: return "uint16";
    case SampleType::f16: return "half";
    case SampleType::f32: return "float";
  }
  return "unknown";
}

int bits_per_sample(SampleType type) {
  switch (type) {
    case SampleType::u8: return 8;
    case SampleType::u16: return 16;
    case SampleType::f16: return 16;
    case SampleType::f32: return 32;
  }
  return 0;
}

bool is_integer(SampleType type) { return type == SampleType::u8 || type == SampleType::u16; }

double nominal_max(SampleType type) {
  switch (type) {
    case SampleType::u8: return 255.0;
    case SampleType::u16: return 65535.0;
    default: return 1.0;
  }
}

}  // namespace pupwave
