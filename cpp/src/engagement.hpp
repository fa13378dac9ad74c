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
#include "heightfield.hpp"
#include "plunge/progress.hpp"
#include "region.hpp"
#include "plunge/tools.hpp"
#include "plunge/types.hpp"

namespace plunge {

// Positions a limited tool grows its cut along (thesis: none; what plunge-mill
// makers prescribe): the contour of its centre region (every loop, walls and
// islands) at most `wallStep` apart, and rows along the region's long axis (or
// offsets of the contour), at most `spacing` apart, their positions at most
// `step` apart. A plunge next
// to the last one on its path cuts a crescent no thicker than the step, so a
// limit e costs about area / (rowSpacing x e) plunges, however wide the rows.
struct GrowthPath {
  std::vector<Vec2> at;
  bool closed = false;   // a loop: its last position is next to its first
  bool contour = false;  // a loop of the contour (entered first; keeps the wall band)
  size_t piece = 0;      // the connected piece of the region it lies in
};
// Inside the contour, `pattern`: rows `spacing` apart, or offsets of the
// contour `spacing` apart (loops, each with a bridge from the loop outside it
// as a row meets the contour). Auto is taken as rows here; the growth tries
// both.
std::vector<GrowthPath> growthPaths(const Polygons& centres, double step, double wallStep, double spacing,
                                    GrowthPattern pattern = GrowthPattern::Rows);
// How far apart rows of plunges of radius r, `step` apart along each row and
// staggered by half a step, may run and still cut everything between them.
double rowSpacing(double r, double step);
// The same for loops side by side (offsets: not staggered).
double loopSpacing(double r, double step);

// What the growth needs of the job (PlanInput's fields of the same names).
struct EngagementOptions {
  ToolTable tools;
  double radialAllowance = 0.0;
  double floorAllowance = 0.0;
  double topZ = 0.0;
  double maxWallStock = 0.0;   // the wall band the contour keeps (stock.hpp)
  double maxFloorStock = 0.0;  // over sculptured floors, what the growth leaves to the finisher
  std::optional<Vec2> start;   // where the machine starts
  GrowthPattern pattern = GrowthPattern::Auto;
  Progress progress;
};

// The plan's plunges (tools largest first, each tool's in tour order) rebuilt so
// that every tool keeps its engagement limit and core over removed material.
// Tools without limits keep their plunges and order. Start holes come first.
// `stock` starts uncut and is left cut by every returned plunge.
std::vector<Plunge> growWithinLimits(const Region& region, const DepthSolver& depths,
                                     const std::vector<Plunge>& ordered, HeightField& stock,
                                     const EngagementOptions& options);

}  // namespace plunge
