// A limit the user set that a plan cannot keep is said: which, by how much,
// where and why (docs/plan-format.md, "Limits that cannot be kept").
#pragma once
#include <string>

#include "plunge/types.hpp"

namespace plunge {

// Records a broken limit in the plan and warns with `what` (a sentence for
// people, no JSON keys), where the worst is and why.
void sayBroken(Plan& plan, const std::string& what, BrokenLimit broken);

}  // namespace plunge
