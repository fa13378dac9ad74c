// The pocket region: an outer wall loop with island loops, validated and oriented
// so that the material to remove is on the left of every wall segment.
// Exact (double precision) queries used by packing and covering to guarantee
// that no plunge gouges a wall: distance to the walls and point containment,
// both accelerated by a Boost.Geometry R-tree of the wall segments.
#pragma once
#include <memory>
#include <optional>
#include <vector>

#include "plunge/geometry.hpp"

namespace plunge {

class Region {
 public:
  struct Vertex {
    Vec2 p;
    int prevWall;  // wall ending at this vertex
    int nextWall;  // wall starting at this vertex
    bool reflex;   // interior angle above 180 degrees: a disk can touch the vertex itself
  };

  // Validates the loops (either orientation) and throws plunge::Error naming the
  // problem: too few distinct points, non-finite coordinates, zero area,
  // self-intersection, islands crossing or outside the boundary, islands overlapping.
  Region(const Loop& boundary, const std::vector<Loop>& islands);
  ~Region();
  Region(Region&&) noexcept;
  Region& operator=(Region&&) noexcept;

  // loops()[0] is the boundary (counter-clockwise), the rest the islands (clockwise).
  const std::vector<Loop>& loops() const { return loops_; }
  const std::vector<Segment>& walls() const { return walls_; }
  const std::vector<Vertex>& vertices() const { return vertices_; }
  // Loop index of a wall.
  int wallLoop(int wall) const { return wallLoop_[wall]; }
  double area() const;
  Polygons polygons() const { return loops_; }

  // Point strictly inside the region (ray casting; points on a wall are ambiguous).
  bool contains(Vec2 p) const;
  // Distance from p to the nearest wall; exact when it is at most `within`,
  // otherwise some value above `within`.
  double wallDistance(Vec2 p, double within) const;
  // Nearest wall point to p among the walls whose bounding box comes within
  // `within` of p (returns false if none): it may lie farther than `within`.
  bool nearestWallPoint(Vec2 p, double within, Vec2& point, double& distance, int* wall = nullptr) const;
  // A disk of radius `clearance` at c lies inside the region (walls at least
  // clearance - tol away, centre inside).
  bool diskFits(Vec2 c, double clearance, double tol = 1e-9) const;
  // Walls whose bounding box meets the square of half-size `radius` around p.
  std::vector<int> wallsNear(Vec2 p, double radius) const;
  // wallsNear, but at most the k nearest to p: pairs of walls in reach stay few
  // when a tool is as large as the pocket (or the walls very fine).
  std::vector<int> nearestWallsNear(Vec2 p, double radius, size_t k) const;
  // reflexVerticesNear, but at most the k nearest to p.
  std::vector<int> nearestReflexVerticesNear(Vec2 p, double radius, size_t k) const;
  // Walls whose bounding box meets the box [lo, hi].
  std::vector<int> wallsInBox(Vec2 lo, Vec2 hi) const;
  // Reflex vertices whose position lies in the square of half-size radius around p.
  std::vector<int> reflexVerticesNear(Vec2 p, double radius) const;
  // Axis-aligned bounds of the boundary: min and max corners.
  Vec2 minCorner() const { return lo_; }
  Vec2 maxCorner() const { return hi_; }

 private:
  // The constructor's steps: material on the left of every wall, walls and
  // vertices indexed, then the checks that the loops neither cross nor nest wrongly.
  void orientLoops();
  void buildWalls();
  void checkCrossings() const;
  void checkWallPair(size_t i, size_t j) const;
  void checkNesting() const;

  struct Index;
  std::vector<Loop> loops_;
  std::vector<Segment> walls_;
  std::vector<int> wallLoop_;
  std::vector<size_t> loopFirst_;
  std::vector<Vertex> vertices_;
  Vec2 lo_, hi_;
  std::unique_ptr<Index> index_;
};

// Large boundaries (fine chordal tolerances give tens of thousands of
// vertices): the region with its loops simplified (Douglas-Peucker, Boost.Geometry)
// within the smallest tolerance of 1, 2, 4 ... um up to maxTolerance mm that
// leaves at most maxVertices vertices. Every simplified wall lies within
// `tolerance` of the original walls and back, so a plan on it whose radial
// allowance is raised by `tolerance` keeps the asked allowance to the real
// walls. None (tolerance 0) when the region is small enough, or when no
// simplification is both small enough and still a valid region.
std::optional<Region> simplifiedRegion(const Region& region, size_t maxVertices, double maxTolerance,
                                       double& tolerance);

}  // namespace plunge
