#pragma once
// The designed banks of the PUPs presets, stored in their to_bytes form (preset_banks.inc,
// written by tools/train/preset_bank_table.cpp), so that building a preset's transform (every encode
// and decode of a stream naming one) skips the 15-60 ms least-squares design. The stored bank
// equals design_preset's bit for bit (tests/pups/stored_presets_test.cpp), so streams do not
// change.

#include <optional>
#include <string_view>

#include "transforms/pups/filter_bank.h"

namespace pupwave::pups {

// The stored bank of preset `name`, or nothing when the table has no such preset.
std::optional<FilterBank> stored_preset_bank(std::string_view name);

}  // namespace pupwave::pups
