#include "mesh_floor.hpp"

#include <algorithm>
#include <boost/geometry.hpp>
#include <boost/geometry/index/rtree.hpp>
#include <boost/iterator/function_output_iterator.hpp>
#include <cmath>
#include <utility>
#include <vector>

#include "detail.hpp"
#include "plunge/error.hpp"

namespace plunge {

namespace bg = boost::geometry;
namespace bgi = boost::geometry::index;
using detail::kInf;
using detail::kNaN;

namespace {

// More triangles than a floor of a few square metres at 0.001 mm needs: a
// bound that keeps a hostile input from exhausting memory.
constexpr size_t kMaxTriangles = 8000000;

Vec3 operator-(const Vec3& a, const Vec3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vec3 cross(const Vec3& a, const Vec3& b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
Vec2 xy(const Vec3& p) { return {p.x, p.y}; }

// The cutter's corner radius: a ball's is its radius, a flat one's 0.
double cornerOf(const Cutter& c) {
  return c.shape == CutterShape::Flat ? 0.0 : c.shape == CutterShape::Ball ? c.radius : c.cornerRadius;
}

// The highest tip height of the cutter at c touching the segment p-q: the
// lift z(t) - profile(|P(t) - c|) over the part of the segment under the
// cutter. The distance is convex in t and the profile convex and rising in
// it, so the lift is concave: a golden-section search finds its maximum.
double dropOnEdge(const Vec3& p, const Vec3& q, Vec2 c, const Cutter& cutter) {
  const Vec2 w = xy(p) - c, e = xy(q) - xy(p);
  const double a = dot(e, e);
  if (a <= 1e-24) return -kInf;  // vertical: its top vertex decides
  const double b = 2 * dot(w, e), cc = dot(w, w) - cutter.radius * cutter.radius;
  const double disc = b * b - 4 * a * cc;
  if (disc < 0) return -kInf;
  const double root = std::sqrt(disc);
  double lo = std::max(0.0, (-b - root) / (2 * a)), hi = std::min(1.0, (-b + root) / (2 * a));
  if (lo > hi) return -kInf;
  auto lift = [&](double t) { return p.z + t * (q.z - p.z) - cutterProfile(cutter, norm(w + e * t)); };
  double best = std::max(lift(lo), lift(hi));
  if (cutter.shape == CutterShape::Flat) return best;  // linear: the ends
  constexpr double kGolden = 0.6180339887498949;
  double x1 = hi - kGolden * (hi - lo), x2 = lo + kGolden * (hi - lo);
  double f1 = lift(x1), f2 = lift(x2);
  for (int i = 0; i < 200 && hi - lo > 1e-14; ++i) {
    if (f1 < f2) {
      lo = x1, x1 = x2, f1 = f2;
      x2 = lo + kGolden * (hi - lo), f2 = lift(x2);
    } else {
      hi = x2, x2 = x1, f2 = f1;
      x1 = hi - kGolden * (hi - lo), f1 = lift(x1);
    }
  }
  return std::max({best, f1, f2});
}

// Whether q lies in the triangle's shadow (edges included, to rounding).
bool inShadow(Vec2 q, Vec2 a, Vec2 b, Vec2 c) {
  const double d1 = cross(b - a, q - a), d2 = cross(c - b, q - b), d3 = cross(a - c, q - c);
  const double tol = 1e-12 * (dot(b - a, b - a) + dot(c - b, c - b) + dot(a - c, a - c));
  return (d1 >= -tol && d2 >= -tol && d3 >= -tol) || (d1 <= tol && d2 <= tol && d3 <= tol);
}

}  // namespace

double dropOnTriangle(const Vec3& a, const Vec3& b, const Vec3& c, Vec2 center, const Cutter& cutter) {
  const double R = cutter.radius, rc = cornerOf(cutter), rf = R - rc;
  double best = -kInf;
  // Vertices and edges (the ends of each edge's part under the cutter are
  // searched too, so its vertices need no test of their own).
  best = std::max({best, dropOnEdge(a, b, center, cutter), dropOnEdge(b, c, center, cutter),
                   dropOnEdge(c, a, center, cutter)});
  for (const Vec3* v : {&a, &b, &c}) {
    const double d = dist(xy(*v), center);
    if (d <= R) best = std::max(best, v->z - cutterProfile(cutter, d));
  }
  // The facet: the cutter (a disk of radius rf swept by a ball of radius rc)
  // touches the plane at the point of its rim uphill, lowered by rc along the
  // normal; valid where that point lies in the triangle.
  Vec3 n = cross(b - a, c - a);
  if (n.z < 0) n = {-n.x, -n.y, -n.z};
  const double len = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
  if (!(len > 0)) return best;
  n = {n.x / len, n.y / len, n.z / len};
  if (n.z < 1e-12) return best;  // vertical: its edges decide
  const double nxy = std::hypot(n.x, n.y);
  const Vec2 uphill = nxy > 1e-15 ? Vec2{-n.x / nxy, -n.y / nxy} : Vec2{0, 0};
  const Vec2 s = center + uphill * rf;                  // the ball's centre circle, uphill
  const Vec2 contact = s - Vec2{n.x, n.y} * rc;         // where it touches the plane
  if (!inShadow(contact, xy(a), xy(b), xy(c))) return best;
  const double h = a.z - rc + (rc - n.x * (s.x - a.x) - n.y * (s.y - a.y)) / n.z;
  return std::max(best, h);
}

namespace {

using Point = bg::model::point<double, 2, bg::cs::cartesian>;
using Box = bg::model::box<Point>;
using Entry = std::pair<Box, std::uint32_t>;

class MeshFloor : public FloorSurface {
 public:
  explicit MeshFloor(const TriangleMesh& mesh) {
    auto built = std::make_shared<Data>();
    Data& d = *built;
    d.deviation = mesh.deviation.size() == 1 ? std::vector<double>(mesh.triangles.size(), mesh.deviation[0])
                                             : mesh.deviation;
    d.maxDeviation = *std::max_element(d.deviation.begin(), d.deviation.end());
    d.vertices.reserve(mesh.vertices.size());
    for (const auto& v : mesh.vertices) d.vertices.push_back({v[0], v[1], v[2]});
    d.triangles = mesh.triangles;
    std::vector<Entry> entries;
    entries.reserve(d.triangles.size());
    d.top.reserve(d.triangles.size());
    std::vector<bool> lower(d.vertices.size(), false);  // a neighbour stands higher
    for (std::uint32_t i = 0; i < d.triangles.size(); ++i) {
      const auto& t = d.triangles[i];
      const Vec3 &a = d.vertices[t[0]], &b = d.vertices[t[1]], &c = d.vertices[t[2]];
      entries.push_back({Box(Point(std::min({a.x, b.x, c.x}), std::min({a.y, b.y, c.y})),
                             Point(std::max({a.x, b.x, c.x}), std::max({a.y, b.y, c.y}))),
                         i});
      d.top.push_back(std::max({a.z, b.z, c.z}));
      for (int k = 0; k < 3; ++k)
        for (int m = 0; m < 3; ++m)
          if (d.vertices[t[m]].z > d.vertices[t[k]].z) lower[t[k]] = true;
    }
    d.index = Index(entries.begin(), entries.end());  // bulk loading: deterministic
    for (size_t i = 0; i < d.vertices.size(); ++i)
      if (!lower[i]) d.peaks.push_back(d.vertices[i]);
    data_ = std::move(built);
  }

  double height(Vec2 p) const override {
    const Data& d = *data_;
    double best = kNaN;
    d.index.query(bgi::intersects(Point(p.x, p.y)), boost::make_function_output_iterator([&](const Entry& e) {
                    const auto& t = d.triangles[e.second];
                    const Vec3 &a = d.vertices[t[0]], &b = d.vertices[t[1]], &c = d.vertices[t[2]];
                    const double area = cross(xy(b) - xy(a), xy(c) - xy(a));
                    if (std::fabs(area) <= 1e-18 || !inShadow(p, xy(a), xy(b), xy(c))) return;
                    // Barycentric weights of b and c.
                    const double u = cross(p - xy(a), xy(c) - xy(a)) / area, v = cross(xy(b) - xy(a), p - xy(a)) / area;
                    const double z = a.z + u * (b.z - a.z) + v * (c.z - a.z);
                    if (!(z <= best)) best = z;
                  }));
    return best;
  }

  // A piecewise linear surface has its local maxima at vertices.
  PeakSearch peaks(Vec2 lo, Vec2 hi, double, const Progress& progress) const override {
    PeakSearch out;
    for (const Vec3& p : data_->peaks) {
      progress.tick();
      if (detail::inside(p, lo, hi)) out.points.push_back(p);
    }
    return out;
  }

  // Each triangle lies within its deviation of the true surface: the cutter
  // grown by that much in every direction, dropped on it, then raised by it,
  // clears every surface that close to the triangle.
  std::optional<double> exactStopHeight(Vec2 c, const Cutter& cutter) const override {
    const Data& d = *data_;
    const double R = cutter.radius + d.maxDeviation;
    std::vector<std::pair<double, std::uint32_t>> near;  // (highest its drop can be, triangle)
    d.index.query(bgi::intersects(Box(Point(c.x - R, c.y - R), Point(c.x + R, c.y + R))),
                  boost::make_function_output_iterator([&](const Entry& e) {
                    near.push_back({d.top[e.second] + d.deviation[e.second], e.second});
                  }));
    // Highest first: a triangle whose highest vertex (raised by its deviation)
    // is below the best contact so far cannot lift the cutter (its profile is
    // never below its tip).
    std::sort(near.begin(), near.end(), [](const auto& x, const auto& y) {
      return x.first > y.first || (x.first == y.first && x.second < y.second);
    });
    double best = -kInf;
    for (const auto& [bound, i] : near) {
      if (bound <= best) break;
      const auto& t = d.triangles[i];
      const double dev = d.deviation[i];
      const Cutter g = dev > 0 ? grownAround(cutter, dev) : cutter;
      best = std::max(best, dropOnTriangle(d.vertices[t[0]], d.vertices[t[1]], d.vertices[t[2]], c, g) + dev);
    }
    return std::isfinite(best) ? best : kNaN;
  }

  std::unique_ptr<FloorSurface> clone() const override { return std::make_unique<MeshFloor>(*this); }

 private:
  using Index = bgi::rtree<Entry, bgi::rstar<16>>;
  struct Data {
    std::vector<Vec3> vertices;
    std::vector<std::array<std::uint32_t, 3>> triangles;
    std::vector<double> top;  // each triangle's highest vertex
    std::vector<Vec3> peaks;  // vertices no neighbour stands above
    std::vector<double> deviation;  // each triangle's
    double maxDeviation = 0.0;
    Index index;
  };
  // Read only once built: clones (one per thread) share it.
  std::shared_ptr<const Data> data_;
};

}  // namespace

void checkMesh(const TriangleMesh& mesh, const std::string& key) {
  if (mesh.triangles.empty()) throw Error(key + ".triangles: at least one triangle is needed");
  if (mesh.triangles.size() > kMaxTriangles)
    throw Error(key + ".triangles: " + std::to_string(mesh.triangles.size()) + " triangles, more than " +
                std::to_string(kMaxTriangles) + ": tessellate the faces more coarsely");
  if (mesh.deviation.size() != 1 && mesh.deviation.size() != mesh.triangles.size())
    throw Error(key + ".deviation: expected one distance, or one per triangle (" +
                std::to_string(mesh.triangles.size()) + "), not " + std::to_string(mesh.deviation.size()));
  for (double d : mesh.deviation)
    if (!std::isfinite(d) || d < 0) throw Error(key + ".deviation: expected distances of 0 or more (mm)");
  for (size_t i = 0; i < mesh.vertices.size(); ++i)
    for (double v : mesh.vertices[i])
      if (!std::isfinite(v)) throw Error(key + ".vertices[" + std::to_string(i) + "]: not a finite point");
  for (size_t i = 0; i < mesh.triangles.size(); ++i)
    for (std::uint32_t k : mesh.triangles[i])
      if (k >= mesh.vertices.size())
        throw Error(key + ".triangles[" + std::to_string(i) + "]: vertex " + std::to_string(k) +
                    " does not exist (" + std::to_string(mesh.vertices.size()) + " vertices)");
}

std::unique_ptr<FloorSurface> makeMeshFloor(const TriangleMesh& mesh) {
  checkMesh(mesh, "floor.mesh");
  return std::make_unique<MeshFloor>(mesh);
}

std::unique_ptr<FloorSurface> makeMeshSurface(const TriangleMesh& mesh) {
  if (mesh.triangles.empty()) return nullptr;
  return std::make_unique<MeshFloor>(mesh);
}

}  // namespace plunge
