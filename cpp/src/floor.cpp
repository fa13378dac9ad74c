#include "plunge/floor.hpp"

#include <BRepAdaptor_Curve.hxx>
#include <BRepAdaptor_Surface.hxx>
#include <BRepBndLib.hxx>
#include <BRepTools.hxx>
#include <BRepTopAdaptor_FClass2d.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
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

// --- flat --------------------------------------------------------------------

class FlatFloor : public FloorSurface {
 public:
  explicit FlatFloor(double z) : z_(z) {}
  double height(Vec2) const override { return z_; }
  std::vector<Vec3> peaks(Vec2 lo, Vec2, double) const override { return {{lo.x, lo.y, z_}}; }
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
  std::vector<Vec3> peaks(Vec2 lo, Vec2 hi, double spacing) const override {
    const int n = samplesFor(std::max(hi.x - lo.x, hi.y - lo.y), spacing, 41, 301);
    OptimizeOptions opt;
    opt.samples = n;
    opt.clusterRadius = 2.5 / n;  // a few grid steps: peaks stay apart
    opt.skipNonFinite = true;
    const OptimizeResult r =
        optimize([&](const double* q) { return height({q[0], q[1]}); }, {{lo.x, hi.x}, {lo.y, hi.y}}, Goal::Maximize, opt);
    std::vector<Vec3> out;
    for (const LocalOptimum& o : r.locals) out.push_back({o.x[0], o.x[1], o.value});
    return out;
  }

 private:
  std::string expr_;
  mutable double x_ = 0, y_ = 0;
  mu::Parser parser_;
};

// --- BREP faces (OpenCASCADE) --------------------------------------------------

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
      f->cls = std::make_unique<BRepTopAdaptor_FClass2d>(f->face, 1e-9);
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

  std::vector<Vec3> peaks(Vec2 lo, Vec2 hi, double spacing) const override {
    std::vector<Vec3> out;
    const Vec2 elo = lo - Vec2{spacing, spacing}, ehi = hi + Vec2{spacing, spacing};
    // Peaks inside faces: local maxima of z(u, v) over each face's parameters.
    for (const auto& f : faces_) {
      if (f->hi.x < elo.x || f->lo.x > ehi.x || f->hi.y < elo.y || f->lo.y > ehi.y) continue;
      OptimizeOptions opt;
      opt.samples = samplesFor(std::max(f->hi.x - f->lo.x, f->hi.y - f->lo.y), spacing, 21, 201);
      opt.clusterRadius = 2.5 / opt.samples;
      opt.skipNonFinite = true;  // outside the trimmed face
      const OptimizeResult r = optimize(
          [&](const double* uv) {
            if (f->cls->Perform(gp_Pnt2d(uv[0], uv[1])) == TopAbs_OUT) return kNaN;
            return f->surf.Value(uv[0], uv[1]).Z();
          },
          {{f->u0, f->u1}, {f->v0, f->v1}}, Goal::Maximize, opt);
      for (const LocalOptimum& o : r.locals) {
        const gp_Pnt p = f->surf.Value(o.x[0], o.x[1]);
        out.push_back({p.X(), p.Y(), p.Z()});
      }
    }
    // Ridges: local maxima of z along every edge; and every vertex.
    TopTools_IndexedMapOfShape edges, vertices;
    TopExp::MapShapes(shape_, TopAbs_EDGE, edges);
    TopExp::MapShapes(shape_, TopAbs_VERTEX, vertices);
    for (int i = 1; i <= edges.Extent(); ++i) {
      const TopoDS_Edge& e = TopoDS::Edge(edges(i));
      if (BRep_Tool::Degenerated(e) || !BRep_Tool::IsGeometric(e)) continue;
      BRepAdaptor_Curve c(e);
      const double t0 = c.FirstParameter(), t1 = c.LastParameter();
      if (!(t1 > t0)) continue;
      OptimizeOptions opt;
      opt.samples = samplesFor(c.Value(t0).Distance(c.Value(t1)) * 2, spacing, 21, 401);
      const OptimizeResult r = optimize([&](const double* t) { return c.Value(t[0]).Z(); }, {{t0, t1}},
                                        Goal::Maximize, opt);
      for (const LocalOptimum& o : r.locals) {
        const gp_Pnt p = c.Value(o.x[0]);
        out.push_back({p.X(), p.Y(), p.Z()});
      }
    }
    for (int i = 1; i <= vertices.Extent(); ++i) {
      const gp_Pnt p = BRep_Tool::Pnt(TopoDS::Vertex(vertices(i)));
      out.push_back({p.X(), p.Y(), p.Z()});
    }
    std::vector<Vec3> kept;
    for (const Vec3& p : out)
      if (inside(p, elo, ehi)) kept.push_back(p);
    return kept;
  }

 private:
  static constexpr int kGrid = 24;
  struct Sample {
    double u, v, x, y;
  };
  struct Face {
    TopoDS_Face face;
    BRepAdaptor_Surface surf;
    std::unique_ptr<BRepTopAdaptor_FClass2d> cls;
    double u0 = 0, u1 = 0, v0 = 0, v1 = 0;
    Vec2 lo, hi;
    std::vector<Sample> samples;
    mutable double lastU = 0, lastV = 0;  // Newton's warm start: neighbouring queries are close
    mutable bool hasLast = false;
  };

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
      for (const Sample& s : f.samples)
        if (std::hypot(s.x - p.x, s.y - p.y) < std::hypot(best->x - p.x, best->y - p.y)) best = &s;
      u = best->u;
      v = best->v;
      ok = solve(f, p, u, v);
    }
    if (!ok || f.cls->Perform(gp_Pnt2d(u, v)) == TopAbs_OUT) return false;
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
