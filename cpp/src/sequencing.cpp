#include "plunge/sequencing.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <numeric>
#include <random>

#include "detail.hpp"
#include "plunge/error.hpp"

namespace plunge {

using namespace detail;

namespace {

// Gains below this are rounding, not shorter tours (relative to the largest
// length a gain is computed from: an open path's dummy constant is ~1e6 mm on
// big jobs, where one unit in the last place is 1e-10 mm, and a threshold below
// that lets two moves undo each other forever).
constexpr double kRelEps = 1e-12;
constexpr int kNeighbours = 10;
// Simulated annealing makes 20 n moves per stage (the thesis) up to this many
// points. A move reverses up to n / 2 positions, so beyond it the moves per
// stage shrink by (kAnnealFull / n)^2, which bounds the work (about as much as
// kAnnealFull points take, 1-2 s), and a local search polishes the tour.
constexpr int kAnnealFull = 1500;
// Moves between calls of TourOptions::poll.
constexpr long kPollEvery = 256;

// The tour as an array with positions; an open path is a closed tour through an
// extra "dummy" node whose edges cost nothing (or, when the path must begin at a
// given node, nothing to that node and a large constant to all others, which
// every tour pays exactly once).
class Tsp {
 public:
  Tsp(const std::vector<Vec2>& pts, bool open, int startNode, std::function<void()> poll)
      : pts_(pts), n_(static_cast<int>(pts.size())), poll_(std::move(poll)) {
    m_ = open ? n_ + 1 : n_;
    dummy_ = open ? n_ : -1;
    start_ = startNode;
    Bounds b;
    b.add(pts);
    if (open && startNode >= 0) big_ = (norm(b.hi - b.lo) + 1.0) * (n_ + 1);
    eps_ = 1e-10 + kRelEps * (std::max(big_, norm(b.hi - b.lo)) + norm(b.hi) + norm(b.lo));
    buildNeighbours();
  }

  void poll() const {
    if (poll_) poll_();
  }

  double d(int a, int b) const {
    if (a == dummy_ || b == dummy_) {
      const int o = a == dummy_ ? b : a;
      return start_ < 0 || o == start_ ? 0.0 : big_;
    }
    return dist(pts_[a], pts_[b]);
  }

  int succ(int a) const { return t_[(pos_[a] + 1) % m_]; }
  int pred(int a) const { return t_[(pos_[a] + m_ - 1) % m_]; }

  double length() const {
    double len = 0;
    for (int i = 0; i < m_; ++i) len += d(t_[i], t_[(i + 1) % m_]);
    return len;
  }

  void setOrder(const std::vector<int>& order) {
    t_ = order;
    pos_.assign(m_, 0);
    for (int i = 0; i < m_; ++i) pos_[t_[i]] = i;
  }
  const std::vector<int>& order() const { return t_; }

  // Construction: greedy edge fragments joined end to end, nearest first, then
  // (an open path) opened at the dummy node.
  void greedyEdge() {
    std::vector<int> order = joinFragments(greedyFragments());
    if (dummy_ >= 0) order.insert(order.begin() + openingCut(order) + 1, dummy_);
    setOrder(order);
  }

  // Greedy edge: shortest candidate edges first, keeping degrees <= 2 and no
  // early cycle. Returns each node's fragment neighbours.
  std::vector<std::vector<int>> greedyFragments() const {
    struct E {
      double len;
      int a, b;
    };
    std::vector<E> edges;
    for (int a = 0; a < n_; ++a)
      for (int b : nb_[a])
        if (b != dummy_ && a < b) edges.push_back({d(a, b), a, b});
    std::sort(edges.begin(), edges.end(), [](const E& x, const E& y) {
      return x.len < y.len || (x.len == y.len && (x.a < y.a || (x.a == y.a && x.b < y.b)));
    });
    std::vector<std::vector<int>> adj(n_);
    std::vector<int> root(n_);
    std::iota(root.begin(), root.end(), 0);
    auto find = [&](int x) {
      while (root[x] != x) x = root[x] = root[root[x]];
      return x;
    };
    int added = 0;
    for (const E& e : edges) {
      if (added == n_ - 1) break;
      if (adj[e.a].size() >= 2 || adj[e.b].size() >= 2 || find(e.a) == find(e.b)) continue;
      adj[e.a].push_back(e.b);
      adj[e.b].push_back(e.a);
      root[find(e.a)] = find(e.b);
      ++added;
    }
    return adj;
  }

  // Walk the fragments, always continuing to the nearest free fragment end.
  std::vector<int> joinFragments(const std::vector<std::vector<int>>& adj) const {
    std::vector<char> used(n_, 0);
    std::vector<int> order;
    auto walk = [&](int from) {
      int prev = -1, cur = from;
      while (cur >= 0 && !used[cur]) {
        used[cur] = 1;
        order.push_back(cur);
        int next = -1;
        for (int x : adj[cur])
          if (x != prev && !used[x]) next = x;
        prev = cur;
        cur = next;
      }
    };
    std::vector<int> ends;
    for (int i = 0; i < n_; ++i)
      if (adj[i].size() < 2) ends.push_back(i);
    walk(ends.empty() ? 0 : ends[0]);
    while (static_cast<int>(order.size()) < n_) {
      const int last = order.back();
      int best = -1;
      for (int e : ends)
        if (!used[e] && (best < 0 || d(last, e) < d(last, best))) best = e;
      if (best < 0)
        for (int i = 0; i < n_ && best < 0; ++i)
          if (!used[i]) best = i;
      walk(best);
    }
    return order;
  }

  // Where an open path starts: after its longest edge, or next to the start node.
  int openingCut(const std::vector<int>& order) const {
    int cut = 0;
    if (start_ >= 0) {
      const int at = static_cast<int>(std::find(order.begin(), order.end(), start_) - order.begin());
      const int before = (at + n_ - 1) % n_, after = (at + 1) % n_;
      return d(order[before], start_) > d(start_, order[after]) ? before : at;
    }
    for (int i = 0; i < n_; ++i)
      if (d(order[i], order[(i + 1) % n_]) > d(order[cut], order[(cut + 1) % n_])) cut = i;
    return cut;
  }

  // 2-opt and Or-opt to a local optimum, starting from the queued nodes.
  // Returns the length gained.
  double localSearch() {
    double gained = 0;
    for (long pops = 0; !queue_.empty(); ++pops) {
      if (pops % kPollEvery == 0) poll();
      const int a = queue_.front();
      queue_.pop_front();
      queued_[a] = 0;
      double g = twoOpt(a);
      if (g <= 0) g = orOpt(a);
      if (g > 0) gained += g;
    }
    return gained;
  }

  void queueAll() {
    for (int i = 0; i < m_; ++i) push(t_[i]);
  }

  // Iterated local search: local double-bridge kicks, kept when shorter.
  void iterate(long long kicks, std::mt19937_64& rng) {
    if (m_ < 8) return;
    double len = length();
    std::vector<int> bestT = t_, bestPos = pos_;
    double bestLen = len;
    const int maxSeg = std::max(1, std::min(50, (m_ - 2) / 3));
    for (long long k = 0; k < kicks; ++k) {
      if (k % 16 == 0) poll();
      len -= kick(rng, maxSeg);
      len -= localSearch();
      if (len < bestLen - 1e-9) {
        bestLen = len;
        bestT = t_;
        bestPos = pos_;
      } else {
        t_ = bestT;
        pos_ = bestPos;
        len = bestLen;
      }
    }
  }

  // The thesis's simulated annealing (section 4.3.1): random 2-opt moves, a
  // worse tour accepted with probability exp(-dE / T) (eq. 4.81), geometric
  // cooling, stop when cold or when the best tour stops improving. Returns
  // whether it made fewer moves than the thesis (above kAnnealFull points).
  bool anneal(std::mt19937_64& rng) {
    if (m_ < 4) return false;
    std::uniform_real_distribution<double> u(0.0, 1.0);
    auto delta = [&](int i, int j) {  // reverse positions i+1 .. j
      const int a = t_[i], b = t_[(i + 1) % m_], c = t_[j], e = t_[(j + 1) % m_];
      return d(a, c) + d(b, e) - d(a, b) - d(c, e);
    };
    auto randomMove = [&](int& i, int& j) {
      const int a = static_cast<int>(rng() % m_);
      const std::vector<int>& nb = nb_[a];
      const int c = nb.empty() || rng() % 4 == 0 ? static_cast<int>(rng() % m_) : nb[rng() % nb.size()];
      i = pos_[a];
      j = pos_[c];
      if (i > j) std::swap(i, j);
      return j - i >= 2 && !(i == 0 && j == m_ - 1);
    };
    double sum = 0;
    int count = 0;
    for (int k = 0; k < 1000; ++k) {
      int i, j;
      if (!randomMove(i, j)) continue;
      const double dE = delta(i, j);
      if (dE > 0 && (big_ == 0 || dE < 0.5 * big_)) {  // not the open path's constant
        sum += dE;
        ++count;
      }
    }
    if (count == 0) return false;
    const double t0 = (sum / count) / std::log(2.0);  // worse moves accepted half the time at first
    double temperature = t0, len = length(), bestLen = len;
    std::vector<int> bestT = t_;
    // Stop when cold, or frozen: three stages in a row accepting almost nothing.
    int frozen = 0;
    const double shrink = std::min(1.0, static_cast<double>(kAnnealFull) / m_);
    const long long perStage = std::max<long long>(100, std::llround(20.0 * m_ * shrink * shrink));
    while (temperature > 1e-5 * t0 && frozen < 3) {
      long long accepted = 0;
      for (long long k = 0; k < perStage; ++k) {
        if (k % kPollEvery == 0) poll();
        int i, j;
        if (!randomMove(i, j)) continue;
        const double dE = delta(i, j);
        if (dE < 0 || u(rng) < std::exp(-dE / temperature)) {
          reversePositions(i + 1, j);
          len += dE;
          ++accepted;
          if (len < bestLen - 1e-9) {
            bestLen = len;
            bestT = t_;
          }
        }
      }
      frozen = accepted * 1000 < perStage ? frozen + 1 : 0;
      temperature *= 0.95;  // geometric cooling
    }
    setOrder(bestT);
    return shrink < 1.0;
  }

  int dummy() const { return dummy_; }

 private:
  void buildNeighbours() {
    std::vector<PointValue> vals;
    for (int i = 0; i < n_; ++i) vals.emplace_back(toBPoint(pts_[i]), i);
    RStarTree<PointValue> index(vals.begin(), vals.end());
    nb_.assign(m_, {});
    const int k = std::min(kNeighbours, n_ - 1);
    for (int i = 0; i < n_; ++i) {
      std::vector<PointValue> hits;
      index.query(bgi::nearest(toBPoint(pts_[i]), k + 1), std::back_inserter(hits));
      std::vector<int>& nb = nb_[i];
      for (const PointValue& h : hits)
        if (h.second != i) nb.push_back(h.second);
      std::sort(nb.begin(), nb.end(), [&](int a, int b) {
        const double da = d(i, a), db = d(i, b);
        return da < db || (da == db && a < b);
      });
      if (nb.size() > static_cast<size_t>(k)) nb.resize(k);
      if (dummy_ >= 0 && (start_ < 0 || i == start_)) nb.insert(nb.begin(), dummy_);
    }
    queued_.assign(m_, 0);
  }

  void push(int a) {
    if (!queued_[a]) {
      queued_[a] = 1;
      queue_.push_back(a);
    }
  }

  // Reverses the tour between positions i and j (inclusive, going forward),
  // or the complementary part, whichever is shorter: the same cyclic tour.
  void reversePositions(int i, int j) {
    int len = (j - i + m_) % m_ + 1;
    if (2 * len > m_) {
      const int ni = (j + 1) % m_, nj = (i + m_ - 1) % m_;
      i = ni;
      j = nj;
      len = m_ - len;
    }
    for (int k = 0; k < len / 2; ++k) {
      const int p = (i + k) % m_, q = (j - k + m_) % m_;
      std::swap(t_[p], t_[q]);
      pos_[t_[p]] = p;
      pos_[t_[q]] = q;
    }
  }

  // Removes edges {a,b} and {c,e}, adds {a,c} and {b,e}; the two edges must
  // have the same direction along the tour.
  void apply2opt(int a, int b, int c, int e) {
    if (succ(a) == b)
      reversePositions(pos_[b], pos_[c]);
    else
      reversePositions(pos_[a], pos_[e]);
    for (int x : {a, b, c, e}) push(x);
  }

  double twoOpt(int a) {
    for (int dir = 0; dir < 2; ++dir) {
      const int b = dir == 0 ? succ(a) : pred(a);
      const double dab = d(a, b);
      for (int c : nb_[a]) {
        const double dac = d(a, c);
        if (dac >= dab) break;
        const int e = dir == 0 ? succ(c) : pred(c);
        if (c == b || e == a) continue;
        const double gain = dab + d(c, e) - dac - d(b, e);
        if (gain > eps_) {
          apply2opt(a, b, c, e);
          push(a);
          return gain;
        }
      }
    }
    return 0;
  }

  // Moves a segment of 1-3 nodes starting at a (in either direction) between
  // two neighbours of its ends, reversed or not.
  double orOpt(int a) {
    if (m_ < 8) return 0;
    for (int dir = 0; dir < 2; ++dir)
      for (int len = 1; len <= 3; ++len) {
        int s1 = a, s2 = a;
        for (int k = 1; k < len; ++k) s2 = dir == 0 ? succ(s2) : pred(s2);
        if (dir == 1) std::swap(s1, s2);  // s1 .. s2 in forward order
        const int p = pred(s1), nx = succ(s2);
        const double removeGain = d(p, s1) + d(s2, nx) - d(p, nx);
        if (removeGain <= eps_) continue;
        auto inSeg = [&](int x) {
          for (int y = s1;; y = succ(y)) {
            if (y == x) return true;
            if (y == s2) return false;
          }
        };
        for (int end : {s1, s2})
          for (int c : nb_[end]) {
            if (d(end, c) >= removeGain) break;
            for (int e : {succ(c), pred(c)}) {
              if (inSeg(c) || inSeg(e) || c == p || c == nx || e == p || e == nx) continue;
              int cc = c, ee = e;
              if (succ(ee) == cc) std::swap(cc, ee);  // cc -> ee forward
              const double same = d(cc, s1) + d(s2, ee), flipped = d(cc, s2) + d(s1, ee);
              const double gain = removeGain - (std::min(same, flipped) - d(cc, ee));
              if (gain <= eps_) continue;
              // The move as two or three 2-opt moves.
              apply2opt(p, s1, cc, ee);   // p-cc ... nx-s2 ... s1-ee
              apply2opt(p, cc, nx, s2);   // p-nx ... cc-s2 ... s1-ee
              if (same < flipped) apply2opt(cc, s2, s1, ee);
              for (int x : {p, nx, s1, s2, cc, ee}) push(x);
              return gain;
            }
          }
      }
    return 0;
  }

  // Swaps two short adjacent stretches of the tour (a double bridge); returns
  // the change in length (negative when longer).
  double kick(std::mt19937_64& rng, int maxSeg) {
    const int p = static_cast<int>(rng() % m_);
    const int l1 = 1 + static_cast<int>(rng() % maxSeg), l2 = 1 + static_cast<int>(rng() % maxSeg);
    auto at = [&](int k) { return t_[(p + k) % m_]; };
    const int a0 = at(1), a1 = at(l1), b0 = at(l1 + 1), b1 = at(l1 + l2), before = at(0), after = at(l1 + l2 + 1);
    const double delta =
        d(before, a0) + d(a1, b0) + d(b1, after) - d(before, b0) - d(b1, a0) - d(a1, after);
    std::vector<int> seg;
    for (int k = l1 + 1; k <= l1 + l2; ++k) seg.push_back(at(k));
    for (int k = 1; k <= l1; ++k) seg.push_back(at(k));
    for (int k = 0; k < l1 + l2; ++k) {
      const int q = (p + 1 + k) % m_;
      t_[q] = seg[k];
      pos_[seg[k]] = q;
    }
    for (int x : {before, a0, a1, b0, b1, after}) push(x);
    return delta;
  }

  const std::vector<Vec2>& pts_;
  int n_, m_, dummy_ = -1, start_ = -1;
  std::function<void()> poll_;
  double big_ = 0;
  double eps_ = 0;  // a gain must exceed this (kRelEps)
  std::vector<std::vector<int>> nb_;
  std::vector<int> t_, pos_;
  std::deque<int> queue_;
  std::vector<char> queued_;
};

// Exact answer for a handful of points: every order.
std::vector<int> exhaustive(const std::vector<Vec2>& pts, bool closed, int startNode) {
  const int n = static_cast<int>(pts.size());
  std::vector<int> perm(n), best;
  std::iota(perm.begin(), perm.end(), 0);
  double bestLen = std::numeric_limits<double>::infinity();
  do {
    if (closed && perm[0] != 0) break;  // rotations of a cycle are the same tour
    if (startNode >= 0 && perm[0] != startNode) continue;
    const double len = tourLength(pts, perm, closed);
    if (len < bestLen - 1e-12) {
      bestLen = len;
      best = perm;
    }
  } while (std::next_permutation(perm.begin(), perm.end()));
  return best;
}

}  // namespace

double tourLength(const std::vector<Vec2>& points, const std::vector<int>& order, bool closed) {
  double len = 0.0;
  for (size_t i = 1; i < order.size(); ++i) len += dist(points[order[i - 1]], points[order[i]]);
  if (closed && order.size() > 1) len += dist(points[order.back()], points[order.front()]);
  return len;
}

std::vector<int> shortenKeepingOrder(const std::vector<Vec2>& p, const std::function<bool(int, int)>& dependent,
                                     const std::function<void()>& poll) {
  constexpr int kMaxSegment = 3, kMaxPasses = 50;
  const int n = static_cast<int>(p.size());
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  auto d = [&](int a, int b) { return dist(p[a], p[b]); };
  bool improved = true;
  for (int pass = 0; improved && pass < kMaxPasses; ++pass) {
    improved = false;
    for (int i = 1; i < n; ++i)
      for (int len = 1; len <= kMaxSegment && i + len <= n; ++len) {
        if (poll && (i * kMaxSegment + len) % kPollEvery == 0) poll();
        // The run order[i .. i + len - 1], between prev and next.
        const int first = order[i], last = order[i + len - 1], prev = order[i - 1];
        const bool hasNext = i + len < n;
        const double saved = d(prev, first) + (hasNext ? d(last, order[i + len]) - d(prev, order[i + len]) : 0.0);
        auto passes = [&](int q) {
          for (int k = i; k < i + len; ++k)
            if (dependent(order[k], q) || dependent(q, order[k])) return false;
          return true;
        };
        int after = -1;  // insert after the point now at this position
        double best = 1e-9;
        for (int j = i - 1; j >= 1 && passes(order[j]); --j) {
          const double gain = saved - (d(order[j - 1], first) + d(last, order[j]) - d(order[j - 1], order[j]));
          if (gain > best) best = gain, after = j - 1;
        }
        for (int j = i + len; j < n && passes(order[j]); ++j) {
          const double added = d(order[j], first) + (j + 1 < n ? d(last, order[j + 1]) - d(order[j], order[j + 1]) : 0.0);
          if (saved - added > best) best = saved - added, after = j;
        }
        if (after < 0) continue;
        const std::vector<int> run(order.begin() + i, order.begin() + i + len);
        order.erase(order.begin() + i, order.begin() + i + len);
        const int at = after < i ? after + 1 : after - len + 1;
        order.insert(order.begin() + at, run.begin(), run.end());
        improved = true;
      }
  }
  return order;
}

namespace {

// The order over points; an open path begins at startNode (if >= 0), a closed
// tour at any node.
std::vector<int> solve(const std::vector<Vec2>& points, bool closed, int startNode, const TourOptions& options) {
  const int n = static_cast<int>(points.size());
  std::vector<int> order;
  if (n <= 7) return exhaustive(points, closed, closed ? -1 : startNode);
  std::mt19937_64 rng(options.seed);
  Tsp tsp(points, !closed, closed ? -1 : startNode, options.poll);
  tsp.greedyEdge();
  if (options.method == TourMethod::Annealing) {
    if (tsp.anneal(rng)) {  // fewer moves than the thesis: polish
      tsp.queueAll();
      tsp.localSearch();
    }
  } else {
    tsp.queueAll();
    tsp.localSearch();
    // Kicks: 20 per point for small instances, fewer for large ones (1000 at 5000 points).
    const long long kicks =
        options.kicks >= 0 ? options.kicks : std::min<long long>(20LL * n, std::max<long long>(1000, 5000000LL / n));
    tsp.iterate(kicks, rng);
  }
  const std::vector<int>& t = tsp.order();
  if (closed) return t;
  // Cut the cycle at the dummy node.
  const int m = static_cast<int>(t.size());
  const int at = static_cast<int>(std::find(t.begin(), t.end(), tsp.dummy()) - t.begin());
  for (int k = 1; k < m; ++k) order.push_back(t[(at + k) % m]);
  if (startNode >= 0 && order.front() != startNode) std::reverse(order.begin(), order.end());
  return order;
}

}  // namespace

std::vector<int> tour(const std::vector<Vec2>& points, bool closed, std::optional<Vec2> start,
                      const TourOptions& options) {
  for (const Vec2& p : points)
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) throw Error("tour: point coordinate is not a finite number");
  if (start && (!std::isfinite(start->x) || !std::isfinite(start->y)))
    throw Error("tour: start is not a finite point");
  const int n = static_cast<int>(points.size());
  if (n == 0) return {};
  if (!start) return solve(points, closed, -1, options);
  if (!closed) {
    // An open path from a place: the place is its first node, so the first
    // point is chosen with the others (the nearest one can make the path longer).
    std::vector<Vec2> from(points);
    from.push_back(*start);
    std::vector<int> order = solve(from, false, n, options);
    order.erase(order.begin());
    return order;
  }
  // A closed tour begins at the point nearest to start.
  int nearest = 0;
  for (int i = 1; i < n; ++i)
    if (dist(points[i], *start) < dist(points[nearest], *start)) nearest = i;
  std::vector<int> order = solve(points, true, -1, options);
  std::rotate(order.begin(), std::find(order.begin(), order.end(), nearest), order.end());
  return order;
}

}  // namespace plunge
