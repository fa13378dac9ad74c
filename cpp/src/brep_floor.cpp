// BREP floors: the faces of a BREP file, read and evaluated with OpenCASCADE
// (built with PLUNGE_WITH_OCCT only).
#include "floor.hpp"

#include <BRepAdaptor_Curve.hxx>
#include <BRepAdaptor_Surface.hxx>
#include <BRepBndLib.hxx>
#include <BRepTools.hxx>
#include <BRepTools_WireExplorer.hxx>
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
#include <TopoDS_Wire.hxx>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <fstream>
#include <iostream>
#include <limits>
#include <sstream>

#include "detail.hpp"
#include "plunge/error.hpp"
#include "plunge/optimizer.hpp"

namespace plunge {

namespace {

using detail::inside;
using detail::kFallbackSamples;
using detail::kNaN;
using detail::peakOptions;
using detail::sampledPeaks;
using detail::samplesFor;

// Whether (u, v) lies outside a face, without running OCCT's classifier per
// point (it was 97 % of a sculptured plan's time). The face's wires, as closed
// polylines in (u, v) within a thousandth of a cell of their pcurves (about
// 0.5 um on the face: under the tolerance of any wire), decide by the parity
// of their crossings of a ray from the point.
// A raster of the parameter box (cells of about 0.5 mm on the face, 64 to 512
// a side) keeps, for each cell no polyline comes within a quarter cell of, the
// state of its centre; each row lists the polyline pieces that cross it.
// Points off the box are classified by OCCT.
class UvClassifier {
 public:
  UvClassifier(const TopoDS_Face& face, double u0, double u1, double v0, double v1, double extent)
      : exact_(face, 1e-9), n_(std::clamp(static_cast<int>(std::ceil(extent / kCellSize)), 64, 512)),
        u0_(u0), v0_(v0), du_((u1 - u0) / n_), dv_((v1 - v0) / n_) {
    exactOnly_ = !(du_ > 0.0) || !(dv_ > 0.0) || !wires(face);
    if (!exactOnly_) index();
  }

  bool outside(double u, double v) const {
    const double x = (u - u0_) / du_, y = (v - v0_) / dv_;
    // The box's far sides (where searches end up, clamped) belong to its last cells.
    if (exactOnly_ || !(x >= 0.0 && y >= 0.0 && x <= n_ && y <= n_)) return exactOut(u, v);
    const size_t k = static_cast<size_t>(std::min(y, n_ - 0.5)) * n_ + static_cast<size_t>(std::min(x, n_ - 0.5));
    unsigned char& s = state_[k];
    if (s == kNear) return parityOut({x, y});
    if (s == kUnknown) s = parityOut({std::floor(x) + 0.5, std::floor(y) + 0.5}) ? kOut : kIn;
    return s == kOut;
  }

 private:
  static constexpr double kCellSize = 0.5;    // mm on the face, about
  static constexpr double kChord = 0.001;     // cells: the polylines' distance from the pcurves
  static constexpr double kNearCells = 0.25;  // cells: the band marked around the polylines
  static constexpr unsigned char kUnknown = 0, kIn = 1, kOut = 2, kNear = 3;
  struct Seg {
    Vec2 a, b;  // in cells
  };

  bool exactOut(double u, double v) const { return exact_.Perform(gp_Pnt2d(u, v)) == TopAbs_OUT; }

  // A ray from q to +u: outside if it crosses the polylines an even number of times.
  bool parityOut(Vec2 q) const {
    const size_t row = static_cast<size_t>(std::min(q.y, n_ - 0.5));
    int crossings = 0;
    for (int s = rowStart_[row]; s < rowStart_[row + 1]; ++s) {
      const Seg& g = segs_[rowSeg_[s]];
      if ((g.a.y > q.y) != (g.b.y > q.y) && g.a.x + (q.y - g.a.y) * (g.b.x - g.a.x) / (g.b.y - g.a.y) > q.x)
        ++crossings;
    }
    return crossings % 2 == 0;
  }

  // Every wire as a closed polyline (edges in order, each along its
  // orientation); false where a wire cannot be walked so.
  bool wires(const TopoDS_Face& face) {
    for (TopExp_Explorer w(face, TopAbs_WIRE); w.More(); w.Next()) {
      const TopoDS_Wire wire = TopoDS::Wire(w.Current());
      int edges = 0, walked = 0;
      for (TopExp_Explorer e(wire, TopAbs_EDGE); e.More(); e.Next()) ++edges;
      std::vector<Vec2> loop;
      for (BRepTools_WireExplorer e(wire, face); e.More(); e.Next(), ++walked)
        if (!appendEdge(e.Current(), face, loop)) return false;
      if (walked != edges || loop.size() < 2 || dist(loop.front(), loop.back()) > 1.0) return false;
      for (size_t k = 0; k < loop.size(); ++k) segs_.push_back({loop[k], loop[(k + 1) % loop.size()]});
    }
    return !segs_.empty();
  }

  // The edge's pcurve in cells, chords split until their middles lie within
  // kChord of them (from 64 pieces, so that no wiggle hides between samples).
  bool appendEdge(const TopoDS_Edge& e, const TopoDS_Face& face, std::vector<Vec2>& loop) const {
    double t0, t1;
    const Handle(Geom2d_Curve) c = BRep_Tool::CurveOnSurface(e, face, t0, t1);
    if (c.IsNull() || !std::isfinite(t0) || !std::isfinite(t1)) return false;
    auto at = [&](double t) {
      const gp_Pnt2d p = c->Value(t);
      return Vec2{(p.X() - u0_) / du_, (p.Y() - v0_) / dv_};
    };
    std::vector<Vec2> pts{at(t0)};
    std::function<void(double, Vec2, double, Vec2, int)> split = [&](double a, Vec2 pa, double b, Vec2 pb,
                                                                     int depth) {
      const double m = 0.5 * (a + b);
      const Vec2 pm = at(m);
      if (distanceToSegment({pa, pb}, pm) > kChord && depth < 24) {
        split(a, pa, m, pm, depth + 1);
        split(m, pm, b, pb, depth + 1);
        return;
      }
      pts.push_back(pm);
      pts.push_back(pb);
    };
    constexpr int kPieces = 64;
    for (int k = 1; k <= kPieces; ++k) {
      const double a = t0 + (t1 - t0) * (k - 1) / kPieces, b = t0 + (t1 - t0) * k / kPieces;
      split(a, pts.back(), b, at(b), 0);
    }
    if (e.Orientation() == TopAbs_REVERSED) std::reverse(pts.begin(), pts.end());
    loop.insert(loop.end(), pts.begin(), pts.end());
    return true;
  }

  // The cells within kNearCells of each segment marked, and the rows it spans
  // listed (row -> segments).
  void index() {
    state_.assign(static_cast<size_t>(n_) * n_, kUnknown);
    std::vector<std::pair<size_t, int>> rows;
    for (size_t s = 0; s < segs_.size(); ++s) {
      const Vec2 a = segs_[s].a, b = segs_[s].b;
      const int steps = 1 + static_cast<int>(std::ceil(4.0 * std::max(std::fabs(b.x - a.x), std::fabs(b.y - a.y))));
      for (int t = 0; t <= steps; ++t) {
        const Vec2 p = a + (b - a) * (static_cast<double>(t) / steps);
        for (long j = static_cast<long>(std::floor(p.y - kNearCells)); j <= static_cast<long>(std::floor(p.y + kNearCells)); ++j)
          for (long i = static_cast<long>(std::floor(p.x - kNearCells));
               i <= static_cast<long>(std::floor(p.x + kNearCells)); ++i)
            if (i >= 0 && j >= 0 && i < n_ && j < n_) state_[static_cast<size_t>(j) * n_ + i] = kNear;
      }
      const long j0 = std::max(0L, static_cast<long>(std::floor(std::min(a.y, b.y))));
      const long j1 = std::min<long>(n_ - 1, static_cast<long>(std::floor(std::max(a.y, b.y))));
      for (long j = j0; j <= j1; ++j) rows.push_back({static_cast<size_t>(j), static_cast<int>(s)});
    }
    compress(rows, static_cast<size_t>(n_), rowStart_, rowSeg_);
  }

  static void compress(std::vector<std::pair<size_t, int>>& pairs, size_t n, std::vector<int>& start,
                       std::vector<int>& items) {
    std::sort(pairs.begin(), pairs.end());
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
    start.assign(n + 1, 0);
    for (const auto& p : pairs) ++start[p.first + 1];
    for (size_t k = 0; k < n; ++k) start[k + 1] += start[k];
    items.resize(pairs.size());
    for (size_t k = 0; k < pairs.size(); ++k) items[k] = pairs[k].second;
  }

  BRepTopAdaptor_FClass2d exact_;
  int n_;
  double u0_, v0_, du_, dv_;
  bool exactOnly_ = false;
  std::vector<Seg> segs_;
  std::vector<int> rowStart_, rowSeg_;
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
      Bnd_Box box;
      BRepBndLib::AddOptimal(f->face, box, false, false);  // the surface, not its control net
      double z0, z1;
      box.Get(f->lo.x, f->lo.y, z0, f->hi.x, f->hi.y, z1);
      const double extent = std::max({f->hi.x - f->lo.x, f->hi.y - f->lo.y, z1 - z0});
      f->cls = std::make_unique<UvClassifier>(f->face, f->u0, f->u1, f->v0, f->v1, extent);
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
