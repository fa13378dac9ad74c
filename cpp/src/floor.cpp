#include "plunge/floor.hpp"

#include <BRepAdaptor_Curve.hxx>
#include <BRepAdaptor_Surface.hxx>
#include <BRepBndLib.hxx>
#include <BRepTools.hxx>
#include <BRepTopAdaptor_FClass2d.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <Geom2d_Curve.hxx>
#include <Standard_Failure.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <fstream>
#include <iostream>
#include <limits>
#include <muParser.h>
#include <sstream>

#include "detail.hpp"
#include "plunge/error.hpp"
#include "plunge/optimizer.hpp"

namespace plunge {

namespace {

using detail::kNaN;

int samplesFor(double extent, double spacing, int lo, int hi) {
  return std::clamp(static_cast<int>(std::ceil(extent / spacing)) + 1, lo, hi);
}

bool inside(Vec3 p, Vec2 lo, Vec2 hi) { return p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y; }

// Samples per variable of the fallback when the optimizer runs out of budget.
constexpr int kFallbackSamples = 241;

// The optimizer's options for a peak search: its grid, and progress polled.
OptimizeOptions peakOptions(int samples, const Progress& progress) {
  OptimizeOptions opt;
  opt.samples = samples;
  opt.clusterRadius = 2.5 / samples;  // a few grid steps: peaks stay apart
  opt.skipNonFinite = true;           // outside the domain (a trimmed face)
  opt.poll = [&progress] { progress.tick(); };
  return opt;
}

// The fallback of a peak search: `at(i, j)` on an n x m grid (m = 1: a curve)
// gives a point (z NaN outside the domain); every grid point at least as high
// as its neighbours, raised by its largest rise or fall to one of them.
template <class F>
std::vector<Vec3> sampledPeaks(int n, int m, F at, const Progress& progress) {
  std::vector<Vec3> g(static_cast<size_t>(n) * m);
  for (int j = 0; j < m; ++j) {
    progress.tick();
    for (int i = 0; i < n; ++i) g[static_cast<size_t>(j) * n + i] = at(i, j);
  }
  std::vector<Vec3> out;
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < n; ++i) {
      const Vec3& p = g[static_cast<size_t>(j) * n + i];
      if (!std::isfinite(p.z)) continue;
      bool top = true;
      double rise = 0;
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) {
          const int a = i + di, b = j + dj;
          if ((!di && !dj) || a < 0 || a >= n || b < 0 || b >= m) continue;
          const double z = g[static_cast<size_t>(b) * n + a].z;
          if (!std::isfinite(z)) continue;
          top = top && z <= p.z;
          rise = std::max(rise, std::fabs(z - p.z));
        }
      if (top) out.push_back({p.x, p.y, p.z + rise});
    }
  return out;
}

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

// --- BREP faces (OpenCASCADE) --------------------------------------------------

// Whether (u, v) lies outside a face, with a raster of its parameter box filled
// as queries come: a cell that no piece of the face's boundary comes near takes
// the state of its centre, classified exactly once; in a cell the boundary
// crosses or passes near, every point is classified exactly. The boundary is
// its pcurves as polylines within a tenth of a cell, and "near" is the cell and
// its eight neighbours. (OCCT's classifier, run per point, was 97 % of a
// sculptured plan's time.)
class UvClassifier {
 public:
  UvClassifier(const TopoDS_Face& face, double u0, double u1, double v0, double v1)
      : exact_(face, 1e-9), u0_(u0), v0_(v0), du_((u1 - u0) / kCells), dv_((v1 - v0) / kCells),
        state_(kCells * kCells, kUnknown) {
    if (!(du_ > 0.0) || !(dv_ > 0.0)) {
      state_.assign(state_.size(), kNear);
      return;
    }
    for (TopExp_Explorer ex(face, TopAbs_EDGE); ex.More(); ex.Next())
      if (!markEdge(TopoDS::Edge(ex.Current()), face)) {
        state_.assign(state_.size(), kNear);  // a boundary not sampled: exact everywhere
        return;
      }
  }

  bool outside(double u, double v) const {
    const double fu = (u - u0_) / du_, fv = (v - v0_) / dv_;
    if (!(fu >= 0.0 && fv >= 0.0 && fu < kCells && fv < kCells)) return exactOut(u, v);
    unsigned char& s = state_[static_cast<size_t>(fv) * kCells + static_cast<size_t>(fu)];
    if (s == kNear) return exactOut(u, v);
    if (s == kUnknown)
      s = exactOut(u0_ + (std::floor(fu) + 0.5) * du_, v0_ + (std::floor(fv) + 0.5) * dv_) ? kOut : kIn;
    return s == kOut;
  }

 private:
  static constexpr int kCells = 256;
  static constexpr unsigned char kUnknown = 0, kIn = 1, kOut = 2, kNear = 3;

  bool exactOut(double u, double v) const { return exact_.Perform(gp_Pnt2d(u, v)) == TopAbs_OUT; }

  // Marks the cells near the edge's pcurve; false if it has none.
  bool markEdge(const TopoDS_Edge& e, const TopoDS_Face& face) {
    double t0, t1;
    const Handle(Geom2d_Curve) c = BRep_Tool::CurveOnSurface(e, face, t0, t1);
    if (c.IsNull() || !std::isfinite(t0) || !std::isfinite(t1)) return false;
    const double tol = 0.1 * std::min(du_, dv_);
    std::vector<gp_Pnt2d> pts;
    auto at = [&](double t) { return c->Value(t); };
    // Chords split until their middles lie within tol of them (from 64 pieces,
    // so that no wiggle hides between two samples).
    std::function<void(double, gp_Pnt2d, double, gp_Pnt2d, int)> split = [&](double a, gp_Pnt2d pa, double b,
                                                                              gp_Pnt2d pb, int depth) {
      const double m = 0.5 * (a + b);
      const gp_Pnt2d pm = at(m);
      const double lx = pb.X() - pa.X(), ly = pb.Y() - pa.Y(), len = std::sqrt(lx * lx + ly * ly);
      const double off = len > 0 ? std::fabs((pm.X() - pa.X()) * ly - (pm.Y() - pa.Y()) * lx) / len
                                 : pm.Distance(pa);
      if (off > tol && depth < 24) {
        split(a, pa, m, pm, depth + 1);
        split(m, pm, b, pb, depth + 1);
        return;
      }
      pts.push_back(pm);
      pts.push_back(pb);
    };
    constexpr int kPieces = 64;
    gp_Pnt2d prev = at(t0);
    pts.push_back(prev);
    for (int k = 1; k <= kPieces; ++k) {
      const double a = t0 + (t1 - t0) * (k - 1) / kPieces, b = t0 + (t1 - t0) * k / kPieces;
      const gp_Pnt2d pb = at(b);
      split(a, prev, b, pb, 0);
      prev = pb;
    }
    for (size_t k = 1; k < pts.size(); ++k) markSegment(pts[k - 1], pts[k]);
    return true;
  }

  void markSegment(gp_Pnt2d a, gp_Pnt2d b) {
    const double lx = (b.X() - a.X()) / du_, ly = (b.Y() - a.Y()) / dv_;
    const int steps = 1 + static_cast<int>(std::ceil(2.0 * std::max(std::fabs(lx), std::fabs(ly))));
    for (int s = 0; s <= steps; ++s) {
      const double f = static_cast<double>(s) / steps;
      const long i = static_cast<long>(std::floor((a.X() - u0_) / du_ + f * lx));
      const long j = static_cast<long>(std::floor((a.Y() - v0_) / dv_ + f * ly));
      for (long dj = -1; dj <= 1; ++dj)
        for (long di = -1; di <= 1; ++di) {
          const long x = i + di, y = j + dj;
          if (x >= 0 && y >= 0 && x < kCells && y < kCells) state_[static_cast<size_t>(y) * kCells + x] = kNear;
        }
    }
  }

  BRepTopAdaptor_FClass2d exact_;
  double u0_, v0_, du_, dv_;
  mutable std::vector<unsigned char> state_;
};

class BrepFloor : public FloorSurface {
 public:
  // A clone shares the (read-only) shape and builds its own adaptors, whose
  // B-spline caches are what evaluation changes.
  std::unique_ptr<FloorSurface> clone() const override { return std::make_unique<BrepFloor>(shape_); }
  explicit BrepFloor(const TopoDS_Shape& shape) : shape_(shape) {
    for (TopExp_Explorer ex(shape, TopAbs_FACE); ex.More(); ex.Next()) {
      auto f = std::make_unique<Face>();
      f->face = TopoDS::Face(ex.Current());
      f->surf.Initialize(f->face);
      BRepTools::UVBounds(f->face, f->u0, f->u1, f->v0, f->v1);
      f->cls = std::make_unique<UvClassifier>(f->face, f->u0, f->u1, f->v0, f->v1);
      Bnd_Box box;
      BRepBndLib::AddOptimal(f->face, box, false, false);  // the surface, not its control net
      double z0, z1;
      box.Get(f->lo.x, f->lo.y, z0, f->hi.x, f->hi.y, z1);
      // A coarse grid of the face: Newton's start points for (x, y) -> (u, v).
      for (int i = 0; i <= kGrid; ++i)
        for (int j = 0; j <= kGrid; ++j) {
          const double u = f->u0 + (f->u1 - f->u0) * i / kGrid, v = f->v0 + (f->v1 - f->v0) * j / kGrid;
          const gp_Pnt p = f->surf.Value(u, v);
          f->samples.push_back({u, v, p.X(), p.Y()});
        }
      faces_.push_back(std::move(f));
    }
    if (faces_.empty()) throw Error("floor.brep: the shape has no face");
  }

  double height(Vec2 p) const override {
    double best = kNaN;
    for (const auto& f : faces_) {
      const double tol = 1e-7;
      if (p.x < f->lo.x - tol || p.x > f->hi.x + tol || p.y < f->lo.y - tol || p.y > f->hi.y + tol) continue;
      double z;
      if (faceHeight(*f, p, z) && !(z <= best)) best = z;
    }
    return best;
  }

  PeakSearch peaks(Vec2 lo, Vec2 hi, double spacing, const Progress& progress) const override {
    PeakSearch out;
    const Vec2 elo = lo - Vec2{spacing, spacing}, ehi = hi + Vec2{spacing, spacing};
    for (const auto& f : faces_)
      if (!(f->hi.x < elo.x || f->lo.x > ehi.x || f->hi.y < elo.y || f->lo.y > ehi.y))
        facePeaks(*f, spacing, progress, out);
    // Ridges: local maxima of z along every edge; and every vertex.
    TopTools_IndexedMapOfShape edges, vertices;
    TopExp::MapShapes(shape_, TopAbs_EDGE, edges);
    TopExp::MapShapes(shape_, TopAbs_VERTEX, vertices);
    for (int i = 1; i <= edges.Extent(); ++i) edgePeaks(TopoDS::Edge(edges(i)), spacing, progress, out);
    for (int i = 1; i <= vertices.Extent(); ++i) {
      const gp_Pnt p = BRep_Tool::Pnt(TopoDS::Vertex(vertices(i)));
      out.points.push_back({p.X(), p.Y(), p.Z()});
    }
    std::vector<Vec3> kept;
    for (const Vec3& p : out.points)
      if (inside(p, elo, ehi)) kept.push_back(p);
    out.points = std::move(kept);
    return out;
  }

 private:
  static constexpr int kGrid = 24;
  struct Sample {
    double u, v, x, y;
  };
  struct Face {
    TopoDS_Face face;
    BRepAdaptor_Surface surf;
    std::unique_ptr<UvClassifier> cls;
    double u0 = 0, u1 = 0, v0 = 0, v1 = 0;
    Vec2 lo, hi;
    std::vector<Sample> samples;
    mutable double lastU = 0, lastV = 0;  // Newton's warm start: neighbouring queries are close
    mutable bool hasLast = false;
  };

  // Peaks inside a face: local maxima of z(u, v) over its parameters.
  void facePeaks(const Face& f, double spacing, const Progress& progress, PeakSearch& out) const {
    auto z = [&](double u, double v) {
      // The classifier never returns from a non-finite point (the optimizer
      // does not pass one; the fallback's grid has none either).
      if (f.cls->outside(u, v)) return kNaN;
      return f.surf.Value(u, v).Z();
    };
    const int n = samplesFor(std::max(f.hi.x - f.lo.x, f.hi.y - f.lo.y), spacing, 21, 201);
    OptimizeResult r;
    try {
      r = optimize([&](const double* uv) { return z(uv[0], uv[1]); }, {{f.u0, f.u1}, {f.v0, f.v1}},
                   Goal::Maximize, peakOptions(n, progress));
    } catch (const Cancelled&) {
      throw;
    } catch (const Error&) {
      return;  // no finite value: a face with nothing inside its parameter box
    }
    for (const LocalOptimum& o : r.locals) {
      const gp_Pnt p = f.surf.Value(o.x[0], o.x[1]);
      out.points.push_back({p.X(), p.Y(), p.Z()});
    }
    if (r.converged) return;
    ++out.fallbacks;
    const int k = kFallbackSamples;
    for (const Vec3& p : sampledPeaks(k, k, [&](int i, int j) {
           const double u = f.u0 + (f.u1 - f.u0) * i / (k - 1), v = f.v0 + (f.v1 - f.v0) * j / (k - 1);
           const gp_Pnt q = f.surf.Value(u, v);
           return Vec3{q.X(), q.Y(), z(u, v)};
         }, progress))
      out.points.push_back(p);
  }

  void edgePeaks(const TopoDS_Edge& e, double spacing, const Progress& progress, PeakSearch& out) const {
    if (BRep_Tool::Degenerated(e) || !BRep_Tool::IsGeometric(e)) return;
    BRepAdaptor_Curve c(e);
    const double t0 = c.FirstParameter(), t1 = c.LastParameter();
    if (!(t1 > t0) || !std::isfinite(t0) || !std::isfinite(t1)) return;
    OptimizeOptions opt = peakOptions(samplesFor(c.Value(t0).Distance(c.Value(t1)) * 2, spacing, 21, 401), progress);
    opt.clusterRadius = OptimizeOptions{}.clusterRadius;  // an edge is finite everywhere, its peaks few
    opt.skipNonFinite = false;
    const OptimizeResult r = optimize([&](const double* t) { return c.Value(t[0]).Z(); }, {{t0, t1}},
                                      Goal::Maximize, opt);
    for (const LocalOptimum& o : r.locals) {
      const gp_Pnt p = c.Value(o.x[0]);
      out.points.push_back({p.X(), p.Y(), p.Z()});
    }
    if (r.converged) return;
    ++out.fallbacks;
    for (const Vec3& p : sampledPeaks(kFallbackSamples * 4, 1, [&](int i, int) {
           const gp_Pnt q = c.Value(t0 + (t1 - t0) * i / (kFallbackSamples * 4 - 1));
           return Vec3{q.X(), q.Y(), q.Z()};
         }, progress))
      out.points.push_back(p);
  }

  // Newton on (x(u, v), y(u, v)) = p; the face's point above p, if any.
  bool solve(const Face& f, Vec2 p, double& u, double& v) const {
    for (int it = 0; it < 30; ++it) {
      gp_Pnt s;
      gp_Vec su, sv;
      f.surf.D1(u, v, s, su, sv);
      const double rx = s.X() - p.x, ry = s.Y() - p.y;
      if (std::hypot(rx, ry) < 1e-10) return true;
      const double det = su.X() * sv.Y() - su.Y() * sv.X();
      if (std::fabs(det) < 1e-14) return false;  // vertical: not part of a height field
      const double du = (rx * sv.Y() - ry * sv.X()) / det, dv = (su.X() * ry - su.Y() * rx) / det;
      u = std::clamp(u - du, f.u0, f.u1);
      v = std::clamp(v - dv, f.v0, f.v1);
    }
    const gp_Pnt s = f.surf.Value(u, v);
    return std::hypot(s.X() - p.x, s.Y() - p.y) < 1e-7;
  }

  bool faceHeight(const Face& f, Vec2 p, double& z) const {
    double u, v;
    bool ok = false;
    if (f.hasLast) {
      u = f.lastU;
      v = f.lastV;
      ok = solve(f, p, u, v);
    }
    if (!ok) {
      const Sample* best = &f.samples.front();
      double nearest = std::numeric_limits<double>::infinity();
      for (const Sample& s : f.samples) {
        const double d2 = (s.x - p.x) * (s.x - p.x) + (s.y - p.y) * (s.y - p.y);
        if (d2 < nearest) nearest = d2, best = &s;
      }
      u = best->u;
      v = best->v;
      ok = solve(f, p, u, v);
    }
    if (!ok || f.cls->outside(u, v)) return false;
    f.lastU = u;
    f.lastV = v;
    f.hasLast = true;
    z = f.surf.Value(u, v).Z();
    return true;
  }

  TopoDS_Shape shape_;
  std::vector<std::unique_ptr<Face>> faces_;
};

std::unique_ptr<FloorSurface> brepFrom(std::istream& in, const std::string& what) {
  TopoDS_Shape shape;
  BRep_Builder builder;
  // OpenCASCADE reports format problems on standard output: keep them off it.
  std::ostringstream chatter;
  std::streambuf* out = std::cout.rdbuf(chatter.rdbuf());
  try {
    BRepTools::Read(shape, in, builder);
  } catch (const Standard_Failure& e) {
    std::cout.rdbuf(out);
    throw Error("floor.brep: cannot read " + what + ": " + e.GetMessageString());
  }
  std::cout.rdbuf(out);
  if (shape.IsNull()) throw Error("floor.brep: " + what + " holds no BREP shape");
  return std::make_unique<BrepFloor>(shape);
}

constexpr std::uintmax_t kMaxBrepBytes = 1ULL << 30;

}  // namespace

std::unique_ptr<FloorSurface> makeFlatFloor(double z) { return std::make_unique<FlatFloor>(z); }

std::unique_ptr<FloorSurface> makeExpressionFloor(const std::string& expression) {
  return std::make_unique<ExpressionFloor>(expression);
}

std::unique_ptr<FloorSurface> makeBrepFloor(const std::string& path) {
  // A regular file of a sane size: not a device or pipe that never ends.
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw Error("floor.brep: cannot read " + path + ": no such file");
  if (!std::filesystem::is_regular_file(path, ec)) throw Error("floor.brep: " + path + " is not a file");
  if (std::filesystem::file_size(path, ec) > kMaxBrepBytes)
    throw Error("floor.brep: " + path + " is larger than 1 GB");
  std::ifstream in(path);
  if (!in) throw Error("floor.brep: cannot read " + path);
  return brepFrom(in, path);
}

std::unique_ptr<FloorSurface> makeBrepFloorFromText(const std::string& brep) {
  std::istringstream in(brep);
  return brepFrom(in, "the BREP text");
}

}  // namespace plunge
