#include "floor.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <sstream>
#include <iomanip>
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
  // On a 32 x 32 grid over the pocket, along x and along y, 21 samples over
  // 0.01 mm and over 0.1 mm: a floor that turns up and down four times or
  // more there, by 0.01 mm or more, is texture, not a shape a plunger follows
  // (a ridge or a step turns at most twice). Deterministic, a few milliseconds.
  std::string unfollowable(Vec2 lo, Vec2 hi) const override {
    constexpr int kGrid = 32, kSamples = 21;
    for (double length : {0.01, 0.1})
      for (int j = 0; j < kGrid; ++j)
        for (int i = 0; i < kGrid; ++i) {
          const Vec2 p{lo.x + (hi.x - lo.x) * (i + 0.5) / kGrid, lo.y + (hi.y - lo.y) * (j + 0.5) / kGrid};
          for (const Vec2 along : {Vec2{1, 0}, Vec2{0, 1}}) {
            double z[kSamples];
            bool finite = true;
            for (int k = 0; k < kSamples && finite; ++k) {
              z[k] = height(p + along * (length * k / (kSamples - 1)));
              finite = !std::isnan(z[k]);
            }
            if (!finite) continue;
            int turns = 0, sign = 0;
            double low = z[0], high = z[0];
            for (int k = 1; k < kSamples; ++k) {
              low = std::min(low, z[k]);
              high = std::max(high, z[k]);
              const double d = z[k] - z[k - 1];
              if (std::fabs(d) <= 1e-9 * (1.0 + std::fabs(z[k]))) continue;
              const int s = d > 0 ? 1 : -1;
              if (sign != 0 && s != sign) ++turns;
              sign = s;
            }
            if (turns >= 4 && high - low >= 0.01) {
              std::ostringstream m;
              m << std::fixed << std::setprecision(3) << "floor.expression: it rises and falls by " << high - low
                << " mm " << turns << " times within " << length << " mm at (" << p.x << ", " << p.y
                << "), finer than any plunger or depth search can follow: describe the floor's shape without"
                   " that texture";
              return m.str();
            }
          }
        }
    return {};
  }
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
