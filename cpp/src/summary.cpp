#include "plunge/summary.hpp"

#include <algorithm>
#include <iomanip>
#include <sstream>

namespace plunge {

// What the plan's depths were found on: the bundles' program reads a floor of
// faces as the addon's mesh, the README's install as the faces themselves.
std::string floorKindSaid(const std::string& kind) {
  if (kind == "brep") return "depths on the floor's faces";
  if (kind == "mesh") return "depths on the floor's faces as a mesh";
  if (kind == "expression") return "depths on the floor's expression";
  return "a flat floor";
}

std::string planSummary(const Plan& plan) {
  const PlanStats& st = plan.stats;
  std::ostringstream s;
  s << std::fixed << std::setprecision(2) << st.plungeCount << " plunges (";
  for (size_t i = 0; i < st.perTool.size(); ++i)
    s << (i ? ", " : "") << "T" << st.perTool[i].toolId << " " << std::defaultfloat << std::setprecision(6)
      << st.perTool[i].diameter << std::fixed << std::setprecision(2) << " mm: " << st.perTool[i].count;
  s << "), coverage " << 100 * st.coverage << " %, travel " << std::setprecision(0) << st.travelLength << " mm"
    << std::setprecision(2) << "; stock left: walls up to " << st.maxWallStockLeft << " mm (" << 100 * st.coreCoverage
    << " % of the core cut), floor up to " << st.maxFloorStockLeft << " mm (mean " << st.meanFloorStock << " mm); "
    << std::setprecision(1) << st.volumeRemoved / 1000 << " cm3 removed, " << st.volumeLeft / 1000 << " cm3 left";
  if (st.restMaterial)
    s << "; rest plunging: " << st.volumeBefore / 1000 << " cm3 in the pocket before this operation, "
      << 100 * st.volumeRemoved / std::max(st.volumeBefore, 1e-9) << " % of it removed here"
      << (st.airPlunges ? ", " + std::to_string(st.airPlunges) + " plunges in cleared space left out" : std::string());
  if (st.floorStockPlunges) s << "; " << st.floorStockPlunges << " plunges added for the floor stock";
  if (st.startHoles) s << "; " << st.startHoles << " start holes";
  if (st.peckedPlunges) s << "; " << st.peckedPlunges << " deep holes into solid pecked";
  if (st.levels > 1) s << "; " << st.levels << " levels (flute length)";
  // The tools as mounted, where given: what the holders were kept clear with.
  for (const ToolCount& t : st.perTool) {
    if (!t.stickOut) continue;
    s << std::setprecision(1) << "; T" << t.toolId << " held " << *t.stickOut << " mm from its tip in ";
    if (t.holderDiameter) s << "a " << *t.holderDiameter << " mm holder";
    else s << "a holder of unknown diameter";
    if (t.shankDiameter) s << ", shank " << *t.shankDiameter << " mm";
    if (t.holderLimited) s << " (" << t.holderLimited << " plunges stopped above their depth by it)";
    s << std::setprecision(2);
  }
  if (const int without = st.noLeadOutMaterial + st.noLeadOutWalls; st.leadOuts + without > 0) {
    s << "; lead-outs on " << st.leadOuts << " plunges";
    if (st.raisedLeadOuts) s << ", " << st.raisedLeadOuts << " of them raised out of their neighbours' steps";
    if (without)
      s << " (none on " << st.noLeadOutMaterial << " with material all round, " << st.noLeadOutWalls
        << " with no room at the walls)";
  }
  s << "; about " << st.estimatedMinutes << " min";
  if (st.minutesAtSafeHeight > st.estimatedMinutes + 0.05)
    s << " (" << st.minutesAtSafeHeight - st.estimatedMinutes << " min saved by stock-aware heights)";
  if (plan.selection) s << "; " << choiceSummary(*plan.selection);
  s << "; " << floorKindSaid(st.floorKind);
  return s.str();
}

std::string choiceSummary(const ToolSelection& sel) {
  auto names = [](const std::vector<double>& ds) {
    std::ostringstream n;
    for (size_t i = 0; i < ds.size(); ++i) n << (i ? "/" : "") << ds[i];
    return n.str();
  };
  // The largest set considered is the library as given.
  const ToolSetResult* library = nullptr;
  const ToolSetResult* chosen = nullptr;
  for (const ToolSetResult& r : sel.sets) {
    if (!library || r.diameters.size() > library->diameters.size()) library = &r;
    if (r.diameters == sel.chosen) chosen = &r;
  }
  std::ostringstream s;
  s << "plungers chosen: " << names(sel.chosen);
  if (!library || !chosen || library == chosen) return s.str() + " (every plunger of the library)";
  std::vector<double> left;
  for (double d : library->diameters)
    if (std::find(sel.chosen.begin(), sel.chosen.end(), d) == sel.chosen.end()) left.push_back(d);
  s << " of " << names(library->diameters) << "; left out " << names(left);
  if (!library->refused.empty()) return s.str() + " (the whole library cannot be planned)";
  const double chosenEstimate = chosen->evaluated ? chosen->estimate : chosen->minutes;
  s.str("");
  s << "plungers chosen: " << names(sel.chosen) << " of " << names(library->diameters) << "; left out " << names(left)
    << std::fixed << std::setprecision(1);
  // Said as it is: a saving, no difference (rounded to 0.1 min: never "-0.0"),
  // or an estimate above the whole library's plan (the choice ranks estimates).
  const double saves = library->minutes - chosenEstimate;
  if (saves >= 0.05)
    s << ", which saves about " << saves << " min by the estimate"
      << (library->plunges > 0 ? "" : " (at least: its lower bound)");
  else if (saves > -0.05)
    s << ", which takes as long by the estimate, with fewer tools";
  else
    s << ", whose estimate is about " << -saves << " min above the whole library's plan (the choice ranks the"
      << " estimates)";
  return s.str();
}


}  // namespace plunge
