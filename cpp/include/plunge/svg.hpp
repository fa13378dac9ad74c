// The plan's pictures (SVG), one per question.
#pragma once
#include <string>
#include <vector>

#include "plunge/types.hpp"

namespace plunge {

// Plan: each plunge disk coloured by tool, each tool's path in order, starts
// and lead-outs. Stock: what the plan leaves (the wall band in red, the floor
// stock map on sculptured floors) and every broken limit, numbered where its
// worst is. Heights: each plunge's stop height (sculptured floors, and plans a holder stopped).
enum class SvgView { Plan, Stock, Heights };

// The views a plan of this input has: Heights only over a sculptured floor,
// or where a holder stopped plunges above their depth.
std::vector<SvgView> svgViews(const PlanInput& input, const Plan& plan);
// "plan", "stock", "heights": the file suffix and the Python key.
const char* svgViewName(SvgView view);

std::string planToSvg(const PlanInput& input, const Plan& plan, SvgView view = SvgView::Plan);

}  // namespace plunge
