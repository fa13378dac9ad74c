// The mesh floor (mesh_floor.hpp): its exact drop-cutter against brute force on
// each triangle, its stops against the true surface it was made from, and bad
// meshes refused.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "depth.hpp"
#include "mesh_floor.hpp"
#include "plunge/calls.hpp"
#include "plunge/error.hpp"

using namespace plunge;

namespace {

// The highest lift z - profile over a fine barycentric sample of the triangle
// under the cutter: a lower bound of the true drop, as close as the sample is fine.
double bruteTriangle(const Vec3& a, const Vec3& b, const Vec3& c, Vec2 center, const Cutter& cutter, int n) {
  double best = -INFINITY;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; i + j <= n; ++j) {
      const double u = double(i) / n, v = double(j) / n, w = 1 - u - v;
      const Vec2 p{w * a.x + u * b.x + v * c.x, w * a.y + u * b.y + v * c.y};
      const double d = dist(p, center);
      if (d > cutter.radius) continue;
      best = std::max(best, w * a.z + u * b.z + v * c.z - cutterProfile(cutter, d));
    }
  return best;
}

const Cutter kCutters[] = {{CutterShape::Flat, 5, 0}, {CutterShape::Ball, 5, 5}, {CutterShape::Bull, 5, 1.5},
                           {CutterShape::Bull, 3, 0.2}};

double bowl(double x, double y) { return -20 + 4 * std::sin(0.08 * x) * std::cos(0.06 * y) + 0.01 * x * y / 10; }
const char* kBowl = "-20 + 4*sin(0.08*x)*cos(0.06*y) + 0.01*x*y/10";

// The bowl on a grid of `h` mm over [0, w] x [0, d], two triangles a cell.
TriangleMesh gridMesh(double w, double d, double h, double deviation) {
  TriangleMesh m;
  const int nx = static_cast<int>(std::round(w / h)), ny = static_cast<int>(std::round(d / h));
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) m.vertices.push_back({i * h, j * h, bowl(i * h, j * h)});
  auto at = [&](int i, int j) { return static_cast<std::uint32_t>(j * (nx + 1) + i); };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  m.deviation = {deviation};
  return m;
}

}  // namespace

TEST(MeshFloor, DropOnATriangleIsItsHighestContact) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> pos(-6, 6), height(-3, 3);
  int touching = 0;
  for (int k = 0; k < 300; ++k) {
    const Vec3 a{pos(rng), pos(rng), height(rng)}, b{pos(rng), pos(rng), height(rng)}, c{pos(rng), pos(rng), height(rng)};
    const Vec2 center{0.5 * pos(rng), 0.5 * pos(rng)};
    for (const Cutter& cutter : kCutters) {
      const double exact = dropOnTriangle(a, b, c, center, cutter);
      const double brute = bruteTriangle(a, b, c, center, cutter, 700);
      if (!std::isfinite(brute)) continue;  // the sample missed a sliver under the rim
      ++touching;
      EXPECT_GE(exact, brute - 1e-9) << "gouge, triangle " << k << " cutter r " << cutter.radius;
      EXPECT_LE(exact, brute + 0.02) << "above every contact, triangle " << k << " cutter r " << cutter.radius;
    }
  }
  EXPECT_GT(touching, 600);
}

TEST(MeshFloor, DropOnAPlaneIsTheClosedForm) {
  // A plane rising at slope m along x: a flat cutter touches at its rim
  // uphill, a ball R/cos - R higher than its tip, a bull between.
  const double m = 0.5, cosA = 1 / std::sqrt(1 + m * m);
  const Vec3 a{-50, -50, -25}, b{50, -50, 25}, c{0, 50, 0};  // z = m x
  const Vec2 o{1, 2};
  EXPECT_NEAR(dropOnTriangle(a, b, c, o, {CutterShape::Flat, 5, 0}), m * (1 + 5), 1e-9);
  EXPECT_NEAR(dropOnTriangle(a, b, c, o, {CutterShape::Ball, 5, 5}), m * 1 + 5 / cosA - 5, 1e-9);
  // Bull: the flat part's rim (radius 3) uphill, then the corner (2) along the normal.
  EXPECT_NEAR(dropOnTriangle(a, b, c, o, {CutterShape::Bull, 5, 2}), m * (1 + 3) + 2 / cosA - 2, 1e-9);
}

TEST(MeshFloor, HeightIsTheTrianglesAndNaNBesideThem) {
  TriangleMesh m;
  m.vertices = {{0, 0, 0}, {10, 0, 10}, {0, 10, 20}};
  m.triangles = {{0, 1, 2}};
  const auto floor = makeMeshFloor(m);
  EXPECT_NEAR(floor->height({2, 3}), 2 + 2 * 3, 1e-12);
  EXPECT_TRUE(std::isnan(floor->height({8, 8})));
}

TEST(MeshFloor, StopsNeverBelowTheSurfaceItWasMadeFromAndCloseAboveIt) {
  // The bowl tessellated at 0.25 mm: its vertical distance from the surface
  // (second derivatives below 0.0116) is under 0.0002 mm; said as 0.0005.
  const double deviation = 0.0005;
  const auto mesh = makeMeshFloor(gridMesh(100, 80, 0.25, deviation));
  const auto truth = makeExpressionFloor(kBowl);
  const DepthSolver meshSolver(*mesh, {0, 0}, {100, 80}, 0.5);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> x(10, 90), y(10, 70);
  for (int k = 0; k < 40; ++k) {
    const Vec2 c{x(rng), y(rng)};
    for (const Cutter& cutter : kCutters) {
      const double ours = meshSolver.stopHeight(c, cutter);
      const double brute = stopHeightBruteForce(*truth, c, cutter, 0.1);
      EXPECT_GE(ours, brute - 1e-6) << "below the true surface at " << c.x << "," << c.y << " r " << cutter.radius;
      EXPECT_LE(ours, brute + 0.01) << "more than 0.01 mm above at " << c.x << "," << c.y << " r " << cutter.radius;
    }
  }
}

TEST(MeshFloor, DeviationKeepsTheCutterOffInEveryDirection) {
  // On a 45 degree slope the mesh raised by its deviation keeps the ball that
  // much off the plane along its normal: the stop is deviation / cos higher.
  TriangleMesh m;
  m.vertices = {{-50, -50, -50}, {50, -50, 50}, {0, 50, 0}};
  m.triangles = {{0, 1, 2}};
  const Cutter ball{CutterShape::Ball, 5, 5};
  const auto exact = makeMeshFloor(m);
  m.deviation = {0.1};
  const auto kept = makeMeshFloor(m);
  const DepthSolver a(*exact, {-10, -10}, {10, 10}, 0.5), b(*kept, {-10, -10}, {10, 10}, 0.5);
  EXPECT_NEAR(b.stopHeight({0, 0}, ball) - a.stopHeight({0, 0}, ball), 0.1 * std::sqrt(2.0), 1e-9);
}

TEST(MeshFloor, EachTriangleKeepsItsOwnDeviation) {
  // Two triangles side by side: the raise over each is its own.
  TriangleMesh m;
  m.vertices = {{0, 0, 0}, {20, 0, 0}, {20, 20, 0}, {0, 20, 0}, {40, 0, 0}, {40, 20, 0}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}, {1, 4, 5}, {1, 5, 2}};
  m.deviation = {0.01, 0.01, 0.2, 0.2};
  const auto floor = makeMeshFloor(m);
  const DepthSolver solver(*floor, {0, 0}, {40, 20}, 0.5);
  const Cutter flat{CutterShape::Flat, 3, 0};
  EXPECT_NEAR(solver.stopHeight({6, 10}, flat), 0.01, 1e-9);
  EXPECT_NEAR(solver.stopHeight({34, 10}, flat), 0.2, 1e-9);
  EXPECT_NEAR(solver.stopHeight({20, 10}, flat), 0.2, 1e-9);  // over both: the higher
}

TEST(MeshFloor, RefusesBadMeshes) {
  TriangleMesh m;
  m.vertices = {{0, 0, 0}, {10, 0, 0}, {0, 10, 0}};
  EXPECT_THROW(makeMeshFloor(m), Error);  // no triangle
  m.triangles = {{0, 1, 3}};
  EXPECT_THROW(makeMeshFloor(m), Error);  // no vertex 3
  m.triangles = {{0, 1, 2}};
  m.deviation = {-1};
  EXPECT_THROW(makeMeshFloor(m), Error);
  m.deviation = {0.1, 0.2};  // neither one nor one per triangle
  EXPECT_THROW(makeMeshFloor(m), Error);
  m.deviation = {0};
  m.vertices[1][2] = NAN;
  EXPECT_THROW(makeMeshFloor(m), Error);
}

TEST(MeshFloor, PlansThroughTheCallsWithEveryPlungeAboveTheTrueFloor) {
  // The bowl as a plan's mesh floor: no stop below the true surface plus the
  // floor allowance, measured by brute force on the expression.
  const TriangleMesh fm = gridMesh(100, 80, 0.5, 0.002);
  nlohmann::json mesh{{"deviation", fm.deviation[0]}, {"vertices", fm.vertices}, {"triangles", fm.triangles}};
  nlohmann::json input{{"version", 1},
                       {"boundary", {{5, 5}, {95, 5}, {95, 75}, {5, 75}}},
                       {"tools", {{{"diameter", 16}, {"id", 1}}, {{"diameter", 8}, {"id", 2}, {"shape", "ball"}}}},
                       {"top_z", 0},
                       {"safe_z", 5},
                       {"floor", {{"mesh", mesh}}},
                       {"allowance", {{"radial", 0.5}, {"floor", 0.3}}}};
  const nlohmann::json plan = planCall(input, false);
  const auto truth = makeExpressionFloor(kBowl);
  ASSERT_GT(plan["plunges"].size(), 20u);
  for (const auto& p : plan["plunges"]) {
    const int id = p["tool_id"].get<int>();
    const Cutter cutter = id == 1 ? Cutter{CutterShape::Flat, 8, 0} : Cutter{CutterShape::Ball, 4, 4};
    const Vec2 c{p["x"].get<double>(), p["y"].get<double>()};
    const double floorStop = stopHeightBruteForce(*truth, c, grownAround(cutter, 0.3), 0.2) + 0.3;
    EXPECT_GE(p["z"].get<double>(), floorStop - 1e-6) << "gouge at " << c.x << "," << c.y;
  }
}
