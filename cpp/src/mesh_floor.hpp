// A floor given as a triangle mesh ("floor": {"mesh": ...}, docs/plan-format.md):
// what a planner built without OpenCASCADE reads, from the FreeCAD addon's
// tessellation of the selected faces.
//
// Stop heights come from an exact drop of the flat, ball or bull cutter on
// the triangles (drop-cutter: the highest contact over each triangle's facet,
// edges and vertices), not from a search. Each triangle lies within its
// `deviation` of the true surface, so the cutter grown by it in every
// direction (its tip that much lower, grownAround) is dropped on it and raised
// by it: the true cutter then keeps clear of every surface that close to the
// triangle, so a stop is never below the true one.
#pragma once
#include <memory>
#include <string>

#include "depth.hpp"
#include "floor.hpp"
#include "plunge/types.hpp"

namespace plunge {

// Throws plunge::Error naming what is wrong with the mesh (indices out of
// range, values not finite, no triangle, a negative deviation, deviations
// neither one nor one per triangle), the input's key first ("floor.mesh").
void checkMesh(const TriangleMesh& mesh, const std::string& key);
std::unique_ptr<FloorSurface> makeMeshFloor(const TriangleMesh& mesh);
// The same surface of a checked mesh (the part's triangles within reach,
// part.hpp); none without a triangle.
std::unique_ptr<FloorSurface> makeMeshSurface(const TriangleMesh& mesh);

// The tip height at which `cutter` over `center` first touches the triangles
// (a, b, c), without deviation; -inf when none is under the cutter. Exact up to
// rounding: the facet's contact in closed form, the edges' by a golden-section
// search of a concave function (the lift along an edge is its height minus a
// convex profile of a convex distance).
double dropOnTriangle(const Vec3& a, const Vec3& b, const Vec3& c, Vec2 center, const Cutter& cutter);

}  // namespace plunge
