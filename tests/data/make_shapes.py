#!/usr/bin/env python3
"""Generates the test pockets in tests/data/shapes (run once; outputs are committed).

Every shape uses plunger diameters 20, 12 and 6 mm unless stated, a flat floor and
a small radial allowance, so that the allowance path is exercised everywhere.
"""
import json
import math
import os

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "shapes")
TOOLS = [{"diameter": 20.0, "id": 1}, {"diameter": 12.0, "id": 2}, {"diameter": 6.0, "id": 3}]


def circle(cx, cy, r, n):
    return [[round(cx + r * math.cos(2 * math.pi * k / n), 6), round(cy + r * math.sin(2 * math.pi * k / n), 6)]
            for k in range(n)]


def smooth(cx, cy, radius_fn, step):
    """A closed free-form curve r(theta), discretised with about `step` mm chords."""
    pts, t = [], 0.0
    while t < 2 * math.pi - 1e-9:
        r = radius_fn(t)
        pts.append([round(cx + r * math.cos(t), 6), round(cy + r * math.sin(t), 6)])
        t += step / r
    return pts


def write(name, boundary, islands=(), tools=TOOLS, **extra):
    data = {"version": 1, "boundary": boundary, "islands": list(islands), "tools": tools,
            "top_z": 0.0, "safe_z": 5.0, "floor": {"z": -25.0},
            "allowance": {"radial": 0.5, "floor": 0.3}, "strategy": "packing", "seed": 0}
    data.update(extra)
    with open(os.path.join(OUT, name + ".json"), "w") as f:
        json.dump(data, f, indent=1)


def main():
    os.makedirs(OUT, exist_ok=True)
    # A convex polygon.
    write("convex", [[0, 0], [180, -10], [230, 60], [190, 140], [40, 150], [-20, 70]])
    # Concave corners: a comb-like outline with notches and a re-entrant corner.
    write("concave", [[0, 0], [200, 0], [200, 120], [140, 120], [140, 60], [110, 60], [110, 120],
                      [60, 120], [60, 90], [30, 90], [30, 120], [0, 120]])
    # Two islands: a triangle and a rectangle (clockwise on purpose).
    write("islands", [[0, 0], [200, 0], [200, 120], [0, 120]],
          [[[40, 30], [80, 30], [60, 80]], [[120, 40], [120, 90], [160, 90], [160, 40]]])
    # Free-form boundary and a free-form island, finely discretised smooth curves.
    write("freeform",
          smooth(0, 0, lambda t: 95 + 18 * math.sin(3 * t) + 9 * math.cos(5 * t + 0.4), 0.8),
          [smooth(12, -8, lambda t: 26 + 7 * math.sin(2 * t + 1.0) + 4 * math.cos(3 * t), 0.6)])
    # Two lobes meeting at a narrow neck (16 mm wide: only the 12 and 6 mm tools pass).
    lobe, half, gap = 50.0, 8.0, 110.0
    a = math.asin(half / lobe)
    n = 120
    left = [(lobe * math.cos(t), lobe * math.sin(t))
            for t in (a + (2 * math.pi - 2 * a) * k / n for k in range(n + 1))]
    right = [(gap + lobe * math.cos(t), lobe * math.sin(t))
             for t in (-(math.pi - a) + (2 * math.pi - 2 * a) * k / n for k in range(n + 1))]
    write("neck", [[round(x, 6), round(y, 6)] for x, y in left + right])
    # Benchmark: 600 x 400 with four round islands of 60 mm, tools 12, 8 and 5 mm.
    write("benchmark", [[0, 0], [600, 0], [600, 400], [0, 400]],
          [circle(150, 100, 30, 180), circle(450, 100, 30, 180), circle(150, 300, 30, 180), circle(450, 300, 30, 180)],
          tools=[{"diameter": 12.0, "id": 1}, {"diameter": 8.0, "id": 2}, {"diameter": 5.0, "id": 3}],
          allowance={"radial": 0.0, "floor": 0.0})


def example():
    """The bundled example of the README: a mould cavity with free-form walls, a round
    boss and a free-form rib island."""
    outer = smooth(0, 0, lambda t: 110 + 22 * math.cos(2 * t) + 10 * math.sin(3 * t + 0.5), 0.7)
    outer = [[round(1.25 * x, 6), round(0.8 * y, 6)] for x, y in outer]
    boss = circle(-60, 5, 16, 96)
    rib = smooth(55, -5, lambda t: 14 + 9 * math.cos(2 * t), 0.5)
    data = {"version": 1, "boundary": outer, "islands": [boss, rib],
            "tools": [{"diameter": 25.0, "id": 1, "feed": 150}, {"diameter": 16.0, "id": 2, "feed": 200},
                      {"diameter": 8.0, "id": 3, "feed": 250}],
            "top_z": 0.0, "safe_z": 5.0, "floor": {"z": -30.0},
            "allowance": {"radial": 0.5, "floor": 0.3}, "strategy": "packing", "seed": 0}
    path = os.path.join(HERE, "..", "..", "resources", "examples", "pocket.json")
    with open(path, "w") as f:
        json.dump(data, f, indent=1)


if __name__ == "__main__":
    example()
    main()
