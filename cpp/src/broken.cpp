#include "broken.hpp"

#include <iomanip>
#include <sstream>

namespace plunge {

void Said::limit(const std::string& what, BrokenLimit b) {
  std::ostringstream w;
  w << std::fixed << std::setprecision(2) << what << ", the worst at (" << b.at.x << ", " << b.at.y << "): " << b.why;
  warnings.push_back(w.str());
  broken.push_back(std::move(b));
}

Said& Said::operator+=(const Said& more) {
  warnings.insert(warnings.end(), more.warnings.begin(), more.warnings.end());
  broken.insert(broken.end(), more.broken.begin(), more.broken.end());
  return *this;
}

}  // namespace plunge
