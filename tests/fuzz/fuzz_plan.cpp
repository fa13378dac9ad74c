// Fuzz target of the JSON-to-plan path (libFuzzer, or replayed by
// replay_main.cpp in the normal test run). Bad input must end in a
// plunge::Error; anything else is a bug: a crash, a sanitizer report, another
// exception, a run past libFuzzer's -timeout or -rss_limit_mb, or a plan with a
// plunge that gouges a wall, an island or a flat floor, as judged by oracle.hpp
// from the input text alone (none of the planner's code).
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "plunge/error.hpp"
#include "plunge/json.hpp"
#include "plunge/plan.hpp"
#include "oracle.hpp"

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
  const plunge_oracle::Pocket pocket(text);
  for (const plunge::Plunge& p : plan.plunges) {
    const std::string why = pocket.gouge({p.x, p.y}, p.diameter, p.z);
    if (!why.empty()) {
      std::fprintf(stderr, "gouge: %s\n", why.c_str());
      std::abort();
    }
  }
  return 0;
}
