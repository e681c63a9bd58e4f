#include "transforms/pups/design.h"

#include <charconv>
#include <cmath>
#include <map>
#include <optional>
#include <stdexcept>

#include "transforms/pups/refinement.h"

namespace pupwave::pups {

namespace {

DesignParams bspline_params(int degree) {
  DesignParams p;
  p.weight = WeightKind::bspline;
  p.degree = degree;
  return p;
}

DesignParams cinpact_params(WeightKind kind, double c, double sigma, int l) {
  DesignParams p;
  p.weight = kind;
  p.c = c;
  p.sigma = sigma;
  p.extension = l;
  return p;
}

DesignParams poly10_params() {
  DesignParams p;  // (u^2 - 4)^5 on [-2, 2]: Table 1 row 2, the degree-10 masks of Fig. 9/10
  p.weight = WeightKind::polynomial;
  p.coeffs = {-1024, 0, 1280, 0, -640, 0, 160, 0, -20, 0, 1};
  p.domain_lo = -2;
  p.domain_hi = 2;
  return p;
}

// Degree-16 weight on [-3, 3] whose refinement is the 7-tap mask with 4 vanishing moments of
// largest coding gain, 2 cos(w/2)^4 (1 + 2.75 sin(w/2)^2) (`filters search --weight polynomial
// --moments 4`, t = 2.75; docs/pups.md). Only even powers are non-zero.
DesignParams poly16_vm4_params() {
  const double even[] = {4.920068656979502,   -11.297087199932182,    9.150327983296682,
                         -3.902889015809956,  0.999589395428406,      -0.15935165785936276,
                         0.01546976092278702, -0.0008354565659863358, 1.9205234231317668e-05};
  DesignParams p;
  p.weight = WeightKind::polynomial;
  for (double a : even) p.coeffs.insert(p.coeffs.end(), {a, 0.0});
  p.coeffs.pop_back();
  p.domain_lo = -3;
  p.domain_hi = 3;
  p.extension = 8;
  return p;
}

DesignParams with_extension(DesignParams p, int l) {
  p.extension = l;
  return p;
}

std::vector<Preset> make_presets() {
  const auto cin = WeightKind::cinpact, cinI = WeightKind::cinpact_interp;
  return {
      {"chaikin", "quadratic B-spline (Chaikin 1/4 3/4), minimal masks", bspline_params(2)},
      {"cubic-bspline", "cubic B-spline (1 4 6 4 1)/8, minimal masks", bspline_params(3)},
      {"cinpact-c3", "CINPACT c=3 sigma=7.27 (Table 3), minimal masks", cinpact_params(cin, 3, 7.27, 0)},
      // l = 14 is the shortest extension whose error is below the 0.285485 the paper
      // reports for its extended c=3 masks (Fig. 12).
      {"cinpact-c3-ext", "CINPACT c=3 sigma=7.27, extended masks l=14", cinpact_params(cin, 3, 7.27, 14)},
      {"cinpact-interp-c5", "interpolating CINPACT c=5 sigma=4.79 (Table 2), minimal masks",
       cinpact_params(cinI, 5, 4.79, 0)},
      {"cinpact-interp-c5-ext", "interpolating CINPACT c=5 sigma=4.79, extended l=32 (Fig. 16)",
       cinpact_params(cinI, 5, 4.79, 32)},
      {"poly10", "degree-10 polynomial (u^2-4)^5 on [-2,2] (Table 1), minimal masks", poly10_params()},
      // Coding presets found by `filters search` (docs/pups.md, Design search).
      {"chaikin-ext", "quadratic B-spline, extended l=8: Chaikin made fit for coding",
       with_extension(bspline_params(2), 8)},
      {"cinpact-interp-vm4",
       "interpolating CINPACT, (c, sigma) giving B 4 vanishing moments, l=16, JPEG 2000 boundaries",
       cinpact_params(cinI, 4.9135160235465722, 4.9356708723649314, 16), BoundaryRule::line_wss},
      {"poly16-vm4-cg",
       "degree-16 polynomial refining to the 4-vanishing-moment 7-tap mask of largest coding gain, l=8, "
       "JPEG 2000 boundaries",
       poly16_vm4_params(), BoundaryRule::line_wss},
  };
}

// Drops exactly-zero end coefficients: an interpolating weight whose support ends on an even
// index (c in (2k-1, 2k]) has hard zeros there, which would make B's end taps zero and the
// hard system of Eq. 41 singular. Presets have none, so their banks are unchanged.
Refinement trimmed(Refinement r) {
  while (r.coeffs.size() > 2 && r.coeffs.back() == 0.0) r.coeffs.pop_back();
  while (r.coeffs.size() > 2 && r.coeffs.front() == 0.0) {
    r.coeffs.erase(r.coeffs.begin());
    ++r.first;
  }
  return r;
}

// Shortest decimal text that parses back to exactly x.
std::string number(double x) {
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, res.ptr);
}

double parse_number(std::string_view key, std::string_view text) {
  double v = 0;
  const auto res = std::from_chars(text.data(), text.data() + text.size(), v);
  if (res.ec != std::errc() || res.ptr != text.data() + text.size() || !std::isfinite(v))
    throw std::invalid_argument("pups spec: '" + std::string(key) + "' needs a number, got '" +
                                std::string(text) + "'");
  return v;
}

int parse_int(std::string_view key, std::string_view text) {
  const double v = parse_number(key, text);
  if (v != std::floor(v) || std::abs(v) > 1e8)
    throw std::invalid_argument("pups spec: '" + std::string(key) + "' needs an integer");
  return static_cast<int>(v);
}

std::vector<double> parse_list(std::string_view key, std::string_view text) {
  std::vector<double> out;
  std::size_t start = 0;
  while (true) {
    const std::size_t colon = text.find(':', start);
    out.push_back(parse_number(key, text.substr(start, colon - start)));
    if (colon == std::string_view::npos) break;
    start = colon + 1;
  }
  return out;
}

// key=value pairs of "k1=v1,k2=v2"; rejects duplicates and malformed items.
std::map<std::string, std::string, std::less<>> parse_pairs(std::string_view args) {
  std::map<std::string, std::string, std::less<>> kv;
  std::size_t start = 0;
  while (start <= args.size() && !args.empty()) {
    const std::size_t comma = std::min(args.find(',', start), args.size());
    const std::string_view item = args.substr(start, comma - start);
    const std::size_t eq = item.find('=');
    if (eq == std::string_view::npos || eq == 0 || eq + 1 == item.size())
      throw std::invalid_argument("pups spec: expected key=value, got '" + std::string(item) + "'");
    if (!kv.emplace(std::string(item.substr(0, eq)), std::string(item.substr(eq + 1))).second)
      throw std::invalid_argument("pups spec: duplicate key '" + std::string(item.substr(0, eq)) + "'");
    start = comma + 1;
  }
  return kv;
}

// Removes and returns kv[key]; throws if it is required and missing.
std::optional<std::string> take(std::map<std::string, std::string, std::less<>>& kv, std::string_view key,
                                bool required, std::string_view weight) {
  auto it = kv.find(key);
  if (it == kv.end()) {
    if (required)
      throw std::invalid_argument("pups spec: " + std::string(weight) + " needs " + std::string(key) + "=");
    return std::nullopt;
  }
  std::string v = it->second;
  kv.erase(it);
  return v;
}

void parse_weight_keys(std::map<std::string, std::string, std::less<>>& kv, DesignParams& p,
                       std::string_view w) {
  switch (p.weight) {
    case WeightKind::bspline: p.degree = parse_int("degree", *take(kv, "degree", true, w)); break;
    case WeightKind::polynomial: {
      p.coeffs = parse_list("coeffs", *take(kv, "coeffs", true, w));
      const auto dom = parse_list("domain", *take(kv, "domain", true, w));
      if (dom.size() != 2) throw std::invalid_argument("pups spec: domain=lo:hi needs two numbers");
      p.domain_lo = dom[0];
      p.domain_hi = dom[1];
      break;
    }
    case WeightKind::cinpact:
    case WeightKind::cinpact_interp:
      p.c = parse_number("c", *take(kv, "c", true, w));
      p.sigma = parse_number("sigma", *take(kv, "sigma", true, w));
      break;
    case WeightKind::given:
      throw std::invalid_argument("pups spec: 'given' banks cannot be described by a spec");
  }
}

}  // namespace

FilterBank design(const DesignParams& params, const ExtensionRule& rule) {
  const PlacedWeight weight = make_weight(params);
  const Refinement r = trimmed(refine(weight, params.samples));
  FilterBank bank = design_bank(r.coeffs, r.first, rule);
  const int l = bank.design.extension;
  bank.design = params;
  bank.design.extension = l;
  bank.refinement_error = r.error;
  return bank;
}

const std::vector<Preset>& presets() {
  static const std::vector<Preset> all = make_presets();
  return all;
}

FilterBank design_preset(std::string_view name) {
  for (const auto& p : presets())
    if (p.name == name) {
      FilterBank bank = design(p.params, ExtensionRule{p.params.extension});
      bank.name = p.name;
      return bank;
    }
  std::string known;
  for (const auto& p : presets()) known += (known.empty() ? "" : ", ") + p.name;
  throw std::invalid_argument("unknown PUPs preset '" + std::string(name) + "' (known: " + known + ")");
}

DesignSpec parse_design_spec(std::string_view body) {
  DesignSpec spec;
  const std::size_t open = body.find('(');
  if (open == std::string_view::npos) {
    for (const auto& p : presets())
      if (p.name == body) {
        spec.preset = p.name;
        spec.boundary = p.boundary;
        return spec;
      }
    design_preset(body);  // throws the "unknown preset" message listing the known names
  }
  if (body.empty() || body.back() != ')')
    throw std::invalid_argument("pups spec '" + std::string(body) + "': expected <weight>(key=value,...)");
  const std::string weight(body.substr(0, open));
  spec.params.weight = weight_kind_from_string(weight);
  auto kv = parse_pairs(body.substr(open + 1, body.size() - open - 2));
  parse_weight_keys(kv, spec.params, weight);
  if (auto s = take(kv, "samples", false, weight)) spec.params.samples = parse_int("samples", *s);
  if (auto b = take(kv, "boundary", false, weight)) {
    if (*b != "hss" && *b != "wss")
      throw std::invalid_argument("pups spec: boundary must be hss or wss, got '" + *b + "'");
    spec.boundary = *b == "wss" ? BoundaryRule::line_wss : BoundaryRule::wire_hss;
  }
  const auto l = take(kv, "l", false, weight), t = take(kv, "t", false, weight);
  if (l && t) throw std::invalid_argument("pups spec: give l= or t=, not both");
  if (t)
    spec.rule.threshold = parse_number("t", *t);
  else
    spec.rule.extension = l ? parse_int("l", *l) : 0;
  if (!kv.empty())
    throw std::invalid_argument("pups spec: unknown key '" + kv.begin()->first + "' for " + weight);
  return spec;
}

void check_stream_design_bounds(const DesignSpec& spec) {
  if (!spec.preset.empty()) return;
  const DesignParams& p = spec.params;
  auto refuse = [](const std::string& what) {
    throw std::invalid_argument("pups spec in a stream: " + what + " (docs/bitstream.md, Decoder bounds)");
  };
  if (p.coeffs.size() > kStreamMaxCoeffs) refuse("more than 64 polynomial coefficients");
  const int width = make_weight(p).width;  // validates the weight's own parameters; designs nothing
  if (width > kStreamMaxWidth) refuse("support " + std::to_string(width) + " over 64");
  if (p.samples < 1 || p.samples > kStreamMaxSamples) refuse("samples outside 1..1000000");
  if (std::size_t(p.samples) * std::size_t(width + 1) > kStreamMaxSystem)
    refuse("samples x (support + 1) over 2^23");
  if (spec.rule.extension && (*spec.rule.extension < 0 || *spec.rule.extension > kStreamMaxExtension))
    refuse("extension l outside 0..64");
  if (!spec.rule.extension && spec.rule.max_extension > kStreamMaxExtension)
    refuse("extension search over 64");
}

FilterBank design(const DesignSpec& spec) {
  if (!spec.preset.empty()) return design_preset(spec.preset);
  return design(spec.params, spec.rule);
}

std::string canonical_spec_body(const FilterBank& bank, BoundaryRule boundary) {
  for (const auto& p : presets())
    if (p.name == bank.name) return p.name;
  const DesignParams& d = bank.design;
  std::string args;
  switch (d.weight) {
    case WeightKind::bspline: args = "degree=" + std::to_string(d.degree); break;
    case WeightKind::polynomial:
      args = "coeffs=";
      for (std::size_t i = 0; i < d.coeffs.size(); ++i) args += (i ? ":" : "") + number(d.coeffs[i]);
      args += ",domain=" + number(d.domain_lo) + ":" + number(d.domain_hi);
      break;
    case WeightKind::cinpact:
    case WeightKind::cinpact_interp: args = "c=" + number(d.c) + ",sigma=" + number(d.sigma); break;
    case WeightKind::given: throw std::invalid_argument("a bank designed from given taps has no spec form");
  }
  if (d.samples != DesignParams{}.samples) args += ",samples=" + std::to_string(d.samples);
  args += ",l=" + std::to_string(d.extension);
  if (boundary == BoundaryRule::line_wss) args += ",boundary=wss";
  return to_string(d.weight) + "(" + args + ")";
}

}  // namespace pupwave::pups
