// Holders and shanks: how deep a tool can plunge before what holds it meets
// the part or the material still standing.
//
// A tool as mounted is a stack of cylinders on its axis: the flutes (the
// cutting diameter, up to the flute length), the shank (shank_diameter, from
// the flutes' top to the holder's face) and the holder (holder_diameter, from
// the face at the tip + stick_out upward). Only a cylinder wider than the
// cutter can meet material at a plunge: under a narrower one the flutes have
// just cut the hole. Each wider one keeps the clearance (holder_clearance)
// from the stock, sideways and below: the stock is the part around the pocket
// and, in the posted order, the material the earlier plunges left (Touched, an
// upper bound). A holder whose diameter is not given is taken as wide as the
// pocket: its face never goes below the highest material, top_z.
#pragma once
#include <string>
#include <vector>

#include "broken.hpp"
#include "material.hpp"
#include "plunge/tools.hpp"
#include "plunge/types.hpp"
#include "touched.hpp"

namespace plunge {

// Whether anything of the tool above its flutes is known (stick_out given).
bool holderKnown(const Tool& t);

// What the tools' holders keep clear: the clearance ("holder_clearance") and
// the pocket's diagonal (a holder as wide meets the walls wherever it is).
struct HolderSettings {
  double clearance = 1.0;
  double pocketDiagonal = 0.0;
};

// The lowest tip height at which tool t, moved from a to b (a plunge: a == b),
// keeps its shank and holder `clearance` from the stock; -infinity where
// nothing of it is known.
double holderFloor(const Tool& t, const Touched& stock, Vec2 a, Vec2 b, const HolderSettings& settings);

// Which part of a tool stopped a plunge.
enum class HolderPart { Shank, Holder };

// A place where a tool's plunges (its levels there) stop above the depth they
// were to reach.
struct HolderStop {
  int toolId = 0;
  Vec2 at;
  double target = 0.0;  // the depth it was to reach
  double cut = 0.0;     // the deepest it reaches
  HolderPart by = HolderPart::Holder;
};

// What clearHolders changed: the plunges in the same order, each raised to its
// holder floor where needed (Plunge::holderLimited) and left out where a
// raised level cuts nothing a level before did not; and the places stopped.
struct HolderClearance {
  std::vector<Plunge> plunges;
  std::vector<HolderStop> stops;
};


// Tools whose plunges go deeper than their flutes with nothing known above
// them (no stick_out): what holds them is not checked, said once per tool.
std::vector<std::string> uncheckedHolders(const std::vector<Plunge>& plunges, const ToolTable& tools, double topZ);

// The stops no other tool made up for, said per tool: its worst as the
// stick-out that would reach (BrokenLimit "stick_out").
Said holderLimits(const std::vector<HolderStop>& stops, const ToolTable& tools, double clearance);

// The posted plunges (levels split) replayed in order on the stock before
// this operation (material) with the part around the pocket.
HolderClearance clearHolders(const std::vector<Plunge>& ordered, const ToolTable& tools, const Material& material,
                             const HolderSettings& settings);

}  // namespace plunge
