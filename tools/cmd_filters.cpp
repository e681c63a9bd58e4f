// `pupwave filters`: design PUPs filter banks, list the presets and transform specs with their
// figures of merit, show one, condition numbers; `search` is in cmd_filters_search.cpp.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <exception>
#include <iostream>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "tools/cli_numbers.h"
#include "tools/cli_stdio.h"
#include "tools/commands.h"
#include "tools/filter_bank_json.h"
#include "tools/filters_report.h"
#include "transforms/analysis/merit.h"
#include "transforms/pups/design.h"
#include "transforms/pups/pups_transform.h"
#include "transforms/pups/refinement.h"
#include "transforms/spec.h"

namespace pupwave::cli {

namespace {

using pups::FilterBank;

struct DesignOptions {
  std::string weight;
  int degree = 3;
  std::vector<double> coeffs;
  std::vector<double> domain;
  double c = 0, sigma = 0;
  bool optimize_sigma = false;
  int samples = 100000;
  std::optional<int> extend;
  std::optional<double> threshold;
  bool json = false;
};

void emit(const FilterBank& bank, bool json) {
  if (json)
    std::cout << to_json(bank).dump(2) << '\n';
  else
    print_bank(std::cout, bank, pups::BoundaryRule::wire_hss);
}

// The figures of a bank as JSON (for `filters show --json`).
nlohmann::json merit_json(const merit::Merit& m) {
  const merit::CodingVerdict v = merit::coding_verdict(m);
  auto number = [](double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); };
  return {{"coding_gain_db", number(m.coding_gain_db)},
          {"interior_coding_gain_db", number(m.interior_coding_gain_db)},
          {"condition", number(m.condition)},
          {"condition_one_level", number(m.condition_one_level)},
          {"coarse_gain", m.coarse_gain},
          {"coarse_rms", m.coarse_rms},
          {"analysis_moments", m.analysis_moments},
          {"synthesis_moments", m.synthesis_moments},
          {"dc_leak", number(m.dc_leak)},
          {"coding", v.coding},
          {"reason", v.reason}};
}

pups::DesignParams to_params(const DesignOptions& o) {
  pups::DesignParams p;
  p.weight = pups::weight_kind_from_string(o.weight);
  p.degree = o.degree;
  p.coeffs = o.coeffs;
  if (p.weight == pups::WeightKind::polynomial) {
    if (o.domain.size() != 2) throw std::invalid_argument("--domain needs two numbers a,b");
    p.domain_lo = o.domain[0];
    p.domain_hi = o.domain[1];
  }
  p.c = o.c;
  p.sigma = o.sigma;
  p.samples = o.samples;
  return p;
}

void run_design(const DesignOptions& o) {
  pups::DesignParams p = to_params(o);
  if (o.optimize_sigma) p.sigma = pups::optimize_sigma(p);
  pups::ExtensionRule rule;
  if (o.threshold)
    rule.threshold = *o.threshold;
  else
    rule.extension = o.extend.value_or(0);
  emit(pups::design(p, rule), o.json);
}

void add_design(CLI::App& filters) {
  auto o = std::make_shared<DesignOptions>();
  auto* cmd = filters.add_subcommand("design", "Design a PUPs filter bank from a weight function");
  cmd->add_option("--weight", o->weight, "weight function")
      ->required()
      ->check(CLI::IsMember({"bspline", "polynomial", "cinpact", "cinpact-interp"}));
  cmd->add_option("--degree", o->degree, "B-spline degree")->capture_default_str();
  cmd->add_option("--coeffs", o->coeffs, "polynomial coefficients a0 a1 ... (Eq. 32)")->delimiter(',');
  cmd->add_option("--domain", o->domain, "polynomial domain a,b")->delimiter(',')->expected(2);
  cmd->add_option("--c", o->c, "CINPACT support radius c")->check(positive_number());
  cmd->add_option("--sigma", o->sigma, "CINPACT sigma")->check(positive_number());
  cmd->add_flag("--optimize-sigma", o->optimize_sigma, "search the sigma that minimizes E for c");
  cmd->add_option("--samples", o->samples, "samples of the refinement system")->capture_default_str();
  auto* ext = cmd->add_option("--extend", o->extend, "bandwidth extension l (even)");
  cmd->add_option("--threshold", o->threshold, "extend until the orthogonality error is below T")
      ->check(positive_number())
      ->excludes(ext);
  cmd->add_flag("--json", o->json, "print JSON instead of a table");
  add_report_verbosity_flags(*cmd);
  cmd->callback([o] { run_design(*o); });
}

// Figures of every preset on two threads (each bank takes a few tenths of a second).
std::vector<merit::Merit> preset_merits() {
  const auto& all = pups::presets();
  std::vector<merit::Merit> out(all.size());
  std::atomic<std::size_t> next{0};
  std::exception_ptr failure;
  std::mutex failure_mutex;
  auto work = [&] {
    for (std::size_t i; (i = next++) < all.size();) try {
        out[i] = merit::figures_of_merit(*make_pups_transform_from_spec(all[i].name));
      } catch (...) {
        const std::lock_guard lock(failure_mutex);
        failure = std::current_exception();
      }
  };
  std::thread helper(work);
  work();
  helper.join();
  if (failure) std::rethrow_exception(failure);
  return out;
}

void add_list(CLI::App& filters) {
  auto* cmd =
      filters.add_subcommand("list", "List transform specs and PUPs presets with their figures of merit");
  add_report_verbosity_flags(*cmd);
  cmd->callback([] {
    std::cout << "Transform specs:\n";
    std::vector<std::string> specs = transform_specs();
    for (auto& s : pups_transform_specs())
      if (std::find(specs.begin(), specs.end(), s) == specs.end()) specs.push_back(s);
    for (const auto& s : specs) std::cout << "  " << s << '\n';
    const merit::MeritOptions o;
    std::cout << "PUPs presets (transform spec pups:<name>; figures for AR(1) rho = " << fmt(o.rho, 3) << ", "
              << o.levels << " levels, N = " << o.n
              << "; CDF 9/7: " << fmt(merit::coding_gain_db(*make_transform("cdf97"), o), 4) << " dB):\n";
    const std::vector<merit::Merit> merits = preset_merits();
    for (std::size_t i = 0; i < merits.size(); ++i) {
      const auto& p = pups::presets()[i];
      std::cout << "  " << p.name << "  " << p.description << "\n    " << merit_summary(merits[i])
                << "\n    use: " << use_line(merits[i]) << '\n';
    }
    std::cout << "Custom PUPs designs: pups:<weight>(key=value,...), e.g.\n"
                 "  pups:bspline(degree=3)  pups:cinpact(c=3,sigma=7.27,l=14)\n"
                 "  pups:cinpact-interp(c=5,sigma=4.79,t=0.01,boundary=wss)\n"
                 "  pups:polynomial(coeffs=64:0:-48:0:12:0:-1,domain=-2:2)\n"
                 "Search designs: pupwave filters search --help\n";
  });
}

void add_show(CLI::App& filters) {
  auto name = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  auto* cmd =
      filters.add_subcommand("show", "Show a preset or a pups spec body in full, with its figures of merit");
  cmd->add_option("NAME", *name, "preset name or <weight>(...) spec body")->required();
  cmd->add_flag("--json", *json, "print JSON instead of a table");
  add_report_verbosity_flags(*cmd);
  cmd->callback([name, json] {
    std::string body = *name;
    if (body.rfind("pups:", 0) == 0) body = body.substr(5);
    const pups::DesignSpec spec = pups::parse_design_spec(body);
    const FilterBank bank = pups::design(spec);
    const merit::MeritOptions o;
    const merit::Merit m =
        merit::figures_of_merit(*make_pups_transform(bank, "pups:" + body, spec.boundary), o);
    if (*json) {
      nlohmann::json j = to_json(bank);
      j["boundary"] = spec.boundary == pups::BoundaryRule::line_wss ? "wss" : "hss";
      j["figures"] = merit_json(m);
      std::cout << j.dump(2) << '\n';
      return;
    }
    print_bank(std::cout, bank, spec.boundary);
    print_merit(std::cout, m, o);
  });
}

// Condition numbers of the finite analysis operator, as reported in docs/pups.md.
void add_condition(CLI::App& filters) {
  auto spec = std::make_shared<std::string>();
  auto max_n = std::make_shared<int>(300);
  auto sizes = std::make_shared<std::vector<int>>(std::vector<int>{511, 512, 513, 1023});
  auto* cmd = filters.add_subcommand("condition", "Condition numbers of a PUPs transform for N = 1..max-n");
  cmd->add_option("SPEC", *spec, "preset name or <weight>(...) spec body")->required();
  cmd->add_option("--max-n", *max_n, "largest N of the full scan")
      ->capture_default_str()
      ->check(CLI::Range(1, 2048));
  cmd->add_option("--sizes", *sizes, "further sizes")->delimiter(',')->check(CLI::Range(1, 4096));
  add_report_verbosity_flags(*cmd);
  cmd->callback([spec, max_n, sizes] {
    std::string body = *spec;
    if (body.rfind("pups:", 0) == 0) body = body.substr(5);
    const Transform1DPtr t = make_pups_transform_from_spec(body);
    double worst1 = 0, worst2 = 0;
    int at1 = 0, at2 = 0;
    for (int n = 1; n <= *max_n; ++n) {
      const double c1 = analysis_condition_number(*t, static_cast<std::size_t>(n), false);
      const double c2 = analysis_condition_number(*t, static_cast<std::size_t>(n), true);
      if (c1 > worst1) worst1 = c1, at1 = n;
      if (c2 > worst2) worst2 = c2, at2 = n;
    }
    std::cout << t->spec() << "\nN = 1.." << *max_n << ": max 1-norm " << fmt(worst1) << " (N=" << at1
              << "), max 2-norm " << fmt(worst2) << " (N=" << at2 << ")\n";
    for (int n : *sizes)
      std::cout << "N = " << n << ": 1-norm "
                << fmt(analysis_condition_number(*t, static_cast<std::size_t>(n), false)) << ", 2-norm "
                << fmt(analysis_condition_number(*t, static_cast<std::size_t>(n), true)) << '\n';
  });
}

}  // namespace

void add_filters_command(CLI::App& app) {
  auto* filters = app.add_subcommand("filters", "Design, list and show filter banks");
  filters->require_subcommand(1);
  add_design(*filters);
  add_list(*filters);
  add_show(*filters);
  add_condition(*filters);
  add_search(*filters);
}

}  // namespace pupwave::cli
