#include "tools/filter_bank_json.h"

#include <stdexcept>
#include <string>
#include <vector>

namespace pupwave::cli {

namespace {

using pups::DesignParams;
using pups::Filter;
using pups::FilterBank;

nlohmann::json filter_json(const Filter& f) { return {{"offset", f.offset}, {"taps", f.taps}}; }

Filter filter_from_json(const nlohmann::json& j, const char* what) {
  if (!j.is_object() || !j.contains("offset") || !j.contains("taps"))
    throw std::invalid_argument(std::string("filter bank JSON: bad filter ") + what);
  Filter f{j.at("taps").get<std::vector<double>>(), j.at("offset").get<int>()};
  if (f.taps.empty()) throw std::invalid_argument(std::string("filter bank JSON: empty ") + what);
  return f;
}

}  // namespace

nlohmann::json to_json(const FilterBank& bank) {
  const DesignParams& d = bank.design;
  // nlohmann::json prints doubles with 17 significant digits, which round-trips exactly.
  return {{"name", bank.name},
          {"design",
           {{"weight", pups::to_string(d.weight)},
            {"degree", d.degree},
            {"coeffs", d.coeffs},
            {"domain", {d.domain_lo, d.domain_hi}},
            {"c", d.c},
            {"sigma", d.sigma},
            {"samples", d.samples},
            {"extension", d.extension}}},
          {"P", filter_json(bank.P)},
          {"Q", filter_json(bank.Q)},
          {"A", filter_json(bank.A)},
          {"B", filter_json(bank.B)},
          {"refinement_error", bank.refinement_error},
          {"orthogonality_error", bank.orthogonality_error},
          {"shift", bank.shift}};
}

FilterBank filter_bank_from_json(const nlohmann::json& j) {
  try {
    FilterBank b;
    b.name = j.at("name").get<std::string>();
    const auto& d = j.at("design");
    b.design.weight = pups::weight_kind_from_string(d.at("weight").get<std::string>());
    b.design.degree = d.at("degree").get<int>();
    b.design.coeffs = d.at("coeffs").get<std::vector<double>>();
    const auto domain = d.at("domain").get<std::vector<double>>();
    if (domain.size() != 2) throw std::invalid_argument("domain must have two numbers");
    b.design.domain_lo = domain[0];
    b.design.domain_hi = domain[1];
    b.design.c = d.at("c").get<double>();
    b.design.sigma = d.at("sigma").get<double>();
    b.design.samples = d.at("samples").get<int>();
    b.design.extension = d.at("extension").get<int>();
    b.P = filter_from_json(j.at("P"), "P");
    b.Q = filter_from_json(j.at("Q"), "Q");
    b.A = filter_from_json(j.at("A"), "A");
    b.B = filter_from_json(j.at("B"), "B");
    b.refinement_error = j.at("refinement_error").get<double>();
    b.orthogonality_error = j.at("orthogonality_error").get<double>();
    b.shift = j.at("shift").get<int>();
    return b;
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(std::string("filter bank JSON: ") + e.what());
  }
}

}  // namespace pupwave::cli
