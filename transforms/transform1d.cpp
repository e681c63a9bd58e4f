#include "transforms/transform1d.h"

#include <stdexcept>

namespace pupwave {

void Transform1D::analyze(std::span<int32_t>) const {
  throw std::logic_error("transform " + spec() + " has no reversible integer form");
}

void Transform1D::synthesize(std::span<int32_t>) const {
  throw std::logic_error("transform " + spec() + " has no reversible integer form");
}

}  // namespace pupwave
