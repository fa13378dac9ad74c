#include "polygon.hpp"

#include <algorithm>
#include <limits>

#include "clip.hpp"
#include "detail.hpp"

namespace plunge {
namespace clip {

Paths toPaths(const Polygons& p) {
  Paths out;
  out.reserve(p.size());
  for (const Loop& L : p) {
    Path q;
    q.reserve(L.size());
    for (const Vec2& v : L) q.push_back(toInt(v));
    out.push_back(std::move(q));
  }
  return out;
}

Polygons toPolygons(const Paths& p) {
  Polygons out;
  out.reserve(p.size());
  for (const Path& q : p) {
    Loop L;
    L.reserve(q.size());
    for (const IntPoint& v : q) L.push_back(toMm(v));
    out.push_back(std::move(L));
  }
  return out;
}

double area(const Paths& p) {
  double a = 0.0;
  for (const Path& q : p) a += ClipperLib::Area(q);
  return a / (poly::kScale * poly::kScale);
}

Path diskPath(const Circle& c, double chordError, bool circumscribed) {
  // The chord error (sagitta) of n vertices is r (1 - cos(pi / n)).
  const double e = std::clamp(chordError / c.r, 1e-9, 0.5);
  const int n = std::max(12, static_cast<int>(std::ceil(kPi / std::acos(1.0 - e))));
  // Circumscribed: vertices beyond the circle so that the edges touch it; one unit
  // more to stay outside after rounding to integers.
  const double r = circumscribed ? c.r / std::cos(kPi / n) + 1.0 / poly::kScale : c.r;
  Path out;
  out.reserve(n);
  for (int i = 0; i < n; ++i) {
    const double a = 2.0 * kPi * i / n;
    out.push_back(toInt({c.c.x + r * std::cos(a), c.c.y + r * std::sin(a)}));
  }
  return out;
}

Paths boolean(const Paths& a, const Paths& b, ClipperLib::ClipType op) {
  ClipperLib::Clipper c;
  c.AddPaths(a, ClipperLib::ptSubject, true);
  if (!b.empty()) c.AddPaths(b, ClipperLib::ptClip, true);
  Paths out;
  c.Execute(op, out, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
  return out;
}

Paths offset(const Paths& p, double deltaMm, double arcTolerance) {
  ClipperLib::ClipperOffset o;
  o.ArcTolerance = arcTolerance * poly::kScale;
  o.AddPaths(p, ClipperLib::jtRound, ClipperLib::etClosedPolygon);
  Paths out;
  o.Execute(out, deltaMm * poly::kScale);
  return out;
}

std::vector<Paths> components(const Paths& p) {
  ClipperLib::Clipper c;
  c.AddPaths(p, ClipperLib::ptSubject, true);
  ClipperLib::PolyTree tree;
  c.Execute(ClipperLib::ctUnion, tree, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
  std::vector<Paths> out;
  // Outer nodes (not holes) in tree order, each with its direct hole children;
  // islands inside holes are outer nodes further down the tree.
  std::vector<const ClipperLib::PolyNode*> stack(tree.Childs.rbegin(), tree.Childs.rend());
  while (!stack.empty()) {
    const ClipperLib::PolyNode* n = stack.back();
    stack.pop_back();
    Paths comp{n->Contour};
    for (const ClipperLib::PolyNode* h : n->Childs) {
      comp.push_back(h->Contour);
      for (auto it = h->Childs.rbegin(); it != h->Childs.rend(); ++it) stack.push_back(*it);
    }
    out.push_back(std::move(comp));
  }
  return out;
}

void bounds(const Paths& p, Vec2& lo, Vec2& hi) {
  detail::Bounds b;
  for (const Path& q : p)
    for (const IntPoint& v : q) b.add(toMm(v));
  lo = b.lo;
  hi = b.hi;
}

}  // namespace clip

namespace poly {

double area(const Polygons& p) { return clip::area(clip::toPaths(p)); }

Polygons offset(const Polygons& p, double delta, double arcTolerance) {
  return clip::toPolygons(clip::offset(clip::toPaths(p), delta, arcTolerance));
}

Polygons unite(const Polygons& a, const Polygons& b) {
  return clip::toPolygons(clip::boolean(clip::toPaths(a), clip::toPaths(b), ClipperLib::ctUnion));
}
Polygons intersect(const Polygons& a, const Polygons& b) {
  return clip::toPolygons(clip::boolean(clip::toPaths(a), clip::toPaths(b), ClipperLib::ctIntersection));
}
Polygons subtract(const Polygons& a, const Polygons& b) {
  return clip::toPolygons(clip::boolean(clip::toPaths(a), clip::toPaths(b), ClipperLib::ctDifference));
}

std::vector<Polygons> components(const Polygons& p) {
  std::vector<Polygons> out;
  for (const clip::Paths& c : clip::components(clip::toPaths(p))) out.push_back(clip::toPolygons(c));
  return out;
}

Loop disk(const Circle& c, double chordError) { return clip::toPolygons({clip::diskPath(c, chordError)})[0]; }

Polygons unionOfDisks(const std::vector<Circle>& disks, double chordError) {
  clip::Paths all;
  all.reserve(disks.size());
  for (const Circle& c : disks) all.push_back(clip::diskPath(c, chordError));
  return clip::toPolygons(clip::boolean(all, {}, ClipperLib::ctUnion));
}

}  // namespace poly
}  // namespace plunge
