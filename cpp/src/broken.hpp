// A limit the user set that a plan cannot keep is said: which, by how much,
// where and why (docs/plan-format.md, "Limits that cannot be kept").
#pragma once
#include <string>
#include <vector>

#include "plunge/types.hpp"

namespace plunge {

// What a stage of the plan has to say: its warnings, in order, and the limits
// it could not keep (each also a warning). Stages return one; the plan joins
// them in the order of its stages.
struct Said {
  std::vector<std::string> warnings;
  std::vector<BrokenLimit> broken;

  void warn(std::string warning) { warnings.push_back(std::move(warning)); }
  // A broken limit, and its warning: `what` (a sentence for people, no JSON
  // keys), where the worst is and why.
  void limit(const std::string& what, BrokenLimit broken);
  Said& operator+=(const Said& more);
};

}  // namespace plunge
