// What the stages after the covering read of the job (PlanInput's fields of
// the same names): the growth within engagement limits (engagement.hpp) and
// the machine's moves (motion.hpp) share most of it. Here, below both, so that
// the modules they call (grower.hpp, lead_out.hpp) include neither.
#pragma once
#include <optional>

#include "material.hpp"
#include "plunge/geometry.hpp"
#include "plunge/progress.hpp"
#include "plunge/tools.hpp"
#include "plunge/types.hpp"

namespace plunge {

// The job as both read it.
struct JobOptions {
  ToolTable tools;  // largest first
  Material material{std::nullopt, 0.0};  // what the operations before left, up to top_z
  double radialAllowance = 0.0;
  double floorAllowance = 0.0;
  double maxWallStock = 0.0;  // the wall band the covering may leave (the contour keeps it, rapids go around it)
  Progress progress;          // ticked as they work (it may cancel)
};

// What the growth within engagement limits needs besides.
struct EngagementOptions : JobOptions {
  double maxFloorStock = 0.0;  // over sculptured floors, what the growth leaves to the finisher
  std::optional<Vec2> start;   // where the machine starts
  GrowthPattern pattern = GrowthPattern::Auto;
};

// What the machine's moves need besides.
struct MotionOptions : JobOptions {
  double safeZ = 5.0;
  MotionSettings settings;  // lead-outs, heights, pecks, the time model (PlanInput::motion)
};

}  // namespace plunge
