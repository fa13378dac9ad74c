#include "plunge/svg.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <map>
#include <sstream>

#include "detail.hpp"

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

// The plan's picture, layer by layer (planToSvg); y is drawn downwards.
class SvgPicture {
 public:
  SvgPicture(const PlanInput& input, const Plan& plan) : in_(input), plan_(plan) {
    detail::Bounds box;
    box.add(input.boundary);
    lo_ = box.lo;
    hi_ = box.hi;
    size_ = std::max(hi_.x - lo_.x, hi_.y - lo_.y);
    sw_ = size_ / 900.0;
    fs_ = 0.032 * size_;
    for (const ToolCount& t : plan.stats.perTool) colour_.emplace(t.toolId, static_cast<int>(colour_.size()));
    // The stock map's colour scale: yellow at the limit (1 mm when none is set).
    stockScale_ = input.maxFloorStock > 0.0 ? input.maxFloorStock : 1.0;
    for (const Plunge& p : plan.plunges) {
      zLo_ = std::min(zLo_, p.z);
      zHi_ = std::max(zHi_, p.z);
    }
    depthDots_ = !plan.plunges.empty() && zHi_ - zLo_ > 1e-9;
    s_ << std::fixed << std::setprecision(3);
  }

  std::string draw() {
    frame();
    pocket();
    plunges();
    marks();
    legend();
    s_ << "</svg>\n";
    return s_.str();
  }

 private:
  void frame() {
    const double w = hi_.x - lo_.x, h = hi_.y - lo_.y, margin = 0.04 * size_;
    legendH_ = 0.05 * size_ * (5 + plan_.stats.perTool.size() + (plan_.stockMap ? 1 : 0));
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

  // The stock map under the disks, each disk, then each tool's path in execution order.
  void plunges() {
    if (plan_.stockMap) s_ << stockMapSvg(*plan_.stockMap, stockScale_);
    const char* fillOpacity = plan_.stockMap ? "0.06" : "0.22";  // the stock map shows through
    for (const Plunge& p : plan_.plunges) {
      const char* c = kPalette[colour_[p.toolId] % 8];
      s_ << "<circle cx=\"" << p.x << "\" cy=\"" << -p.y << "\" r=\"" << p.diameter / 2 << "\" fill=\"" << c
         << "\" fill-opacity=\"" << fillOpacity << "\" stroke=\"" << c << "\" stroke-width=\"" << sw_ << "\"/>\n";
    }
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
        for (size_t i = from; i <= to; ++i) s_ << mine[i]->x << "," << -mine[i]->y << " ";
        s_ << "\"/>\n";
      }
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
  }

  // What is left uncovered (red), the necks of an automatic tool choice, and
  // over a sculptured floor a dot at each plunge, dark (deep) to light (high).
  void marks() {
    if (!plan_.uncovered.empty())
      s_ << "<path d=\"" << pathData(plan_.uncovered)
         << "\" fill=\"#e00000\" fill-rule=\"nonzero\" stroke=\"none\"/>\n";
    if (plan_.selection)
      for (const Neck& n : plan_.selection->necks)
        s_ << "<line x1=\"" << n.a.x << "\" y1=\"" << -n.a.y << "\" x2=\"" << n.b.x << "\" y2=\"" << -n.b.y
           << "\" stroke=\"#d000d0\" stroke-width=\"" << 3 * sw_ << "\" stroke-dasharray=\"" << 6 * sw_ << "\"/>\n";
    if (depthDots_)
      for (const Plunge& p : plan_.plunges)
        s_ << "<rect x=\"" << p.x - 0.12 * p.diameter << "\" y=\"" << -p.y - 0.12 * p.diameter << "\" width=\""
           << 0.24 * p.diameter << "\" height=\"" << 0.24 * p.diameter << "\" fill=\"" << depthColour(p.z)
           << "\"/>\n";
  }

  std::string depthColour(double z) const {
    const double t = (z - zLo_) / (zHi_ - zLo_);
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

  // Counts, then a line per tool, the stock map's scale and the depth dots' scale.
  void legend() {
    double y = -hi_.y - legendH_ + fs_ * 0.5;
    s_ << std::setprecision(2);
    text(lo_.x, y + fs_,
         std::to_string(plan_.stats.plungeCount) + " plunges, " + number(100.0 * plan_.stats.coverage) +
             " % covered (red: left), travel " + number(plan_.stats.travelLength) + " mm");
    y += 1.4 * fs_;
    for (const ToolCount& t : plan_.stats.perTool) {
      const char* c = kPalette[colour_[t.toolId] % 8];
      s_ << "<circle cx=\"" << lo_.x + fs_ * 0.5 << "\" cy=\"" << y + fs_ * 0.6 << "\" r=\"" << fs_ * 0.45
         << "\" fill=\"" << c << "\" fill-opacity=\"0.5\" stroke=\"" << c << "\"  stroke-width=\"" << sw_ << "\"/>\n";
      text(lo_.x + fs_ * 1.4, y + fs_,
           "T" + std::to_string(t.toolId) + " D" + number(t.diameter) + ": " + std::to_string(t.count) + " plunges");
      y += 1.4 * fs_;
    }
    int starts = 0;
    for (const Plunge& p : plan_.plunges) starts += p.start && !p.startHole;
    text(lo_.x, y + fs_,
         "black: " + std::to_string(starts) + " starts (dots), " + std::to_string(plan_.stats.startHoles) +
             " start holes (rings), " + std::to_string(plan_.stats.leadOuts) + " lead-outs (ticks)");
    y += 1.4 * fs_;
    text(lo_.x, y + fs_, "each tool's path: faint (first plunges) to strong (last)");
    y += 1.4 * fs_;
    if (plan_.stockMap) {
      for (int k = 0; k <= 4; ++k) {
        swatch(lo_.x + k * fs_, y, stockColour(0.5 * k * stockScale_, stockScale_));
        s_ << "\n";
      }
      text(lo_.x + fs_ * 5.4, y + fs_,
           "floor stock, " + std::string(in_.maxFloorStock > 0.0 ? "limit " : "yellow ") + number(stockScale_) +
               ": max " + number(plan_.stats.maxFloorStockLeft) + " mm");
      y += 1.4 * fs_;
    }
    if (depthDots_) {
      swatch(lo_.x, y, depthColour(zLo_));
      swatch(lo_.x + fs_, y, depthColour(zHi_));
      s_ << "\n";
      text(lo_.x + fs_ * 2.4, y + fs_, "stop height " + number(zLo_) + " (dark) to " + number(zHi_) + " mm");
    }
  }

  const PlanInput& in_;
  const Plan& plan_;
  std::ostringstream s_;
  Vec2 lo_, hi_;
  double size_ = 0.0, sw_ = 0.0, fs_ = 0.0, legendH_ = 0.0, stockScale_ = 1.0;
  std::map<int, int> colour_;  // tool id -> palette slot
  double zLo_ = INFINITY, zHi_ = -INFINITY;
  bool depthDots_ = false;
};

}  // namespace

std::string planToSvg(const PlanInput& input, const Plan& plan) { return SvgPicture(input, plan).draw(); }

}  // namespace plunge
