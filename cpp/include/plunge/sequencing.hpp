// Plunge sequencing: a short visiting order of points (thesis section 4.3.1).
//
// Default: greedy-edge construction over k-nearest-neighbour candidate lists,
// improved by 2-opt and Or-opt moves (don't-look bits), then iterated local
// search with local double-bridge kicks. The thesis's simulated annealing
// (acceptance rule 4.81, geometric cooling) is available to compare; above
// 1500 points it makes fewer moves per stage and a local search follows.
// Every random choice comes from the seed: same points and seed, same order.
#pragma once
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "plunge/geometry.hpp"
#include "plunge/types.hpp"

namespace plunge {

struct TourOptions {
  TourMethod method = TourMethod::LocalSearch;
  std::uint64_t seed = 0;
  // Iterated-local-search kicks; -1: chosen from the number of points.
  long long kicks = -1;
  // Called every few hundred moves: a long tour reports progress and can be
  // cancelled (Progress::tick throws). The tour does not depend on it.
  std::function<void()> poll;
};

// A permutation of the point indices making the tour short. closed = false
// gives an open path; with `start`, the path is short from start on (start to
// its first point included). A closed tour with `start` begins at the point
// nearest to it.
// Throws plunge::Error for non-finite coordinates.
std::vector<int> tour(const std::vector<Vec2>& points, bool closed = true,
                      std::optional<Vec2> start = std::nullopt, const TourOptions& options = {});

double tourLength(const std::vector<Vec2>& points, const std::vector<int>& order, bool closed);

// Shortens the open path points[0], points[1], ... by Or-opt moves (a run of
// up to three consecutive points moved elsewhere, in its order) that never
// move a point past one it depends on: for every pair with dependent(a, b),
// the returned order keeps a and b in their given order. The first point
// stays first. Deterministic. For orders a constraint made: a plunge within
// an engagement limit must follow the plunges whose cut it grows from
// (engagement.hpp). `poll` is called every few hundred moves tried.
std::vector<int> shortenKeepingOrder(const std::vector<Vec2>& points, const std::function<bool(int, int)>& dependent,
                                     const std::function<void()>& poll = {});

}  // namespace plunge
