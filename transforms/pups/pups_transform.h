#pragma once
// The PUPs filter bank as a 1-D transform (Transform1D): lifting steps from
// factor_bank(), half-sample symmetric extension of each wire at both ends, perfect
// reconstruction for every line length by construction. Route and measurements:
// docs/pups.md.

#include <string>
#include <string_view>
#include <vector>

#include "transforms/pups/design.h"
#include "transforms/pups/filter_bank.h"
#include "transforms/pups/lifting_factorization.h"
#include "transforms/transform1d.h"

namespace pupwave {

namespace pups {

class PupsTransform final : public Transform1D {
 public:
  // Factors `bank` (throws std::invalid_argument if it is not perfectly reconstructing).
  // spec: the canonical spec string returned by spec(); boundary: how lines are extended.
  PupsTransform(const FilterBank& bank, std::string spec, BoundaryRule boundary = BoundaryRule::wire_hss);

  std::string spec() const override { return spec_; }
  void analyze(std::span<double> line) const override;
  void synthesize(std::span<double> line) const override;
  void analyze(std::span<float> line) const override;
  void synthesize(std::span<float> line) const override;
  // Row-wise lifting of every column (lifting_columns.h), bit-identical to the line form.
  void analyze_columns(std::span<float> block, std::size_t width) const override;
  void synthesize_columns(std::span<float> block, std::size_t width) const override;
  void analyze_columns(std::span<double> block, std::size_t width) const override;
  void synthesize_columns(std::span<double> block, std::size_t width) const override;
  using Transform1D::analyze;
  using Transform1D::analyze_columns;
  using Transform1D::synthesize;
  using Transform1D::synthesize_columns;

  // The design the transform was built from.
  const FilterBank& bank() const { return bank_; }
  // The lifting steps, scales and the banded filters realized away from the ends.
  const LiftingFactorization& factorization() const { return lifting_; }
  BoundaryRule boundary() const { return boundary_; }

 private:
  template <class T>
  void analyze_impl(std::span<T> line) const;
  template <class T>
  void synthesize_impl(std::span<T> line) const;
  template <class T>
  void analyze_columns_impl(std::span<T> block, std::size_t width) const;
  template <class T>
  void synthesize_columns_impl(std::span<T> block, std::size_t width) const;

  struct Step {
    bool predict = true;
    std::vector<double> taps;
    std::ptrdiff_t offset = 0;
  };

  FilterBank bank_;
  LiftingFactorization lifting_;
  std::vector<Step> steps_;
  std::string spec_;
  BoundaryRule boundary_;
};

}  // namespace pups

// Builds the transform of a filter bank (e.g. one read from a file header); spec is what
// spec() returns (the caller's canonical "pups:..." string).
Transform1DPtr make_pups_transform(const pups::FilterBank& bank, std::string spec,
                                   pups::BoundaryRule boundary = pups::BoundaryRule::wire_hss);

// Builds the transform of a spec body (the text after "pups:"): a preset name or
// `<weight>(key=value,...)` (see pups::parse_design_spec). spec() is "pups:" + the
// canonical body, which parses back to the same bank. Throws std::invalid_argument with a
// clear message for a bad body. Results are cached per body (given and canonical), at most
// 256 entries: the cache is emptied when full.
Transform1DPtr make_pups_transform_from_spec(std::string_view body);

// Entries in that cache now (to test its bound).
std::size_t pups_transform_cache_size();

// Condition number of the finite analysis operator of `t` on lines of n samples, from its
// explicit matrix (columns = analyses of unit impulses) and inverse (syntheses): in the
// 1-norm (exact, O(n^2) memory) or, with two_norm, from the singular values (O(n^3)).
double analysis_condition_number(const Transform1D& t, std::size_t n, bool two_norm);

// "pups:<preset>" for every preset.
std::vector<std::string> pups_transform_specs();

}  // namespace pupwave
