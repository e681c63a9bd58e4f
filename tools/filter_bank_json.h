#pragma once
// JSON form of a PUPs filter bank for `pupwave filters ... --json`. It lives with the CLI,
// its only user, so that transforms/ needs no JSON library.

#include <nlohmann/json.hpp>

#include "transforms/pups/filter_bank.h"

namespace pupwave::cli {

// JSON form; doubles are written so that they parse back to the identical value.
nlohmann::json to_json(const pups::FilterBank& bank);
// Rebuilds a bank from to_json output; throws std::invalid_argument on missing or bad fields.
pups::FilterBank filter_bank_from_json(const nlohmann::json& j);

}  // namespace pupwave::cli
