#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepBuilderAPI_MakePolygon.hxx>
#include <BRepBuilderAPI_Sewing.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <GeomAPI_PointsToBSplineSurface.hxx>
#include <Geom_BSplineSurface.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <gp_Circ.hxx>
#include <gp_Pln.hxx>
#include <cmath>
#include <random>
#include <sstream>

#include "depth.hpp"
#include "plunge/error.hpp"

using namespace plunge;
using ::testing::HasSubstr;

namespace {

double bumps(double x, double y) {
  return -20 + 3 * std::exp(-((x - 30) * (x - 30) + (y - 40) * (y - 40)) / 60.0) +
         2 * std::exp(-((x - 70) * (x - 70) + (y - 55) * (y - 55)) / 40.0) + 0.02 * x - 0.01 * y +
         0.5 * std::sin(0.15 * x) * std::cos(0.1 * y);
}

const char* kBumps =
    "-20 + 3*exp(-((x-30)^2+(y-40)^2)/60) + 2*exp(-((x-70)^2+(y-55)^2)/40) + 0.02*x - 0.01*y"
    " + 0.5*sin(0.15*x)*cos(0.1*y)";

// Gouge-free and tight: never below the true maximum (1e-6 mm), at most 0.01 mm above.
void expectTight(const FloorSurface& floor, const DepthSolver& solver, Vec2 c, const Cutter& cutter,
                 double spacing = 0.25, double loose = 0.01) {
  const double ours = solver.stopHeight(c, cutter);
  const double brute = stopHeightBruteForce(floor, c, cutter, spacing);
  EXPECT_GE(ours, brute - 1e-6) << "gouge at " << c.x << "," << c.y << " r " << cutter.radius;
  EXPECT_LE(ours, brute + loose) << "loose at " << c.x << "," << c.y;
}

std::string bsplineFaceBrep() {
  // A B-spline surface through a grid of the bump function, as CAD would hand it over.
  TColgp_Array2OfPnt pts(1, 41, 1, 31);
  for (int i = 1; i <= 41; ++i)
    for (int j = 1; j <= 31; ++j) {
      const double x = 2.5 * (i - 1), y = 2.5 * (j - 1);
      pts.SetValue(i, j, gp_Pnt(x, y, bumps(x, y)));
    }
  GeomAPI_PointsToBSplineSurface fit(pts, 3, 3, GeomAbs_C2, 1e-4);
  const TopoDS_Face face = BRepBuilderAPI_MakeFace(fit.Surface(), 1e-7);
  std::ostringstream s;
  BRepTools::Write(face, s);
  return s.str();
}

}  // namespace

TEST(Depth, CutterProfiles) {
  const Cutter flat{CutterShape::Flat, 5, 0}, ball{CutterShape::Ball, 5, 5}, bull{CutterShape::Bull, 5, 2};
  EXPECT_DOUBLE_EQ(cutterProfile(flat, 4.9), 0);
  EXPECT_DOUBLE_EQ(cutterProfile(ball, 0), 0);
  EXPECT_NEAR(cutterProfile(ball, 3), 5 - 4, 1e-12);
  EXPECT_DOUBLE_EQ(cutterProfile(bull, 3), 0);
  EXPECT_NEAR(cutterProfile(bull, 5), 2, 1e-12);
  EXPECT_NEAR(cutterProfile(bull, 4), 2 - std::sqrt(3.0), 1e-12);
}

TEST(Depth, ExpressionFloorAgainstBruteForce) {
  const auto floor = makeExpressionFloor(kBumps);
  EXPECT_NEAR(floor->height({12, 34}), bumps(12, 34), 1e-12);
  const DepthSolver solver(*floor, {0, 0}, {100, 75}, 2.0);
  ASSERT_GE(solver.peaks().size(), 2u);
  const Cutter flat{CutterShape::Flat, 6, 0};
  expectTight(*floor, solver, {30, 40}, flat);   // holds a peak (interior maximum)
  EXPECT_NEAR(solver.stopHeight({30, 40}, flat), solver.stopHeight({30.5, 40.5}, flat), 0.2);
  expectTight(*floor, solver, {50, 20}, flat);   // no peak inside: the rim
  expectTight(*floor, solver, {70, 55}, {CutterShape::Flat, 3, 0});
  expectTight(*floor, solver, {6, 6}, flat);     // at the floor's edge
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> ux(8, 92), uy(8, 67);
  for (int i = 0; i < 40; ++i) expectTight(*floor, solver, {ux(rng), uy(rng)}, {CutterShape::Flat, 2.0 + i % 7, 0});
}

TEST(Depth, BallAndBullAgainstAnalyticPlane) {
  const double m = 0.3;  // z = m x
  const auto floor = makeExpressionFloor("0.3*x");
  const DepthSolver solver(*floor, {-50, -50}, {50, 50}, 2.0);
  const double k = std::sqrt(1 + m * m);
  EXPECT_NEAR(solver.stopHeight({4, 1}, {CutterShape::Flat, 5, 0}), m * 9, 1e-7);
  EXPECT_NEAR(solver.stopHeight({4, 1}, {CutterShape::Ball, 5, 5}), m * 4 + 5 * (k - 1), 1e-7);
  EXPECT_NEAR(solver.stopHeight({4, 1}, {CutterShape::Bull, 5, 2}), m * (4 + 3) + 2 * (k - 1), 1e-7);
  // A ball in a bowl touches at its lowest point.
  const auto bowl = makeExpressionFloor("(x^2 + y^2) / 200");
  const DepthSolver bs(*bowl, {-50, -50}, {50, 50}, 2.0);
  EXPECT_NEAR(bs.stopHeight({0, 0}, {CutterShape::Ball, 5, 5}), 0.0, 1e-9);
}

TEST(Depth, BallAndBullAgainstBruteForce) {
  const auto floor = makeExpressionFloor(kBumps);
  const DepthSolver solver(*floor, {0, 0}, {100, 75}, 2.0);
  for (Vec2 c : {Vec2{30, 40}, Vec2{50, 20}, Vec2{68, 52}})
    for (const Cutter& k : {Cutter{CutterShape::Ball, 6, 6}, Cutter{CutterShape::Bull, 6, 2}})
      expectTight(*floor, solver, c, k);
  // Thin corners (a flat cutter grown by a floor allowance) are searched on rings.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> ux(8, 92), uy(8, 67);
  for (int i = 0; i < 24; ++i)
    expectTight(*floor, solver, {ux(rng), uy(rng)}, grownAround({CutterShape::Flat, 2.0 + i % 6, 0}, 0.1 + 0.1 * (i % 4)),
                0.05);
}

TEST(Depth, ThinCornerOnSteepPlanes) {
  // The grown flat cutter on a plane z = m x touches in its corner: exact.
  for (double m : {0.2, 1.0, 3.0}) {
    const auto floor = makeExpressionFloor(std::to_string(m) + "*x");
    const DepthSolver solver(*floor, {-50, -50}, {50, 50}, 2.0);
    const double rc = 0.3, flat = 5, k = std::sqrt(1 + m * m);
    const Cutter grown = grownAround({CutterShape::Flat, flat, 0}, rc);
    // The corner's centre circle at x = flat, the torus touches the plane rc * k above it less rc.
    EXPECT_NEAR(solver.stopHeight({4, 1}, grown), m * (4 + flat) + rc * (k - 1), 1e-6) << m;
  }
}

TEST(Depth, BsplineFaceFromOcct) {
  const auto floor = makeBrepFloorFromText(bsplineFaceBrep());
  EXPECT_NEAR(floor->height({31.2, 38.7}), bumps(31.2, 38.7), 0.01);  // the fit follows the function
  EXPECT_TRUE(std::isnan(floor->height({150, 10})));                 // no floor there
  const DepthSolver solver(*floor, {0, 0}, {100, 75}, 2.0);
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> ux(8, 92), uy(8, 67);
  for (int i = 0; i < 25; ++i) expectTight(*floor, solver, {ux(rng), uy(rng)}, {CutterShape::Flat, 3.0 + i % 6, 0});
  expectTight(*floor, solver, {30, 40}, {CutterShape::Flat, 5, 0});
  expectTight(*floor, solver, {30, 40}, {CutterShape::Ball, 5, 5});
}

TEST(Depth, TrimmedFaceInsideAndOutside) {
  // A plane face z = -10 bounded by a star (concave corners) with a round hole
  // and a triangular hole: where the floor is (not NaN) against the analytic
  // region, at random points and on a fine row grid, away from the boundary by
  // more than 1e-4 mm (the face's own tolerance is 1e-7).
  std::vector<Vec2> star;
  for (int k = 0; k < 14; ++k) {
    const double a = 2 * kPi * k / 14, r = k % 2 ? 22.0 : 40.0;
    star.push_back({50 + r * std::cos(a), 50 + r * std::sin(a)});
  }
  const std::vector<Vec2> tri{{38, 40}, {44, 40}, {41, 46}};
  auto polygonWire = [](const std::vector<Vec2>& pts) {
    BRepBuilderAPI_MakePolygon p;
    for (Vec2 q : pts) p.Add(gp_Pnt(q.x, q.y, -10));
    p.Close();
    return p.Wire();
  };
  const gp_Circ hole(gp_Ax2(gp_Pnt(58, 55, -10), gp_Dir(0, 0, 1)), 6);
  BRepBuilderAPI_MakeFace mk(gp_Pln(gp_Pnt(0, 0, -10), gp_Dir(0, 0, 1)), polygonWire(star));
  mk.Add(TopoDS::Wire(BRepBuilderAPI_MakeWire(BRepBuilderAPI_MakeEdge(hole)).Wire().Reversed()));
  mk.Add(TopoDS::Wire(polygonWire(tri).Reversed()));
  ASSERT_TRUE(mk.IsDone());
  std::ostringstream s;
  BRepTools::Write(mk.Face(), s);
  const auto floor = makeBrepFloorFromText(s.str());
  auto inPolygon = [](const std::vector<Vec2>& poly, Vec2 p) {
    bool in = false;
    for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++)
      if ((poly[i].y > p.y) != (poly[j].y > p.y) &&
          p.x < poly[j].x + (p.y - poly[j].y) * (poly[i].x - poly[j].x) / (poly[i].y - poly[j].y))
        in = !in;
    return in;
  };
  auto nearEdge = [](const std::vector<Vec2>& poly, Vec2 p) {
    for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++)
      if (distanceToSegment({poly[j], poly[i]}, p) < 1e-4) return true;
    return false;
  };
  int checked = 0;
  auto check = [&](Vec2 p) {
    const double toHole = std::fabs(dist(p, {58, 55}) - 6);
    if (nearEdge(star, p) || nearEdge(tri, p) || toHole < 1e-4) return;
    const bool inside = inPolygon(star, p) && !inPolygon(tri, p) && dist(p, {58, 55}) > 6;
    const double z = floor->height(p);
    EXPECT_EQ(inside, !std::isnan(z)) << p.x << "," << p.y;
    if (inside) {
      EXPECT_NEAR(z, -10, 1e-9);
    }
    ++checked;
  };
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(5, 95);
  for (int i = 0; i < 20000; ++i) check({u(rng), u(rng)});
  for (double y = 8.013; y < 92; y += 0.37)
    for (double x = 8.007; x < 92; x += 0.05) check({x, y});
  EXPECT_GT(checked, 100000);
  // Searches end on the parameter box's sides and on the wires: still classified.
  const DepthSolver solver(*floor, {8, 8}, {92, 92}, 2.0);
  EXPECT_NEAR(solver.stopHeight({50, 50}, {CutterShape::Flat, 3, 0}), -10, 1e-9);
}

TEST(Depth, SeveralFacesMeetingAtARidge) {
  // A roof z = -10 - |x| / 4 of two planar faces: over the ridge the stop is the ridge.
  BRep_Builder b;
  TopoDS_Compound roof;
  b.MakeCompound(roof);
  b.Add(roof, BRepBuilderAPI_MakeFace(BRepBuilderAPI_MakePolygon(gp_Pnt(-40, -30, -20), gp_Pnt(0, -30, -10),
                                                                 gp_Pnt(0, 30, -10), gp_Pnt(-40, 30, -20), true)));
  b.Add(roof, BRepBuilderAPI_MakeFace(BRepBuilderAPI_MakePolygon(gp_Pnt(0, -30, -10), gp_Pnt(40, -30, -20),
                                                                 gp_Pnt(40, 30, -20), gp_Pnt(0, 30, -10), true)));
  std::ostringstream s;
  BRepTools::Write(roof, s);
  const auto floor = makeBrepFloorFromText(s.str());
  EXPECT_NEAR(floor->height({-8, 3}), -12, 1e-9);
  EXPECT_NEAR(floor->height({8, 3}), -12, 1e-9);
  const DepthSolver solver(*floor, {-40, -30}, {40, 30}, 2.0);
  EXPECT_NEAR(solver.stopHeight({2, 0}, {CutterShape::Flat, 5, 0}), -10, 1e-7);   // ridge inside the disk
  EXPECT_NEAR(solver.stopHeight({12, 0}, {CutterShape::Flat, 5, 0}), -11.75, 1e-7);  // rim nearest the ridge
  expectTight(*floor, solver, {1, 5}, {CutterShape::Ball, 4, 4});
}

// Distance from a point at (rho from the axis, height h) to the solid of a
// cutter with its tip at z (its profile, then its side straight up), sampled
// along the profile every 2 um: the 3D distance, the solid being round.
static double distanceToCutter(const Cutter& k, double z, double rho, double h) {
  if (rho <= k.radius && h >= z + cutterProfile(k, rho)) return 0.0;
  double best = rho > k.radius && h >= z + cutterProfile(k, k.radius) ? rho - k.radius : 1e9;
  for (double t = 0; t <= k.radius; t += 0.002)
    best = std::min(best, std::hypot(rho - t, h - z - cutterProfile(k, t)));
  return best;
}

TEST(Depth, PlungeHeightKeepsBothAllowancesIn3D) {
  // A fillet-like rise (a sigmoid, 68 degrees at its steepest) on the bumps:
  // beside the cutter the floor rises by more than the floor allowance within
  // the radial allowance. Sampled densely: no floor point nearer the cutter's
  // solid than the floor allowance (in 3D, normal to the floor: on a slope
  // that is more than the allowance vertically), nothing beside it within
  // the radial allowance, and the height no higher than one of the two
  // requires.
  const std::string expr = std::string(kBumps) + " + 10/(1+exp(-(x-50)))";
  const auto floor = makeExpressionFloor(expr);
  const DepthSolver solver(*floor, {0, 0}, {100, 75}, 2.0);
  const double fa = 0.3, ra = 0.5;
  for (const Cutter& k : {Cutter{CutterShape::Flat, 6, 0}, Cutter{CutterShape::Ball, 5, 5}, Cutter{CutterShape::Bull, 6, 2}})
    for (Vec2 c : {Vec2{40, 30}, Vec2{43.3, 31}, Vec2{44, 50}, Vec2{47, 20}, Vec2{30, 40}}) {
      const double z = solver.plungeHeight(c, k, fa, ra);
      const Cutter g = grownSideways(k, ra), around = grownAround(k, fa);
      double under = -1e9, beside = -1e9, normal = -1e9, nearest = 1e9;
      for (double y = c.y - g.radius - fa; y <= c.y + g.radius + fa; y += 0.05)
        for (double x = c.x - g.radius - fa; x <= c.x + g.radius + fa; x += 0.05) {
          const double rho = dist({x, y}, c);
          const double f = floor->height({x, y});
          if (rho <= k.radius) under = std::max(under, f - cutterProfile(k, rho));
          if (rho <= g.radius) beside = std::max(beside, f - cutterProfile(g, rho));
          if (rho <= around.radius) normal = std::max(normal, f - cutterProfile(around, rho) + fa);
          // Only points that may lie within the allowance (a point more than
          // 2 fa below the cutter's lowest point within fa sideways is farther).
          if (rho <= k.radius + fa && f > z + cutterProfile(k, rho - fa) - 2 * fa)
            nearest = std::min(nearest, distanceToCutter(k, z, rho, f));
          // The grown cutter is the tool plus the radial allowance sideways.
          if (rho <= k.radius) {
            EXPECT_LE(cutterProfile(g, rho + ra), cutterProfile(k, rho) + 1e-12);
          }
        }
      EXPECT_GE(z, under + fa - 1e-6) << c.x << "," << c.y;
      EXPECT_GE(nearest, fa - 0.002) << c.x << "," << c.y;  // the 2 um of the profile's sampling
      EXPECT_GE(z, beside - 1e-6) << c.x << "," << c.y;
      EXPECT_LE(z, std::max(normal, beside) + 0.01) << c.x << "," << c.y;
    }
  // Where the rise is beside the cutter it holds it up; on the plain bumps it does not.
  const Cutter flat{CutterShape::Flat, 6, 0};
  EXPECT_GT(solver.plungeHeight({43.3, 31}, flat, fa, ra), solver.stopHeight({43.3, 31}, flat) + fa + 0.1);
  // There the normal offset alone holds it: on the bumps' slope a little more
  // than the allowance vertically.
  EXPECT_NEAR(solver.plungeHeight({20, 40}, flat, fa, ra), solver.stopHeight({20, 40}, grownAround(flat, fa)) + fa,
              1e-9);
  EXPECT_GT(solver.plungeHeight({20, 40}, flat, fa, ra), solver.stopHeight({20, 40}, flat) + fa + 0.005);
}

TEST(Depth, TheRimBoundIsNeverAboveThePlungeHeight) {
  // plungeHeightAtLeast lets the floor-stock step and the lead-outs skip the exact
  // height: it must never exceed it (or they would skip plunges and moves
  // that fit), for any shape, allowance and place, and on a rise beside the
  // cutter it should come near it (or it skips nothing).
  const std::string expr = std::string(kBumps) + " + 10/(1+exp(-(x-50)))";
  const auto floor = makeExpressionFloor(expr);
  const DepthSolver solver(*floor, {0, 0}, {100, 75}, 2.0);
  int near = 0, n = 0;
  for (const Cutter& k : {Cutter{CutterShape::Flat, 6, 0}, Cutter{CutterShape::Ball, 5, 5}, Cutter{CutterShape::Bull, 6, 2},
                          Cutter{CutterShape::Flat, 2.5, 0}})
    for (double fa : {0.0, 0.3})
      for (double ra : {0.0, 0.5})
        for (double x = 12; x <= 88; x += 15.1)
          for (double y = 12; y <= 63; y += 17) {
            const double exact = solver.plungeHeight({x, y}, k, fa, ra);
            const double bound = solver.plungeHeightAtLeast({x, y}, k, fa, ra);
            EXPECT_LE(bound, exact + 1e-9) << x << "," << y << " r " << k.radius << " fa " << fa << " ra " << ra;
            EXPECT_EQ(solver.plungesTo({x, y}, k, fa, ra, exact + 1e-9), true);
            EXPECT_EQ(solver.plungesTo({x, y}, k, fa, ra, exact - 1e-3), false);
            ++n;
            if (std::fabs(x - 50) < 10 && exact - bound < 0.05) ++near;
          }
  EXPECT_GT(n, 0);
  EXPECT_GT(near, 10);  // on the rise the rim holds the plunger up
}

TEST(Depth, AFloorNoPlungerCanFollowIsSaidSo) {
  // A floor that rises and falls on a scale no cutter or depth search
  // resolves is refused before planning (its depths took hours); shapes a
  // plunger follows, steps and ridges among them, are not.
  const Vec2 lo{0, 0}, hi{600, 400};
  for (const char* texture : {"-25+sin(x*1e6)", "-25+sin(y*1e3)", "-25+0.5*sin(x*100)*cos(y*100)"}) {
    const std::string why = makeExpressionFloor(texture)->unfollowable(lo, hi);
    EXPECT_THAT(why, HasSubstr("floor.expression: it rises and falls by")) << texture << ": " << why;
  }
  for (const char* shape : {kBumps, "-25+sin(x*10)", "-25+0.001*sin(x*1e6)", "x < 300 ? -20 : -10", "-abs(x-300)/10",
                            "sqrt(x-100)", "-25"}) {
    EXPECT_EQ(makeExpressionFloor(shape)->unfollowable(lo, hi), "") << shape;
  }
}

TEST(Depth, BadFloors) {
  EXPECT_THROW(makeExpressionFloor("sin(x"), Error);
  EXPECT_THROW(makeExpressionFloor("z + 1"), Error);
  EXPECT_THROW(makeExpressionFloor(""), Error);
  EXPECT_THROW(makeBrepFloor("/nonexistent/floor.brep"), Error);
  EXPECT_THROW(makeBrepFloorFromText("not a brep"), Error);
  const auto floor = makeExpressionFloor("sqrt(x)");  // undefined for x < 0
  const DepthSolver solver(*floor, {-20, -20}, {20, 20}, 2.0);
  EXPECT_THROW(solver.stopHeight({-10, 0}, {CutterShape::Flat, 3, 0}), Error);  // no floor under it
}

// A public part's R1 spherical corner blend (1.3 mm^2): its peak search once
// ran forever (finite differences at the parameter box's face stepped BFGS to
// NaN, where OpenCASCADE's face classifier never returns). Now it settles
// within the optimizer's budget, and its depths hold against brute force.
TEST(Depth, SmallSphericalCornerBlend) {
  const auto floor = makeBrepFloor(std::string(PLUNGE_TEST_DATA) + "/floors/sphere_blend.brep");
  Progress progress([](double, const std::string&) { return true; }, std::chrono::milliseconds(0));
  const DepthSolver solver(*floor, {21.9, 5.9}, {23.0, 7.0}, 0.25, progress);
  EXPECT_EQ(solver.peakFallbacks(), 0);
  ASSERT_FALSE(solver.peaks().empty());
  for (const Vec3& p : solver.peaks()) EXPECT_LE(p.z, 24.0 + 1e-6);  // the sphere's top
  for (double r : {0.2, 0.4})
    for (Vec2 c : {Vec2{22.5, 6.5}, Vec2{22.2, 6.8}, Vec2{22.8, 6.1}}) {
      const Cutter cutter{CutterShape::Flat, r, 0};
      // The sample misses the face's trimmed edge, where a disk over it may
      // touch first (the solver takes the edge's maximum): 0.02 loose.
      expectTight(*floor, solver, c, cutter, 0.01, 0.02);
    }
  EXPECT_EQ(solver.depthFallbacks(), 0);
}
