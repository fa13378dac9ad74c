"""The floor faces as a triangle mesh, for a planner built without OpenCASCADE
(the bundles' program): the planner's floor "mesh" (docs/plan-format.md).

OpenCASCADE's tessellation is quick at a coarse deflection and slow at a fine
one (the demo's B-spline floor: 0.2 s at 0.02 mm, 24 s at 0.002 mm). So each
face is tessellated coarsely, then the triangles too far from it are split,
in the surface's own parameters, until none is: new points are the surface's
points at the middle of each edge's parameters.

Each triangle's deviation is measured, not assumed: at its centre and edge
midpoints, the distance between the triangle and the surface's point at the
same place in the triangle's parameters (never less than the distance to
the surface), the largest times MARGIN; the planner gets one per triangle.
It keeps every stop that far off the triangle in every direction, so that a
stop is never below the true surface. On a slope of normal n a distance d
off the surface is d / n_z in height: a triangle is split until its
deviation is under DEVIATION times its n_z (not under STEEP), so that a stop
is at most about 2.25 x DEVIATION above the true one on any slope.

App side: never imports GUI code.
"""
import FreeCAD
import numpy as np
import Part

# OpenCASCADE's first tessellation (mm).
DEFLECTION = 0.02
# Triangles are split until the measured deviation is under this (mm), times
# the z of their normal where they slope, but no less than STEEP.
DEVIATION = 0.002
STEEP = 0.1
# The deviation is sampled where a chord of a smooth surface is farthest from
# it; it is said with this margin.
MARGIN = 1.25
# No more triangles than this per face: the planner reads them all.
MAX_TRIANGLES = 400000


def _surface_points(surface, uv):
    """The surface's points at the parameters uv (k x 2), as a k x 3 array."""
    value = surface.value
    out = np.empty((len(uv), 3))
    for k, (u, v) in enumerate(uv):
        p = value(u, v)
        out[k] = (p.x, p.y, p.z)
    return out


def _corner_parameters(face, points, triangles):
    """Each triangle's corners' (u, v) on the face's surface (m x 3 x 2).

    The tessellation lists its points merged and reordered; the face's
    triangulation keeps their parameters in its own order. Each point is
    matched to the nodes at its place: a point on a seam or at a pole has
    several, and each triangle takes the ones nearest its other corners."""
    surface = face.Surface
    nodes = np.array(face.getUVNodes(), dtype=float).reshape(-1, 2)
    at = _surface_points(surface, nodes)
    tolerance = max(1e-4, 10 * max([e.Tolerance for e in face.Edges] + [face.Tolerance]))
    cell = 4 * tolerance
    grid = {}
    for k, p in enumerate(at):
        grid.setdefault(tuple(np.floor(p / cell).astype(int)), []).append(k)
    candidates = []
    for p in points:
        key = np.floor(p / cell).astype(int)
        found = []
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                for dz in (-1, 0, 1):
                    for k in grid.get((key[0] + dx, key[1] + dy, key[2] + dz), ()):
                        if np.linalg.norm(at[k] - p) <= tolerance:
                            found.append(tuple(nodes[k]))
        if not found:  # not a node's place: the surface's own projection
            found = [surface.parameter(FreeCAD.Vector(*p))]
        candidates.append(sorted(set(found)))
    corners = np.empty((len(triangles), 3, 2))
    for t, tri in enumerate(triangles):
        options = [candidates[i] for i in tri]
        settled = [o[0] for o in options if len(o) == 1]
        ref = np.mean(settled, axis=0) if settled else np.array(options[0][0])
        for c, o in enumerate(options):
            corners[t, c] = min(o, key=lambda uv: (uv[0] - ref[0]) ** 2 + (uv[1] - ref[1]) ** 2)
    return corners


def _stack(*columns):
    return np.stack(columns, axis=1)


def face_mesh(face, deflection=DEFLECTION, deviation=DEVIATION):
    """The face's mesh: points (n x 3), triangles (m x 3) and each triangle's
    measured deviation from the face (before the margin).

    Each round splits the triangles farther than `deviation` from the face in
    four (one new point on each edge, shared with the neighbour across it);
    a neighbour with one new point on its edges is halved, one with two or
    more is split in four too, so that the mesh has no cracks."""
    points, tris = face.tessellate(deflection)
    P = np.array([(p.x, p.y, p.z) for p in points], dtype=float).reshape(-1, 3)
    T = np.array(tris, dtype=np.int64).reshape(-1, 3)
    if isinstance(face.Surface, Part.Plane) or not len(T):
        return P, T, np.zeros(len(T))  # its triangles lie in it
    surface = face.Surface
    UV = _corner_parameters(face, P, T)
    while True:
        # The surface at each triangle's edge midpoints and centre, against the triangle there.
        UVm = (UV + UV[:, [1, 2, 0]]) / 2
        Sm = _surface_points(surface, UVm.reshape(-1, 2)).reshape(-1, 3, 3)
        Sc = _surface_points(surface, UV.mean(axis=1))
        off = np.maximum(np.linalg.norm(Sm - (P[T] + P[T[:, [1, 2, 0]]]) / 2, axis=2).max(axis=1),
                         np.linalg.norm(Sc - P[T].mean(axis=1), axis=1))
        normal = np.cross(P[T[:, 1]] - P[T[:, 0]], P[T[:, 2]] - P[T[:, 0]])
        nz = np.abs(normal[:, 2]) / np.maximum(np.linalg.norm(normal, axis=1), 1e-300)
        far = off > deviation * np.clip(nz, STEEP, 1.0)
        if not far.any() or len(T) + 3 * far.sum() > MAX_TRIANGLES:
            return P, T, off
        # Edges (sorted point pairs) and which triangles' sides they are.
        edges = np.sort(np.stack([T, T[:, [1, 2, 0]]], axis=2), axis=2).reshape(-1, 2)
        _, first, inverse = np.unique(edges, axis=0, return_index=True, return_inverse=True)
        side = inverse.reshape(-1, 3)  # the edge of each triangle's side k (from corner k)
        split = np.zeros(len(first), dtype=bool)
        split[side[far].ravel()] = True
        while True:  # two new points on a triangle's sides: all three
            count = split[side].sum(axis=1)
            whole = count >= 2
            grow = whole & (count < 3)
            if not grow.any():
                break
            split[side[grow].ravel()] = True
        new = np.full(len(first), -1, dtype=np.int64)
        new[split] = len(P) + np.arange(split.sum())
        P = np.vstack([P, Sm.reshape(-1, 3)[first[split]]])
        mid = new[side]  # the new point on each side, or -1
        keep = count == 0
        red = count == 3
        parts_T, parts_UV = [T[keep]], [UV[keep]]
        (a, b, c), (ab, bc, ca) = T[red].T, mid[red].T
        (ua, ub, uc), (mab, mbc, mca) = UV[red].transpose(1, 0, 2), UVm[red].transpose(1, 0, 2)
        parts_T += [_stack(a, ab, ca), _stack(ab, b, bc), _stack(ca, bc, c), _stack(ab, bc, ca)]
        parts_UV += [_stack(ua, mab, mca), _stack(mab, ub, mbc), _stack(mca, mbc, uc), _stack(mab, mbc, mca)]
        # One new point, on side k (corners k, k+1): halved from it to the opposite corner.
        for k in range(3):
            green = (count == 1) & (mid[:, k] >= 0)
            if not green.any():
                continue
            order = [k, (k + 1) % 3, (k + 2) % 3]
            (a, b, c), m = T[green][:, order].T, mid[green, k]
            (ua, ub, uc), um = UV[green][:, order].transpose(1, 0, 2), UVm[green, k]
            parts_T += [_stack(a, m, c), _stack(m, b, c)]
            parts_UV += [_stack(ua, um, uc), _stack(um, ub, uc)]
        T, UV = np.concatenate(parts_T), np.concatenate(parts_UV)


def floor_mesh(faces, deflection=DEFLECTION, deviation=DEVIATION):
    """The planner's floor "mesh" of the faces: their triangles (tessellated
    together, so that neighbours share their edges' points) and each one's
    distance from the faces, with its margin."""
    compound = Part.makeCompound([f.copy() for f in faces])
    compound.tessellate(deflection)
    vertices, triangles, deviations = [], [], []
    for face in compound.Faces:
        P, T, measured = face_mesh(face, deflection, deviation)
        triangles.extend((T + len(vertices)).tolist())
        vertices.extend(P.tolist())
        deviations.extend((measured * MARGIN).tolist())
    return {"vertices": vertices, "triangles": triangles, "deviation": deviations}
