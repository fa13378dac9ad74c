#include "broken.hpp"

#include <iomanip>
#include <sstream>

namespace plunge {

void sayBroken(Plan& plan, const std::string& what, BrokenLimit broken) {
  std::ostringstream w;
  w << std::fixed << std::setprecision(2) << what << ", the worst at (" << broken.at.x << ", " << broken.at.y
    << "): " << broken.why;
  plan.warnings.push_back(w.str());
  plan.broken.push_back(std::move(broken));
}

}  // namespace plunge
