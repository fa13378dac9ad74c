#!/usr/bin/env python3
"""Pocket families benchmark: how lean plans within an engagement limit are on
random pockets of eight families (fixed seeds, so every run plans the same
pockets): dumbbells (round or rectangular lobes, necks 0.5-1.5 x the smallest
tool wide), L and T pockets, slots 2-3 x the largest tool wide, annuli (a disk
with a round island), rectangles with round islands, rotated rectangles and
free-form walls (a smooth random radius function). Each pocket gets three
plungers (30/20/12, 25/16/10, 20/12/6 or 16/10/5 mm, by seed).

Each pocket is planned with the command-line tool unlimited and with every
tool's max_engagement = f x D for each limit f. A limited plan's ratio is

    plunges / max(unlimited plan's plunges, row bound),
    row bound = sum over tools i of area_i / (0.87 D_i e_i),  e_i = f D_i,

where area_i is the part of the pocket tool i reaches (the pocket eroded by
r_i + radial allowance, then dilated by r_i) and no larger tool reaches. Every
limited plan is replayed on exact polygon stock (tests/python/engagement_check.py):
plunges over their limit by more than 0.01 mm are counted (starts are exempt).
Shapes that are not valid polygons, where a tool fits nowhere, or that the
planner refuses are skipped (the same ones every run) and counted.

Prints per family and overall the median and worst ratio per limit, the worst
pockets, the over-limit plunges (should be 0), the planning time, and a
markdown table for docs/benchmarks.md:

    nice /usr/bin/python3 tests/bench/bench_family.py --seed 0 --count 8 --limits 0.5 0.25 0.15 --jobs 1

--save-worst DIR writes the inputs (with their limits) of the worst pockets there.
"""
import argparse
import json
import math
import os
import random
import statistics
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ProcessPoolExecutor

from shapely import affinity
from shapely.geometry import LineString, Point, Polygon, box
from shapely.ops import unary_union

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "tests", "python"))
import engagement_check as ec  # noqa: E402

SLACK = 0.01                  # mm over the limit the checker forgives
ROW_SPACING = 0.87            # rows 0.87 D apart
TOOL_SETS = [(30, 20, 12), (25, 16, 10), (20, 12, 6), (16, 10, 5)]
FAMILIES = ["dumbbell", "L", "T", "slot", "annulus", "islands", "rotated", "freeform"]


# ---------------------------------------------------------------------------
# Shapes: each takes the random source and the tool set (largest first) and
# returns (boundary polygon, list of island polygons).

def disk(x, y, r):
    return Point(x, y).buffer(r, resolution=16)


def dumbbell(rng, tools):
    big, small = tools[0], tools[-1]
    neck = rng.uniform(0.5, 1.5) * small
    gap = rng.uniform(0.5, 2.0) * big
    if rng.random() < 0.5:
        r = rng.uniform(1.2, 2.0) * big
        c = r + gap / 2
        lobes = [disk(-c, 0, r), disk(c, 0, r)]
    else:
        w, h = rng.uniform(2.2, 3.5) * big, rng.uniform(2.2, 3.5) * big
        c = w / 2 + gap / 2
        lobes = [box(-c - w / 2, -h / 2, -c + w / 2, h / 2), box(c - w / 2, -h / 2, c + w / 2, h / 2)]
    return unary_union(lobes + [box(-c, -neck / 2, c, neck / 2)]), []


def l_pocket(rng, tools):
    big = tools[0]
    w1, w2 = rng.uniform(1.5, 3.0) * big, rng.uniform(1.5, 3.0) * big
    l1, l2 = rng.uniform(3.5, 6.0) * big, rng.uniform(3.5, 6.0) * big
    return box(0, 0, l1, w1).union(box(0, 0, w2, l2)), []


def t_pocket(rng, tools):
    big = tools[0]
    w1, w2 = rng.uniform(1.5, 3.0) * big, rng.uniform(1.5, 3.0) * big
    l1, l2 = rng.uniform(4.0, 7.0) * big, rng.uniform(2.5, 5.0) * big
    return box(-l1 / 2, 0, l1 / 2, w1).union(box(-w2 / 2, -l2, w2 / 2, w1 / 2)), []


def slot(rng, tools):
    big = tools[0]
    w, length = rng.uniform(2.0, 3.0) * big, rng.uniform(4.0, 10.0) * big
    if rng.random() < 0.5:  # round ends
        return LineString([(-length / 2 + w / 2, 0), (length / 2 - w / 2, 0)]).buffer(w / 2, resolution=16), []
    return box(-length / 2, -w / 2, length / 2, w / 2), []


def annulus(rng, tools):
    big = tools[0]
    outer = rng.uniform(2.5, 4.5) * big
    ring = rng.uniform(1.2, min(2.5, outer / big - 0.4)) * big
    inner = outer - ring
    a, s = rng.uniform(0, 2 * math.pi), rng.uniform(0.0, 0.2) * ring
    return disk(0, 0, outer), [disk(s * math.cos(a), s * math.sin(a), inner)]


def rect_islands(rng, tools):
    big = tools[0]
    w, h = rng.uniform(4.0, 7.0) * big, rng.uniform(3.0, 5.0) * big
    placed = []
    for _ in range(rng.randint(1, 3)):
        for _try in range(40):
            r, gap = rng.uniform(0.3, 1.0) * big, rng.uniform(0.6, 1.5) * big
            x, y = rng.uniform(r + gap, w - r - gap), rng.uniform(r + gap, h - r - gap)
            if all(math.hypot(x - a, y - b) > r + q + gap for a, b, q in placed):
                placed.append((x, y, r))
                break
    return box(0, 0, w, h), [disk(x, y, r) for x, y, r in placed]


def rotated(rng, tools):
    big = tools[0]
    w, h = rng.uniform(2.5, 7.0) * big, rng.uniform(1.5, 4.0) * big
    return affinity.rotate(box(-w / 2, -h / 2, w / 2, h / 2), rng.uniform(0, 180), origin=(0, 0)), []


def freeform(rng, tools):
    big = tools[0]
    radius, squash = rng.uniform(2.5, 4.0) * big, rng.uniform(0.6, 1.0)
    waves = [(k, rng.uniform(0, 0.45 / k), rng.uniform(0, 2 * math.pi)) for k in range(2, 7)]
    pts = []
    for i in range(180):
        t = 2 * math.pi * i / 180
        r = radius * (1 + sum(a * math.sin(k * t + p) for k, a, p in waves))
        pts.append((r * math.cos(t), squash * r * math.sin(t)))
    return Polygon(pts), []


SHAPES = {"dumbbell": dumbbell, "L": l_pocket, "T": t_pocket, "slot": slot, "annulus": annulus,
          "islands": rect_islands, "rotated": rotated, "freeform": freeform}
TURNED = {"dumbbell", "L", "T", "slot"}  # turned by a random angle (rotated turns itself)


def ring(geometry, clockwise):
    xy = list(geometry.exterior.coords)[:-1]
    if Polygon(xy).exterior.is_ccw == clockwise:
        xy.reverse()
    return [[round(x, 4), round(y, 4)] for x, y in xy]


def pocket(family, seed):
    """The planner input of one pocket (unlimited), the same for the same family and seed."""
    rng = random.Random("%s:%d" % (family, seed))
    tools = rng.choice(TOOL_SETS)
    outline, islands = SHAPES[family](rng, tools)
    if family in TURNED:
        angle = rng.uniform(0, 180)
        outline = affinity.rotate(outline, angle, origin=(0, 0))
        islands = [affinity.rotate(i, angle, origin=(0, 0)) for i in islands]
    return {
        "boundary": ring(outline, False), "islands": [ring(i, True) for i in islands],
        "tools": [{"diameter": d, "id": k + 1} for k, d in enumerate(tools)],
        "top_z": 0, "safe_z": 5, "floor": {"z": -12},
        "allowance": {"radial": rng.choice([0.0, 0.3, 0.5]), "floor": 0.2},
        "max_wall_stock": rng.choice([0.5, 1.0, 2.0]), "seed": seed,
    }


# ---------------------------------------------------------------------------
# The row bound

def region(data):
    return Polygon(data["boundary"], data["islands"])


def reach_areas(data):
    """Per tool (largest first): the area it reaches that no larger tool reaches."""
    shape = region(data)
    radial = data["allowance"]["radial"]
    reached, areas = None, []
    for t in sorted(data["tools"], key=lambda t: -t["diameter"]):
        r = t["diameter"] / 2
        opening = shape.buffer(-(r + radial), resolution=32).buffer(r, resolution=32)
        own = opening if reached is None else opening.difference(reached)
        areas.append((t["diameter"], own.area))
        reached = opening if reached is None else reached.union(opening)
    return areas


def row_bound(areas, fraction):
    return sum(a / (ROW_SPACING * d * fraction * d) for d, a in areas)


def invalid(data):
    """Why the random shape is skipped, or None."""
    shape = region(data)
    if not shape.is_valid:
        return "walls cross"
    radial = data["allowance"]["radial"]
    if any(shape.buffer(-(t["diameter"] / 2 + radial)).is_empty for t in data["tools"]):
        return "a tool fits nowhere"
    return None


# ---------------------------------------------------------------------------
# Planning and checking

def limited(data, fraction):
    data = json.loads(json.dumps(data))
    for t in data["tools"]:
        if fraction:
            t["max_engagement"] = fraction * t["diameter"]
    return data


def plan(cli, data, tmp):
    """The CLI's plan of data, or None when it refuses the input (status 2)."""
    src, out = os.path.join(tmp, "in.json"), os.path.join(tmp, "plan.json")
    with open(src, "w") as f:
        json.dump(data, f)
    run = subprocess.run([cli, "plan", src, "-o", out], capture_output=True, text=True, timeout=900)
    if run.returncode == 2:
        return None
    if run.returncode != 0:
        raise RuntimeError("%s failed (%d): %s" % (cli, run.returncode, run.stderr[-500:]))
    with open(out) as f:
        return json.load(f)


def over_limit(data, result):
    return len(ec.over_limit(data, result, SLACK))


def bench_pocket(job):
    """One pocket: its plans and measures, or the reason it was skipped."""
    family, seed, cli, limits = job
    data = pocket(family, seed)
    record = {"family": family, "seed": seed, "tools": [t["diameter"] for t in data["tools"]]}
    why = invalid(data)
    if why:
        return dict(record, skipped=why)
    areas = reach_areas(data)
    with tempfile.TemporaryDirectory() as tmp:
        free = plan(cli, data, tmp)
        if free is None:
            return dict(record, skipped="refused")
        record.update(free=free["stats"]["plunge_count"], seconds=free["stats"]["planning_seconds"], runs={})
        for f in limits:
            run = limited(data, f)
            t0 = time.perf_counter()
            result = plan(cli, run, tmp)
            if result is None:
                return dict(record, skipped="refused at %g D" % f)
            count = result["stats"]["plunge_count"]
            bound = max(record["free"], row_bound(areas, f))
            t1 = time.perf_counter()
            over = over_limit(run, result)
            record["seconds"] += result["stats"]["planning_seconds"]
            record["runs"][f] = {"plunges": count, "bound": bound, "ratio": count / bound, "over": over,
                                 "plan_wall": t1 - t0, "check": time.perf_counter() - t1}
    return record


def run_all(jobs_list, jobs):
    if jobs <= 1:
        for job in jobs_list:
            yield bench_pocket(job)
        return
    with ProcessPoolExecutor(jobs) as pool:
        yield from pool.map(bench_pocket, jobs_list)


# ---------------------------------------------------------------------------
# Report

def ratios(records, f):
    return [r["runs"][f]["ratio"] for r in records]


def cell(values):
    return "%.2f / %.2f" % (statistics.median(values), max(values)) if values else "-"


def table(done, families, limits):
    head = "| family | pockets | " + " | ".join("%g D: median / worst" % f for f in limits) + " | over-limit plunges |"
    lines = [head, "|" + "---|" * (len(limits) + 3)]
    for name in families + ["all"]:
        group = [r for r in done if name in ("all", r["family"])]
        over = sum(r["runs"][f]["over"] for r in group for f in limits)
        lines.append("| %s | %d | %s | %d |" % (name, len(group), " | ".join(cell(ratios(group, f)) for f in limits),
                                                over))
    return "\n".join(lines)


def worst(done, limits, n):
    entries = [(r["runs"][f]["ratio"], r, f) for r in done for f in limits]
    return sorted(entries, key=lambda e: -e[0])[:n]


def save_worst(done, limits, folder, n=3):
    """The inputs of the n worst pockets (each at its worst limit)."""
    os.makedirs(folder, exist_ok=True)
    paths, seen = [], set()
    for ratio, r, f in worst(done, limits, len(done) * len(limits)):
        if (r["family"], r["seed"]) in seen or len(paths) == n:
            continue
        seen.add((r["family"], r["seed"]))
        path = os.path.join(folder, "worst%d_%s_seed%d_%gD.json" % (len(paths) + 1, r["family"], r["seed"], f))
        with open(path, "w") as out:
            json.dump(limited(pocket(r["family"], r["seed"]), f), out, indent=1)
        paths.append((path, ratio))
    return paths


def report(records, families, limits, wall, folder):
    done = [r for r in records if "skipped" not in r]
    skipped = [r for r in records if "skipped" in r]
    print("\n%d pockets, %d planned, %d skipped%s" % (len(records), len(done), len(skipped), "".join(
        "\n  skipped %s seed %d: %s" % (r["family"], r["seed"], r["skipped"]) for r in skipped)))
    print("\nratio = plunges / max(unlimited plunges, row bound); median / worst per limit\n")
    print(table(done, families, limits))
    print("\nworst 5:\n\n| family | seed | tools (mm) | limit | ratio | plunges | bound | unlimited |")
    print("|---|---|---|---|---|---|---|---|")
    for ratio, r, f in worst(done, limits, 5):
        run = r["runs"][f]
        print("| %s | %d | %s | %g D | %.2f | %d | %.1f | %d |" % (
            r["family"], r["seed"], "/".join("%g" % d for d in r["tools"]), f, ratio, run["plunges"],
            run["bound"], r["free"]))
    over = {f: sum(r["runs"][f]["over"] for r in done) for f in limits}
    print("\nover-limit plunges (exact checker, +%.2f mm): %s" % (SLACK, ", ".join(
        "%g D: %d" % (f, n) for f, n in over.items())))
    print("planning time (planner's own, all plans): %.1f s; checking %.1f s; benchmark wall time %.1f s" % (
        sum(r["seconds"] for r in done), sum(run["check"] for r in done for run in r["runs"].values()), wall))
    if folder:
        for path, ratio in save_worst(done, limits, folder):
            print("saved %s (ratio %.2f)" % (path, ratio))


def progress(r):
    """One line per pocket: plunges / bound = ratio per limit."""
    parts = []
    for f, x in r["runs"].items():
        over = " OVER %d" % x["over"] if x["over"] else ""
        parts.append("%gD %d/%.0f=%.2f%s" % (f, x["plunges"], x["bound"], x["ratio"], over))
    return " ".join(parts)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--seed", type=int, default=0, help="first pocket seed of each family")
    ap.add_argument("--count", type=int, default=8, help="pockets per family")
    ap.add_argument("--limits", type=float, nargs="+", default=[0.5, 0.25, 0.15], help="max_engagement / D")
    ap.add_argument("--cli", default=os.path.join(ROOT, "build", "cpp", "plunge-rough"))
    ap.add_argument("--jobs", type=int, default=1, help="pockets planned and checked side by side")
    ap.add_argument("--families", nargs="+", default=FAMILIES, choices=FAMILIES)
    ap.add_argument("--save-worst", metavar="DIR", help="write the 3 worst pockets' inputs here")
    args = ap.parse_args()
    jobs_list = [(fam, args.seed + i, os.path.abspath(args.cli), args.limits)
                 for fam in args.families for i in range(args.count)]
    t0, records = time.perf_counter(), []
    for r in run_all(jobs_list, args.jobs):
        records.append(r)
        line = r.get("skipped") or progress(r)
        print("%-9s seed %-3d %s" % (r["family"], r["seed"], line), file=sys.stderr, flush=True)
    report(records, args.families, args.limits, time.perf_counter() - t0, args.save_worst)


if __name__ == "__main__":
    main()
