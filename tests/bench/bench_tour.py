#!/usr/bin/env python3
"""Sequencing benchmark: closed tours on TSPLIB instances with known optima (gap with
TSPLIB's rounded edge lengths), the default method beside the thesis's simulated
annealing, and the time to order 5000 random points with each.

    /usr/bin/python3 tests/bench/bench_tour.py
"""
import math
import os
import random
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "build", "cpp"))
import plunge  # noqa: E402

DATA = os.path.join(ROOT, "tests", "data", "tsp")


def load(name):
    with open(os.path.join(DATA, name)) as f:
        lines = [line.split() for line in f if line.strip()]
    optimum = float(lines[1][0])
    pts = [(float(x), float(y)) for _, x, y in lines[2:]]
    return pts, optimum


def rounded_length(pts, order):
    # TSPLIB EUC_2D: every edge rounded to the nearest integer.
    return sum(int(math.dist(pts[order[i - 1]], pts[order[i]]) + 0.5) for i in range(len(order)))


def main():
    print("| instance | points | optimum | method | tour (rounded) | gap | time |")
    print("|---|---|---|---|---|---|---|")
    for name in ("kroA100.txt", "XQL662.txt"):
        pts, optimum = load(name)
        for method in ("local_search", "annealing"):
            t0 = time.perf_counter()
            order = plunge.tour(pts, closed=True, method=method, seed=0)
            dt = time.perf_counter() - t0
            assert sorted(order) == list(range(len(pts)))
            length = rounded_length(pts, order)
            print("| %s | %d | %d | %s | %d | %.2f %% | %.2f s |" % (
                name[:-4], len(pts), optimum, method, length, 100 * (length / optimum - 1), dt))
    rng = random.Random(1)
    pts = [(rng.uniform(0, 1000), rng.uniform(0, 1000)) for _ in range(5000)]
    print()
    for method in ("local_search", "annealing"):
        times = []
        for _ in range(3):
            t0 = time.perf_counter()
            order = plunge.tour(pts, closed=False, start=(0, 0), method=method)
            times.append(time.perf_counter() - t0)
        assert sorted(order) == list(range(5000))
        length = sum(math.dist(pts[order[i - 1]], pts[order[i]]) for i in range(1, len(order)))
        print("5000 random points (open path, %s): median %.2f s over 3 runs, length %.0f" % (
            method, sorted(times)[1], length))

if __name__ == "__main__":
    main()
