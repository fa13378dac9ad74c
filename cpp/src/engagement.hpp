// Real plunge mills, part 1: the radial engagement limit and non-centre-cutting
// plungers (Tool::maxEngagement, minEngagement, centerCutting, coreDiameter).
//
// A packing of full disks makes every plunge cut its whole diameter. A tool
// limited to a radial band e instead grows its cut from a start, as plunge-mill
// makers prescribe: rows, a step of at most e along each. A plunge a step on
// from the one before it cuts a crescent no thicker than the step (every point
// of its disk lies within the step of the other disk). The planner lays the
// rows over the tool's centre region (growthPaths: its contour first, then
// rows along its long axis or offsets of the contour, whichever cost fewer
// plunges; row positions the contours cut anyway, between a wall and an
// island, come last) and enters each path next to material already
// cut, so positions and order come together; the plunges that clear the tool's
// own targets (its share of the packing/covering plan) are kept. What the
// paths miss is grown ring by ring: a plunge centred in the region cut so far
// shrunk by r - e meets no material farther than e from it. A non-centre-
// cutting tool's core of radius rc lies over cut material when its step keeps
// within r - rc, so it grows the same way with e <= r - rc, from start holes
// drilled by a centre-cutting tool of the job.
#pragma once
#include <optional>
#include <vector>

#include "depth.hpp"
#include "growth_paths.hpp"
#include "heightfield.hpp"
#include "options.hpp"
#include "plunge/progress.hpp"
#include "region.hpp"
#include "plunge/tools.hpp"
#include "plunge/types.hpp"

namespace plunge {

// The plan's plunges (tools largest first, each tool's in tour order) rebuilt so
// that every tool keeps its engagement limit and core over removed material.
// Tools without limits keep their plunges and order. Start holes come first.
// `stock` starts uncut and is left cut by every returned plunge.
std::vector<Plunge> growWithinLimits(const Region& region, const DepthSolver& depths,
                                     const std::vector<Plunge>& ordered, HeightField& stock,
                                     const EngagementOptions& options);

}  // namespace plunge
