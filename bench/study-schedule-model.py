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

    bench/study-schedule-model.py --multi A.sqlite B.sqlite ... [--orders A.csv B.csv ...] [--cores 2 16]

Several studies (the stores in the order the studies are run or named), for three schedules:
  separate     one study after the other, each in its order, no result cache;
  cache        one study after the other (scripts/reproduce before one multi-study call): a task
               whose content address an earlier study computed costs nothing (reused at start);
  one-queue    every study in one run (`frictal study run A.toml B.toml ... --store-dir DIR`): each
               free core takes the costliest head of all studies' queues (ties: the earlier
               study); a task whose address another core has taken costs nothing (it waits for
               that result without holding a core).
A task's time is the one recorded for its address in any of the stores (a reused task has none of
its own). The orders are each study's dry-run CSV (the estimates a first run uses); without them,
the recorded times (perfect estimates). Prints per schedule and core count the makespan, the
efficiency (the distinct work, each content address once, / (P * makespan): a task computed twice
counts once), per study its makespan and efficiency (its computed work / (P * its makespan);
separate, cache) or the time its last task ends (one-queue).
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


# Kinds whose result does not depend on the seed (TaskKind::uses_seed = false): their content
# address leaves the seed out, so studies with other seeds share them.
SEEDLESS = {"tilt", "koch-signature", "divider"}


def load_multi(stores, orders):
    """Per study: its name, the tasks in run order as (content key, estimate); the recorded
    time of every content key (the first store that computed it)."""
    studies, times = [], {}
    for i, path in enumerate(stores):
        con = sqlite3.connect(f"file:{path}?mode=ro", uri=True)
        rows = con.execute("SELECT task_id, kind, kind_version, params, seed, wall_s, worker FROM tasks "
                           "WHERE status = 'done' ORDER BY task_id").fetchall()
        name = con.execute("SELECT value FROM meta WHERE key = 'study_name'").fetchone()
        key = {}
        for tid, kind, kv, params, seed, wall, worker in rows:
            k = (kind, kv, params, None if kind in SEEDLESS else seed)
            key[tid] = k
            if worker != "cache" and wall and k not in times:
                times[k] = wall
        if orders:
            with open(orders[i], newline="") as f:
                plan = [(int(r["task_id"]), float(r["estimated_s"])) for r in csv.DictReader(f)]
        else:
            plan = [(tid, None) for tid in key]
        studies.append({"name": name[0] if name else path, "plan": [(key[t], e) for t, e in plan if t in key]})
    missing = {k for s in studies for k, _ in s["plan"]} - set(times)
    if missing:
        sys.exit(f"{len(missing)} tasks have no recorded time in any store (run the studies with --cache none)")
    for s in studies:
        s["plan"] = [(k, times[k] if e is None else e) for k, e in s["plan"]]
        # Each study's own order: decreasing estimate, ties in the given order (as longest_first).
        s["plan"] = sorted(s["plan"], key=lambda ke: -ke[1]) if not orders else s["plan"]
    return studies, times


def list_schedule(tasks, cores, times, taken):
    """Each free core takes the next task; a key in `taken` costs nothing. Returns the end of each
    task (a skipped one ends when its key's computation ends) and the makespan."""
    free = [0.0] * cores
    heapq.heapify(free)
    ends, end = [], 0.0
    for k in tasks:
        if k in taken:
            ends.append(taken[k])
            continue
        start = heapq.heappop(free)
        taken[k] = start + times[k]
        heapq.heappush(free, taken[k])
        ends.append(taken[k])
        end = max(end, taken[k])
    return ends, end


def multi(a):
    studies, times = load_multi(a.multi, a.orders)
    if a.cpu:
        scale = a.cpu / sum(times.values())
        print(f"task times scaled by {scale:.3f} (sum of recorded times -> {a.cpu} s of CPU)")
        times = {k: t * scale for k, t in times.items()}
    names = [s["name"] for s in studies]
    print(f"{len(studies)} studies, {sum(len(s['plan']) for s in studies)} tasks, {len(times)} distinct, "
          f"work {sum(times.values()):.1f} s, longest {max(times.values()):.1f} s")
    distinct = sum(times.values())
    print("| schedule | cores | makespan (s) | efficiency | " + " | ".join(names) + " |")
    print("|---|---|---|---|" + "---|" * len(names))
    for p in a.cores:
        for sched in ("separate", "cache"):
            taken_before = {}
            total, work, cells = 0.0, 0.0, []
            for s in studies:
                keys = [k for k, _ in s["plan"]]
                if sched == "cache":
                    todo = [k for k in keys if k not in taken_before]
                else:
                    todo = keys
                w = sum(times[k] for k in dict.fromkeys(todo))
                _, m = list_schedule(todo, p, times, {})
                for k in todo:
                    taken_before[k] = 0.0
                total += m
                work += w
                cells.append(f"{m:.1f} s, {w / (p * m):.0%}" if m > 0 else "0 (reused)")
            print(f"| {sched} | {p} | {total:.1f} | {distinct / (p * total):.0%} | " + " | ".join(cells) + " |")
        # One queue: every study's tasks merged by decreasing estimate (ties: earlier study, then
        # the study's own order).
        merged = sorted(((-e, i, j, k) for i, s in enumerate(studies) for j, (k, e) in enumerate(s["plan"])))
        ends, m = list_schedule([k for *_, k in merged], p, times, {})
        last = [0.0] * len(studies)
        for (_, i, _, _), e in zip(merged, ends):
            last[i] = max(last[i], e)
        work = sum(times.values())
        print(f"| one-queue | {p} | {m:.1f} | {work / (p * m):.0%} | " +
              " | ".join(f"ends at {t:.1f} s" for t in last) + " |")
    print(f"lower bound per core count P: max(work / P, longest) = " +
          ", ".join(f"{p}: {max(sum(times.values()) / p, max(times.values())):.1f} s" for p in a.cores))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("store", nargs="?")
    ap.add_argument("--multi", nargs="+", help="several stores: model the studies run apart and in one queue")
    ap.add_argument("--orders", nargs="+", help="with --multi: each study's dry-run CSV, in the order of --multi")
    ap.add_argument("--order", help="CSV of `frictal study run --dry-run` (order,task_id,part,estimated_s,estimate)")
    ap.add_argument("--cores", type=int, nargs="+", default=[1, 2, 16])
    ap.add_argument("--cpu", type=float, help="user CPU seconds of the run: scale the task times to sum to it (on a "
                    "loaded machine the recorded wall times carry the load; their sum / CPU is the slowdown)")
    a = ap.parse_args()
    if a.multi:
        return multi(a)
    if not a.store:
        ap.error("give a STORE or --multi STORES")
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
