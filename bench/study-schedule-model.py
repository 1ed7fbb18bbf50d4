#!/usr/bin/env python3
"""Schedule model of a study run on P cores, from the task times a store recorded.

    bench/study-schedule-model.py STORE.sqlite [--order ORDER.csv] [--cores 1 2 16]

Replays the run as the coordinator does it (each free core takes the next task of the queue) with
each task's recorded wall time, for three queue orders:
  grid     task id order (the runner before longest-first scheduling);
  planned  the order of ORDER.csv, written by `frictal study run STUDY --store FRESH.sqlite
           --dry-run` (the kinds' cost models, as a first run would start); tasks marked cached
           there cost nothing (the result cache holds them);
  ideal    decreasing recorded time (longest processing time first with perfect estimates).
Prints per order and core count the makespan, the efficiency sum(t) / (P * makespan) and the
lower bound max(sum(t) / P, max t). The times come from one run (on a shared machine they carry
its load); the model assumes tasks do not slow each other down on P cores.
"""
import argparse
import csv
import heapq
import sqlite3
import sys


def makespan(times, cores):
    free = [0.0] * cores
    heapq.heapify(free)
    end = 0.0
    for t in times:
        start = heapq.heappop(free)
        heapq.heappush(free, start + t)
        end = max(end, start + t)
    return end


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("store")
    ap.add_argument("--order", help="CSV of `frictal study run --dry-run` (order,task_id,part,estimated_s,estimate)")
    ap.add_argument("--cores", type=int, nargs="+", default=[1, 2, 16])
    ap.add_argument("--cpu", type=float, help="user CPU seconds of the run: scale the task times to sum to it (on a "
                    "loaded machine the recorded wall times carry the load; their sum / CPU is the slowdown)")
    a = ap.parse_args()
    con = sqlite3.connect(f"file:{a.store}?mode=ro", uri=True)
    rows = con.execute("SELECT task_id, wall_s, worker FROM tasks WHERE status = 'done' ORDER BY task_id").fetchall()
    wall = {tid: (w or 0.0) for tid, w, worker in rows if worker != "cache"}
    if not wall:
        sys.exit(f"{a.store}: no computed task with a recorded time")
    if a.cpu:
        k = a.cpu / sum(wall.values())
        print(f"task times scaled by {k:.3f} (sum of recorded times -> {a.cpu} s of CPU)")
        wall = {t: w * k for t, w in wall.items()}
    # Each order: the task times in the order the cores take them.
    orders = {"grid": [wall[t] for t in sorted(wall)]}
    if a.order:
        with open(a.order, newline="") as f:
            planned = list(csv.DictReader(f))
        # Tasks the plan takes from the result cache cost nothing.
        orders["planned"] = [0.0 if r["estimate"] == "cached" else wall[int(r["task_id"])] for r in planned
                             if int(r["task_id"]) in wall]
    orders["ideal"] = sorted(wall.values(), reverse=True)
    total = sum(wall.values())
    longest = max(wall.values())
    print(f"{a.store}: {len(wall)} computed tasks, sum {total:.1f} s, longest {longest:.1f} s")
    print("| order | cores | makespan (s) | efficiency | lower bound (s) |")
    print("|---|---|---|---|---|")
    for name, times in orders.items():
        s = sum(times)
        if s <= 0:
            print(f"| {name} | - | 0 | - | 0 |")
            continue
        for p in a.cores:
            m = makespan(times, p)
            print(f"| {name} | {p} | {m:.1f} | {s / (p * m):.0%} | {max(s / p, max(times)):.1f} |")


if __name__ == "__main__":
    main()
