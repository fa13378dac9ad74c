#include "floor.hpp"

#include <algorithm>
#include <cmath>
#include <muParser.h>

#include "detail.hpp"
#include "plunge/error.hpp"
#include "plunge/optimizer.hpp"

namespace plunge {

namespace {

using detail::kFallbackSamples;
using detail::kNaN;
using detail::peakOptions;
using detail::sampledPeaks;
using detail::samplesFor;

// --- flat --------------------------------------------------------------------

class FlatFloor : public FloorSurface {
 public:
  explicit FlatFloor(double z) : z_(z) {}
  double height(Vec2) const override { return z_; }
  PeakSearch peaks(Vec2 lo, Vec2, double, const Progress&) const override { return {{{lo.x, lo.y, z_}}, 0}; }
  bool isFlat() const override { return true; }
  std::unique_ptr<FloorSurface> clone() const override { return std::make_unique<FlatFloor>(z_); }

 private:
  double z_;
};

// --- expression (muParser) ----------------------------------------------------

double naturalLog(double v) { return std::log(v); }

class ExpressionFloor : public FloorSurface {
 public:
  explicit ExpressionFloor(const std::string& expr) : expr_(expr) {
    try {
      parser_.DefineVar("x", &x_);
      parser_.DefineVar("y", &y_);
      parser_.DefineFun("log", naturalLog);  // the contract's log is the natural one
      parser_.SetExpr(expr);
      parser_.Eval();  // parses now: syntax errors and unknown variables surface here
    } catch (const mu::Parser::exception_type& e) {
      throw Error("floor.expression: " + e.GetMsg() + " in \"" + expr + "\"");
    }
  }
  std::unique_ptr<FloorSurface> clone() const override { return std::make_unique<ExpressionFloor>(expr_); }
  double height(Vec2 p) const override {
    x_ = p.x;
    y_ = p.y;
    const double v = parser_.Eval();
    return std::isfinite(v) ? v : kNaN;
  }
  PeakSearch peaks(Vec2 lo, Vec2 hi, double spacing, const Progress& progress) const override {
    const int n = samplesFor(std::max(hi.x - lo.x, hi.y - lo.y), spacing, 41, 301);
    const OptimizeResult r = optimize([&](const double* q) { return height({q[0], q[1]}); },
                                      {{lo.x, hi.x}, {lo.y, hi.y}}, Goal::Maximize, peakOptions(n, progress));
    PeakSearch out;
    for (const LocalOptimum& o : r.locals) out.points.push_back({o.x[0], o.x[1], o.value});
    if (r.converged) return out;
    ++out.fallbacks;
    const int k = kFallbackSamples;
    for (const Vec3& p : sampledPeaks(k, k, [&](int i, int j) {
           const Vec2 q{lo.x + (hi.x - lo.x) * i / (k - 1), lo.y + (hi.y - lo.y) * j / (k - 1)};
           return Vec3{q.x, q.y, height(q)};
         }, progress))
      out.points.push_back(p);
    return out;
  }

 private:
  std::string expr_;
  mutable double x_ = 0, y_ = 0;
  mu::Parser parser_;
};

}  // namespace

std::unique_ptr<FloorSurface> makeFlatFloor(double z) { return std::make_unique<FlatFloor>(z); }

std::unique_ptr<FloorSurface> makeExpressionFloor(const std::string& expression) {
  return std::make_unique<ExpressionFloor>(expression);
}

#ifndef PLUNGE_WITH_OCCT
// Built without OpenCASCADE (the portable planner, PLUNGE_WITH_OCCT=OFF):
// floors of faces come as a mesh instead.
std::unique_ptr<FloorSurface> makeBrepFloor(const std::string&) {
  throw Error("floor.brep: this planner is built without OpenCASCADE: give the floor as a \"mesh\" "
              "(docs/plan-format.md)");
}

std::unique_ptr<FloorSurface> makeBrepFloorFromText(const std::string& text) { return makeBrepFloor(text); }
#endif

}  // namespace plunge
