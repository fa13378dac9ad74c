#include "plunge/svg.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <map>
#include <sstream>
#include <vector>

#include "detail.hpp"
#include "plunge/summary.hpp"

namespace plunge {

namespace {

const char* kPalette[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#9467bd", "#8c564b", "#e377c2", "#17becf", "#bcbd22"};
// Darker shades of the same hues for the tool paths drawn over the disks.
const char* kPathPalette[] = {"#0b3c61", "#a34f00", "#13561a", "#4b2a6e", "#4a2c25", "#8c2a73", "#0b6570", "#66660f"};

std::string pathData(const Polygons& loops) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(3);
  for (const Loop& L : loops) {
    for (size_t i = 0; i < L.size(); ++i) s << (i ? " L" : "M") << L[i].x << " " << -L[i].y;
    s << " Z ";
  }
  return s.str();
}

// Colour of a floor stock: green (none) to yellow (the limit), then to red (twice
// the limit and more); quantized in 16 steps so that equal runs merge.
std::string stockColour(double stock, double limit) {
  const double t = std::clamp(stock / std::max(limit, 1e-9), 0.0, 2.0);
  const double q = std::round(t * 8) / 8;
  int r, g, b;
  if (q <= 1) {
    r = static_cast<int>(40 + 215 * q);
    g = static_cast<int>(170 + 50 * q);
    b = 60;
  } else {
    r = 230;
    g = static_cast<int>(220 * (2 - q));
    b = 40;
  }
  std::ostringstream c;
  c << "rgb(" << r << "," << g << "," << b << ")";
  return c.str();
}

// The floor stock left as coloured cells, runs of one colour in a row merged.
std::string stockMapSvg(const StockMap& m, double limit) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(3) << "<g stroke=\"none\">\n";
  for (size_t j = 0; j < m.ny; ++j) {
    size_t i = 0;
    while (i < m.nx) {
      const float v = m.stock[j * m.nx + i];
      if (std::isnan(v)) {
        ++i;
        continue;
      }
      const std::string c = stockColour(v, limit);
      size_t k = i + 1;
      while (k < m.nx && !std::isnan(m.stock[j * m.nx + k]) && stockColour(m.stock[j * m.nx + k], limit) == c) ++k;
      const double x = m.origin.x + (i - 0.5) * m.spacing, y = m.origin.y + (j + 0.5) * m.spacing;
      s << "<rect x=\"" << x << "\" y=\"" << -y << "\" width=\"" << (k - i) * m.spacing << "\" height=\"" << m.spacing
        << "\" fill=\"" << c << "\"/>\n";
      i = k;
    }
  }
  s << "</g>\n";
  return s.str();
}

// Even-odd containment in a pocket's loops.
bool insideLoops(const Polygons& loops, Vec2 p) {
  bool in = false;
  for (const Loop& L : loops)
    for (size_t i = 0, j = L.size() - 1; i < L.size(); j = i++)
      if ((L[j].y > p.y) != (L[i].y > p.y) && L[j].x + (p.y - L[j].y) / (L[i].y - L[j].y) * (L[i].x - L[j].x) > p.x)
        in = !in;
  return in;
}

// One of the plan's pictures (planToSvg), layer by layer; y is drawn downwards.
// Each view answers one question, so nothing drawn for one hides another.
class SvgPicture {
 public:
  SvgPicture(const PlanInput& input, const Plan& plan, SvgView view) : in_(input), plan_(plan), view_(view) {
    detail::Bounds box;
    box.add(input.boundary);
    lo_ = box.lo;
    hi_ = box.hi;
    size_ = std::max(hi_.x - lo_.x, hi_.y - lo_.y);
    sw_ = size_ / 900.0;
    fs_ = 0.032 * size_;
    for (const ToolCount& t : plan.stats.perTool) colour_.emplace(t.toolId, static_cast<int>(colour_.size()));
    // The stock map's colour scale: yellow at the limit (1 mm when none is set).
    stockScale_ = input.floor.maxFloorStock > 0.0 ? input.floor.maxFloorStock : 1.0;
    for (const Plunge& p : plan.plunges) {
      zLo_ = std::min(zLo_, p.z);
      zHi_ = std::max(zHi_, p.z);
    }
    s_ << std::fixed << std::setprecision(3);
  }

  std::string draw() {
    frame();
    pocket();
    if (view_ == SvgView::Plan && in_.material) material(*in_.material);
    if (view_ == SvgView::Plan) tours();
    if (view_ == SvgView::Stock) stockLeft();
    if (view_ == SvgView::Heights) heights();
    legend();
    s_ << "</svg>\n";
    return s_.str();
  }

 private:
  size_t legendLines() const {
    switch (view_) {
      case SvgView::Plan: return 4 + plan_.stats.perTool.size() + (in_.material ? 1 : 0);
      case SvgView::Stock: return 3 + std::min<size_t>(plan_.broken.size(), kMaxBrokenLines);
      case SvgView::Heights:
        return 3 + (std::any_of(plan_.plunges.begin(), plan_.plunges.end(), [](const Plunge& p) { return p.holderLimited; }) ? 1 : 0);
    }
    return 3;
  }

  void frame() {
    const double w = hi_.x - lo_.x, h = hi_.y - lo_.y, margin = 0.04 * size_;
    legendH_ = 1.4 * fs_ * (legendLines() + 0.8);
    const double vx = lo_.x - margin, vy = -hi_.y - margin - legendH_, vw = w + 2 * margin,
                 vh = h + 2 * margin + legendH_;
    const double pxW = 1200.0, pxH = pxW * vh / vw;
    s_ << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << pxW << "\" height=\"" << pxH << "\" viewBox=\""
       << vx << " " << vy << " " << vw << " " << vh << "\">\n";
    s_ << "<rect x=\"" << vx << "\" y=\"" << vy << "\" width=\"" << vw << "\" height=\"" << vh
       << "\" fill=\"white\"/>\n";
  }

  // The pocket, its islands and the accessible region's outline (dashed).
  void pocket() {
    Polygons all{in_.boundary};
    for (const Loop& L : in_.islands) all.push_back(L);
    s_ << "<path d=\"" << pathData(all) << "\" fill=\"#e8e8e8\" fill-rule=\"evenodd\" stroke=\"#222\" stroke-width=\""
       << 2 * sw_ << "\"/>\n";
    for (const Loop& L : in_.islands)
      s_ << "<path d=\"" << pathData({L}) << "\" fill=\"#9a9a9a\" stroke=\"#222\" stroke-width=\"" << 2 * sw_
         << "\"/>\n";
    s_ << "<path d=\"" << pathData(plan_.accessible) << "\" fill=\"none\" stroke=\"#555\" stroke-dasharray=\""
       << 4 * sw_ << "\" stroke-width=\"" << sw_ << "\"/>\n";
  }

  // Rest plunging: the material the plan starts from, inside the pocket, from
  // light (cut down to the deepest plunge) to dark (the stock top), in blocks
  // of at most about 1/150 of the picture (each its highest).
  static std::string materialColour(double f) {
    f = std::clamp(f, 0.0, 1.0);
    std::ostringstream c;
    c << "rgb(" << static_cast<int>(250 - 90 * f) << "," << static_cast<int>(250 - 105 * f) << ","
      << static_cast<int>(250 - 130 * f) << ")";
    return c.str();
  }
  void material(const MaterialGrid& g) {
    const size_t step = std::max<size_t>(1, static_cast<size_t>(std::ceil(size_ / 150.0 / g.spacing)));
    const double zTop = in_.topZ, zLow = std::min(zLo_, zTop - 1e-3);
    // Blocks whose centre is in the pocket (Qt's SVG renderer, FreeCAD's
    // picture window, has no clip paths).
    Polygons all{in_.boundary};
    for (const Loop& L : in_.islands) all.push_back(L);
    s_ << "<g stroke=\"none\">\n";
    for (size_t j = 0; j < g.ny; j += step) {
      std::string last;
      double runX = 0.0, runW = 0.0;
      auto flush = [&] {
        if (!last.empty())
          // A little taller than the row: no hairline between rows when drawn smooth.
          s_ << "<rect x=\"" << runX << "\" y=\"" << -(g.origin.y + (j + step) * g.spacing) << "\" width=\"" << runW
             << "\" height=\"" << 1.05 * step * g.spacing << "\" fill=\"" << last << "\"/>\n";
        last.clear();
      };
      for (size_t i = 0; i < g.nx; i += step) {
        double top = -std::numeric_limits<double>::infinity();
        for (size_t b = j; b < std::min(g.ny, j + step); ++b)
          for (size_t a = i; a < std::min(g.nx, i + step); ++a) top = std::max(top, std::min(zTop, g.top[b * g.nx + a]));
        const Vec2 centre{g.origin.x + (i + 0.5 * step) * g.spacing, g.origin.y + (j + 0.5 * step) * g.spacing};
        const std::string c = insideLoops(all, centre) ? materialColour((top - zLow) / (zTop - zLow)) : std::string();
        if (c != last || c.empty()) {
          flush();
          last = c;
          runX = g.origin.x + i * g.spacing;
          runW = 0.0;
        }
        runW += step * g.spacing;
      }
      flush();
    }
    s_ << "</g>\n";
  }

  void disk(const Plunge& p, const std::string& fill, double opacity, const std::string& stroke) {
    s_ << "<circle cx=\"" << p.x << "\" cy=\"" << -p.y << "\" r=\"" << p.diameter / 2 << "\" fill=\"" << fill
       << "\" fill-opacity=\"" << opacity << "\" stroke=\"" << stroke << "\" stroke-width=\"" << sw_ << "\"/>\n";
  }

  // The plan: each disk, each tool's path in execution order, its starts and
  // lead-outs, and the necks of an automatic tool choice.
  void tours() {
    for (const Plunge& p : plan_.plunges) disk(p, kPalette[colour_[p.toolId] % 8], 0.22, kPalette[colour_[p.toolId] % 8]);
    // Each tool's path from faint (its first plunges) to strong (its last):
    // the order a limited tool grows its cut in, at a glance.
    for (const ToolCount& t : plan_.stats.perTool) {
      std::vector<const Plunge*> mine;
      for (const Plunge& p : plan_.plunges)
        if (p.toolId == t.toolId) mine.push_back(&p);
      const int parts = 8;
      for (int k = 0; k < parts && mine.size() > 1; ++k) {
        const size_t from = (mine.size() - 1) * k / parts, to = (mine.size() - 1) * (k + 1) / parts;
        if (to <= from) continue;
        s_ << "<polyline fill=\"none\" stroke=\"" << kPathPalette[colour_[t.toolId] % 8] << "\" stroke-width=\""
           << 1.5 * sw_ << "\" stroke-opacity=\"" << 0.25 + 0.75 * (k + 1) / parts << "\" points=\"";
        for (size_t i = from; i <= to; ++i) {
          s_ << mine[i]->x << "," << -mine[i]->y << " ";
          if (i < to)  // the way around the wall band to the next
            for (Vec2 v : mine[i]->via) s_ << v.x << "," << -v.y << " ";
        }
        s_ << "\"/>\n";
      }
      if (!mine.empty())  // where the tool starts: a ring round its first plunge
        s_ << "<circle cx=\"" << mine.front()->x << "\" cy=\"" << -mine.front()->y << "\" r=\""
           << 0.3 * mine.front()->diameter << "\" fill=\"none\" stroke=\"" << kPathPalette[colour_[t.toolId] % 8]
           << "\" stroke-width=\"" << 3 * sw_ << "\"/>\n";
    }
    // Start holes (black rings), starts into solid or onto a hole (black dots)
    // and lead-outs (black ticks from the plunge's centre).
    for (const Plunge& p : plan_.plunges) {
      if (p.startHole) {
        s_ << "<circle cx=\"" << p.x << "\" cy=\"" << -p.y << "\" r=\"" << p.diameter / 2
           << "\" fill=\"none\" stroke=\"#000\" stroke-width=\"" << 3 * sw_ << "\"/>\n";
      } else if (p.start) {
        s_ << "<circle cx=\"" << p.x << "\" cy=\"" << -p.y << "\" r=\"" << 0.15 * p.diameter << "\" fill=\"#000\"/>\n";
      }
      if (p.leadOut)
        s_ << "<line x1=\"" << p.x << "\" y1=\"" << -p.y << "\" x2=\"" << p.leadOut->x << "\" y2=\"" << -p.leadOut->y
           << "\" stroke=\"#000\" stroke-width=\"" << 2 * sw_ << "\"/>\n";
    }
    if (plan_.selection)
      for (const Neck& n : plan_.selection->necks)
        s_ << "<line x1=\"" << n.a.x << "\" y1=\"" << -n.a.y << "\" x2=\"" << n.b.x << "\" y2=\"" << -n.b.y
           << "\" stroke=\"#d000d0\" stroke-width=\"" << 3 * sw_ << "\" stroke-dasharray=\"" << 6 * sw_ << "\"/>\n";
  }

  // The stock left: the floor stock map (sculptured floors), what the disks
  // leave on the walls (red), the disks' outlines for orientation, and each
  // broken limit numbered where its worst is.
  void stockLeft() {
    if (plan_.stockMap)
      s_ << stockMapSvg(*plan_.stockMap, stockScale_);
    else  // a flat floor: cut to its allowance wherever the plunges reach
      s_ << "<path d=\"" << pathData(plan_.accessible) << "\" fill=\"" << stockColour(0.0, 1.0)
         << "\" fill-opacity=\"0.5\" fill-rule=\"nonzero\" stroke=\"none\"/>\n";
    for (const Plunge& p : plan_.plunges)  // faint: where the plunges are, under what they leave
      s_ << "<circle cx=\"" << p.x << "\" cy=\"" << -p.y << "\" r=\"" << p.diameter / 2
         << "\" fill=\"none\" stroke=\"#444\" stroke-opacity=\"0.3\" stroke-width=\"" << 0.6 * sw_ << "\"/>\n";
    if (!plan_.uncovered.empty())
      s_ << "<path d=\"" << pathData(plan_.uncovered)
         << "\" fill=\"#e00000\" fill-rule=\"nonzero\" stroke=\"none\"/>\n";
    for (size_t k = 0; k < plan_.broken.size() && k < kMaxBrokenLines; ++k) {
      const Vec2 at = plan_.broken[k].at;
      s_ << "<circle cx=\"" << at.x << "\" cy=\"" << -at.y << "\" r=\"" << 0.6 * fs_
         << "\" fill=\"white\" fill-opacity=\"0.8\" stroke=\"#d000d0\" stroke-width=\"" << 3 * sw_ << "\"/>\n";
      s_ << "<text x=\"" << at.x << "\" y=\"" << -at.y + 0.35 * fs_
         << "\" text-anchor=\"middle\" font-family=\"sans-serif\" font-weight=\"bold\" fill=\"#d000d0\" font-size=\""
         << fs_ << "\">" << k + 1 << "</text>\n";
    }
  }

  // Where each plunge stops: its disk filled dark (deep) to light (high).
  void heights() {
    std::vector<const Plunge*> order;
    for (const Plunge& p : plan_.plunges) order.push_back(&p);
    // Deepest last, on top: where the tool goes lowest stays visible.
    std::stable_sort(order.begin(), order.end(), [](const Plunge* a, const Plunge* b) { return a->z > b->z; });
    for (const Plunge* p : order) disk(*p, depthColour(p->z), 0.85, "#333");
    // The plunges a holder or shank stopped above their depth: a red ring each.
    for (const Plunge& p : plan_.plunges)
      if (p.holderLimited)
        s_ << "<circle cx=\"" << p.x << "\" cy=\"" << -p.y << "\" r=\"" << 0.35 * p.diameter
           << "\" fill=\"none\" stroke=\"" << kHolderRing << "\" stroke-width=\"" << 2 * sw_ << "\"/>\n";
  }

  std::string depthColour(double z) const {
    const double t = zHi_ - zLo_ > 1e-9 ? (z - zLo_) / (zHi_ - zLo_) : 0.0;
    std::ostringstream c;
    c << "rgb(" << static_cast<int>(30 + 225 * t) << "," << static_cast<int>(20 + 200 * t) << ","
      << static_cast<int>(90 + 40 * (1 - t)) << ")";
    return c.str();
  }

  void text(double x, double y, const std::string& what) {
    s_ << "<text x=\"" << x << "\" y=\"" << y << "\" font-family=\"sans-serif\" font-size=\"" << fs_ << "\">" << what
       << "</text>\n";
  }

  std::string number(double v) const {
    std::ostringstream t;
    t << std::fixed << std::setprecision(2) << v;
    return t.str();
  }

  void swatch(double x, double y, const std::string& fill) {
    s_ << "<rect x=\"" << x << "\" y=\"" << y + 0.2 * fs_ << "\" width=\"" << fs_ << "\" height=\"" << 0.8 * fs_
       << "\" fill=\"" << fill << "\"/>";
  }

  void legend() {
    y_ = -hi_.y - legendH_ + fs_ * 0.5;
    s_ << std::setprecision(2);
    if (view_ == SvgView::Plan) planLegend();
    if (view_ == SvgView::Stock) stockLegend();
    if (view_ == SvgView::Heights) heightsLegend();
  }
  void line(double indent, const std::string& what) {
    text(lo_.x + indent, y_ + fs_, what);
    y_ += 1.4 * fs_;
  }

  void planLegend() {
    line(0, "The plan: " + std::to_string(plan_.stats.plungeCount) + " plunges, travel " +
                number(plan_.stats.travelLength) + " mm, about " + number(plan_.stats.estimatedMinutes) + " min");
    line(0, floorKindSaid(plan_.stats.floorKind));  // a line of its own: on one with the figures it ran off the picture
    for (const ToolCount& t : plan_.stats.perTool) {
      const char* c = kPalette[colour_[t.toolId] % 8];
      s_ << "<circle cx=\"" << lo_.x + fs_ * 0.5 << "\" cy=\"" << y_ + fs_ * 0.6 << "\" r=\"" << fs_ * 0.45
         << "\" fill=\"" << c << "\" fill-opacity=\"0.5\" stroke=\"" << c << "\"  stroke-width=\"" << sw_ << "\"/>\n";
      line(fs_ * 1.4,
           "T" + std::to_string(t.toolId) + " D" + number(t.diameter) + ": " + std::to_string(t.count) + " plunges");
    }
    int starts = 0;
    for (const Plunge& p : plan_.plunges) starts += p.start && !p.startHole;
    line(0, "its path: ring at its first plunge, faint (first) to strong (last)");
    if (in_.material) {
      for (int k = 0; k <= 4; ++k) swatch(lo_.x + k * fs_, y_, materialColour(0.25 * k));
      line(fs_ * 5.4, "material before it: light (cut) to dark (stock top)");
    }
    line(0, "black: " + std::to_string(starts) + " starts (dots), " + std::to_string(plan_.stats.startHoles) +
                " start holes (rings), " + std::to_string(plan_.stats.leadOuts) + " lead-outs (ticks)");
  }

  void stockLegend() {
    line(0, "Stock left: walls up to " + number(plan_.stats.maxWallStockLeft) + " mm (red), " +
                number(100.0 * plan_.stats.coreCoverage) + " % of the core cut");
    if (plan_.stockMap) {
      for (int k = 0; k <= 4; ++k) {
        swatch(lo_.x + k * fs_, y_, stockColour(0.5 * k * stockScale_, stockScale_));
        s_ << "\n";
      }
      line(fs_ * 5.4, "floor stock, " + std::string(in_.floor.maxFloorStock > 0.0 ? "limit " : "yellow ") +
                          number(stockScale_) + ": max " + number(plan_.stats.maxFloorStockLeft) + " mm");
    } else {
      swatch(lo_.x, y_, stockColour(0.0, 1.0));
      line(fs_ * 1.4, "floor: flat, cut to its allowance");
    }
    if (plan_.broken.empty()) line(0, "every limit kept");
    for (size_t k = 0; k < plan_.broken.size() && k < kMaxBrokenLines; ++k) {
      const BrokenLimit& b = plan_.broken[k];
      line(0, std::to_string(k + 1) + ": " + b.limit + " broken " + std::to_string(b.count) + " x, worst " +
                  number(b.worst) + " against " + number(b.asked));
    }
  }

  void heightsLegend() {
    line(0, "Stop heights: " + std::to_string(plan_.stats.plungeCount) + " plunges");
    swatch(lo_.x, y_, depthColour(zLo_));
    swatch(lo_.x + fs_, y_, depthColour(zHi_));
    s_ << "\n";
    line(fs_ * 2.4, number(zLo_) + " mm (dark) to " + number(zHi_) + " mm (light)");
    const long held = std::count_if(plan_.plunges.begin(), plan_.plunges.end(), [](const Plunge& p) { return p.holderLimited; });
    if (held > 0) line(0, std::to_string(held) + " plunges stopped above their depth by the holder (red rings)");
  }

  static constexpr size_t kMaxBrokenLines = 6;
  static constexpr const char* kHolderRing = "#e00000";
  const PlanInput& in_;
  const Plan& plan_;
  SvgView view_;
  std::ostringstream s_;
  Vec2 lo_, hi_;
  double size_ = 0.0, sw_ = 0.0, fs_ = 0.0, legendH_ = 0.0, stockScale_ = 1.0, y_ = 0.0;
  std::map<int, int> colour_;  // tool id -> palette slot
  double zLo_ = INFINITY, zHi_ = -INFINITY;
};

}  // namespace

std::vector<SvgView> svgViews(const PlanInput& input, const Plan& plan) {
  // Stop heights differ over a sculptured floor, and where a holder stopped plunges.
  const bool held = std::any_of(plan.plunges.begin(), plan.plunges.end(), [](const Plunge& p) { return p.holderLimited; });
  if (input.floor.surface.kind == Floor::Kind::Flat && !held) return {SvgView::Plan, SvgView::Stock};
  return {SvgView::Plan, SvgView::Stock, SvgView::Heights};
}

const char* svgViewName(SvgView view) {
  switch (view) {
    case SvgView::Plan: return "plan";
    case SvgView::Stock: return "stock";
    case SvgView::Heights: return "heights";
  }
  return "plan";
}

std::string planToSvg(const PlanInput& input, const Plan& plan, SvgView view) {
  return SvgPicture(input, plan, view).draw();
}

}  // namespace plunge
