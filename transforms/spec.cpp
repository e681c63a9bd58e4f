#include "transforms/spec.h"

#include <stdexcept>

#include "transforms/cdf.h"
#include "transforms/kobbelt/kobbelt_transform.h"
#include "transforms/pups/pups_transform.h"

namespace pupwave {
namespace {

constexpr std::string_view kPupsPrefix = "pups:";
constexpr std::string_view kKobbeltPrefix = "kobbelt:";

std::string joined_specs() {
  std::string s;
  for (const auto& name : transform_specs()) s += (s.empty() ? "" : ", ") + name;
  return s;
}

}  // namespace

std::vector<std::string> transform_specs() {
  std::vector<std::string> specs{"cdf97", "cdf53"};
  for (auto& s : pups_transform_specs()) specs.push_back(std::move(s));
  for (auto& s : kobbelt_transform_specs()) specs.push_back(std::move(s));
  return specs;
}

void check_stream_spec(std::string_view spec) {
  if (spec == "cdf97" || spec == "cdf53") return;
  if (spec.starts_with(kKobbeltPrefix)) {
    make_kobbelt_transform_from_spec(spec.substr(kKobbeltPrefix.size()));  // a name: nothing designed
    return;
  }
  if (spec.starts_with(kPupsPrefix)) {
    pups::check_stream_design_bounds(pups::parse_design_spec(spec.substr(kPupsPrefix.size())));
    return;
  }
  make_transform(spec);  // throws the unknown-spec message
}

Transform1DPtr make_transform(std::string_view spec) {
  if (spec == "cdf97") return make_cdf97();
  if (spec == "cdf53") return make_cdf53();
  if (spec.starts_with(kKobbeltPrefix))
    return make_kobbelt_transform_from_spec(spec.substr(kKobbeltPrefix.size()));
  if (spec.starts_with(kPupsPrefix)) return make_pups_transform_from_spec(spec.substr(kPupsPrefix.size()));
  throw std::invalid_argument("unknown transform spec '" + std::string(spec) +
                              "'; valid specs: " + joined_specs());
}

}  // namespace pupwave
