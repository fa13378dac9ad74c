#include "engagement.hpp"

#include <cmath>

#include "grower.hpp"

namespace plunge {

std::vector<Plunge> Grower::run(const std::vector<Plunge>& ordered) {
  size_t i = 0;
  while (i < ordered.size()) {
    size_t j = i;
    while (j < ordered.size() && ordered[j].toolId == ordered[i].toolId) ++j;
    const std::vector<Plunge> group(ordered.begin() + i, ordered.begin() + j);
    const Tool& tool = toolOf(ordered[i].toolId);
    if (std::isinf(engagementLimit(tool))) {
      for (const Plunge& p : group) add(p);
    } else {
      grow(tool, group);
    }
    i = j;
  }
  std::vector<Plunge> out = holes_;
  out.insert(out.end(), order_.begin(), order_.end());
  return out;
}

std::vector<Plunge> growWithinLimits(const Region& region, const DepthSolver& depths,
                                     const std::vector<Plunge>& ordered, HeightField& stock,
                                     const EngagementOptions& options) {
  return Grower(options, region, depths, stock).run(ordered);
}

}  // namespace plunge
