// Fuzz target of the JSON-to-plan path (libFuzzer, or replayed by
// replay_main.cpp in the normal test run). Bad input must end in a
// plunge::Error; anything else is a bug: a crash, a sanitizer report, another
// exception, a run past libFuzzer's -timeout or -rss_limit_mb, or a plan with a
// plunge that gouges a wall or island.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "plunge/error.hpp"
#include "plunge/json.hpp"
#include "plunge/plan.hpp"
#include "region.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  plunge::PlanInput in;
  plunge::Plan plan;
  try {
    in = plunge::planInputFromJson(text);
    plan = plunge::plan(in);
  } catch (const plunge::Error&) {
    return 0;  // refused with a message: fine
  }
  const plunge::Region walls(in.boundary, in.islands);
  for (const plunge::Plunge& p : plan.plunges) {
    const plunge::Vec2 c{p.x, p.y};
    if (!walls.contains(c) || walls.wallDistance(c, p.diameter) < 0.5 * p.diameter + in.radialAllowance - 1e-6) {
      std::fprintf(stderr, "gouge: plunge of %g mm at (%.9g, %.9g)\n", p.diameter, p.x, p.y);
      std::abort();
    }
  }
  return 0;
}
