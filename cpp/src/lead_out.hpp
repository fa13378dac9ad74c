// Lead-outs (motion.hpp): after reaching depth the tool feeds `lead_out`
// sideways into space already cleared before it retracts.
#pragma once
#include <optional>

#include "depth.hpp"
#include "heightfield.hpp"
#include "options.hpp"
#include "region.hpp"
#include "touched.hpp"

namespace plunge {

// Why a plunge has no lead-out.
enum class NoLeadOut { None, Material, Walls };

// A plunge's lead-out: where it ends and, raised out of the steps around it,
// the height it feeds up to first; or none and why.
struct LeadOut {
  std::optional<Vec2> to;
  std::optional<double> z;
  NoLeadOut why = NoLeadOut::None;
};

// What lead-outs are measured against: the job, the pocket, the floor, the
// stock cut so far and the disks of the plunges made.
struct LeadOutContext {
  const MotionOptions& in;
  const Region& region;
  const DepthSolver& depths;
  const HeightField& stock;
  const Touched& touched;
};

// The lead-out of plunge p just made (stock already cut by it); `back`: the
// plunge before, when the same tool made it.
LeadOut leadOutOf(const LeadOutContext& context, const Plunge& p, const Cutter& cutter,
                  const std::optional<Plunge>& back);

}  // namespace plunge
