#include "codec/image/budget_trim.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace pupwave {
namespace {

// The bound is raised each time the blocks held grow by this share of the budget past it:
// the held bytes stay within about 1 + 1/kCheckShare budgets (and the hull points a cut
// keeps past the bound), at a few bound searches per image.
constexpr double kCheckShare = 16.0;
// ... and by at least this many bytes (small images would search at nearly every block).
constexpr std::size_t kMinCheckBytes = std::size_t(64) << 10;

std::size_t budget_bytes(double budget) {
  return budget < 1e18 ? std::size_t(std::max(budget, 0.0)) : SIZE_MAX;
}

}  // namespace

BudgetTrim::BudgetTrim(std::vector<KeptBlock>& blocks, std::vector<std::vector<HullPoint>>& hulls,
                       double budget)
    : blocks_(blocks), hulls_(hulls), budget_(budget), next_check_(budget_bytes(budget)) {}

void BudgetTrim::add(std::size_t i, EncodedBlock&& coded, std::vector<HullPoint>&& hull) {
  const std::lock_guard<std::mutex> hold(lock_);
  hull.resize(points_to_keep(hull, bound_));
  hull.shrink_to_fit();
  blocks_[i] = KeptBlock(std::move(coded), hull.empty() ? 0 : hull.back().passes, false);
  hulls_[i] = std::move(hull);
  held_ += blocks_[i].size(blocks_[i].pass_count());
  if (held_ > next_check_) tighten();
}

std::size_t BudgetTrim::cut(std::size_t i) {
  std::vector<HullPoint>& hull = hulls_[i];
  const std::size_t keep = points_to_keep(hull, bound_);
  if (keep < hull.size()) {
    hull.resize(keep);
    hull.shrink_to_fit();
    blocks_[i].truncate(hull.empty() ? 0 : hull.back().passes);
  }
  return blocks_[i].size(blocks_[i].pass_count());
}

void BudgetTrim::tighten() {
  bound_ = overflow_slope(hulls_, budget_, bound_);
  held_ = 0;
  for (std::size_t i = 0; i < blocks_.size(); ++i) held_ += cut(i);
  const double step = std::max(budget_ / kCheckShare, double(kMinCheckBytes));
  next_check_ = std::max(held_, budget_bytes(budget_)) + budget_bytes(step);
}

}  // namespace pupwave
