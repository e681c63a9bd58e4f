#include "transforms/pups/stored_presets.h"

#include <cstdint>
#include <vector>

namespace pupwave::pups {
namespace {

struct StoredBank {
  const char* name;
  std::vector<std::uint8_t> bytes;
};

const std::vector<StoredBank>& stored_banks() {
  static const std::vector<StoredBank> banks = {
#include "transforms/pups/preset_banks.inc"
  };
  return banks;
}

}  // namespace

std::optional<FilterBank> stored_preset_bank(std::string_view name) {
  for (const StoredBank& b : stored_banks())
    if (name == b.name) return filter_bank_from_bytes(b.bytes);
  return std::nullopt;
}

}  // namespace pupwave::pups
