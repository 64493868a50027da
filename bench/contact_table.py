#!/usr/bin/env python3
"""Prints bench/results/contact.json (wedge_bench_contact, run by bench/run_contact.sh) as Markdown:
the median CPU time per step of every benchmark with its counters, the ratios Wedge / peer engine and
the goals of bench/README.md ("Contact").

usage: bench/contact_table.py [bench/results/contact.json]
"""
import json
import sys

# (Wedge benchmark, peer benchmark, peer name, goal: the ratio Wedge / peer must not exceed this)
PAIRS = [
    ("Pyramid2D_Wedge/sleep_off", "Pyramid2D_Box2D/sleep_off", "box2d", 1.5),
    ("Pyramid2D_Wedge/sleep_on", "Pyramid2D_Box2D/sleep_on", "box2d", None),
    ("Pile3D_Wedge/sleep_off", "Pile3D_Bullet/sleep_off", "bullet", 1.0),
    ("Pile3D_Wedge/sleep_on", "Pile3D_Bullet/sleep_on", "bullet", 1.0),
]
STEP_GOALS_MS = {"Pile4D_Wedge/1000/sleep_off": 4.0, "Pile4D_Wedge/1000/sleep_on": 4.0,
                 "Pile4D_Wedge/1000/settled": 4.0}
SCENE_GOAL_STEPS_PER_S = 2000.0


def short_name(run_name):
    """'Pile3D_Wedge/sleep_off/iterations:300' -> 'Pile3D_Wedge/sleep_off'."""
    return "/".join(p for p in run_name.split("/") if not p.startswith("iterations:"))


def timed_steps(run_name):
    """The fixed iteration count in the name (the aggregates' 'iterations' is the repetition count)."""
    for part in run_name.split("/"):
        if part.startswith("iterations:"):
            return int(part.split(":")[1])
    return None


GROUPS = ["Pyramid2D_", "Pile3D_", "Pile4D_", "PaperScene/"]


def sort_key(name):
    """Scene, body count, sleeping off before on, Wedge before its peer (random interleaving shuffles
    the JSON)."""
    group = next((i for i, g in enumerate(GROUPS) if name.startswith(g)), len(GROUPS))
    parts = name.split("/")
    count = next((int(p) for p in parts if p.isdigit()), 0)
    sleep = 1 if "sleep_on" in parts else 0
    engine = 0 if "_Wedge" in parts[0] else 1
    return (group, count, sleep, engine, name)


def fmt(value, unit=""):
    if value is None:
        return ""
    if value == 0:
        return "0" + unit
    if abs(value) >= 100:
        return f"{value:.0f}{unit}"
    if abs(value) >= 0.01:
        return f"{value:.3g}{unit}"
    return f"{value:.2g}{unit}"


def main():
    path = sys.argv[1] if len(sys.argv) > 1 else "bench/results/contact.json"
    data = json.load(open(path))
    ctx = data["context"]
    print(f"host {ctx.get('host_name')}, {ctx.get('num_cpus')} cpus @ {ctx.get('mhz_per_cpu')} MHz, "
          f"load {ctx.get('load_avg')}, {ctx.get('date')}")
    print()
    medians, skipped, order = {}, {}, []
    for b in data["benchmarks"]:
        name = short_name(b.get("run_name", b["name"]))
        if b.get("error_occurred"):
            skipped[name] = b.get("error_message", "error")
            if name not in order:
                order.append(name)
            continue
        if b.get("aggregate_name", "median") != "median":
            continue
        if b.get("time_unit") != "ms":
            raise SystemExit(f"{name}: expected ms, got {b.get('time_unit')}")
        medians[name] = b
        if name not in order:
            order.append(name)

    order.sort(key=sort_key)
    print("| benchmark | CPU ms/step | steps/s | timed steps | awake | moving | pairs | max_pen (m) |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    for name in order:
        if name in skipped:
            print(f"| {name} | skipped: {skipped[name]} | | | | | | |")
            continue
        b = medians[name]
        cpu = b["cpu_time"]
        print(f"| {name} | {fmt(cpu)} | {1000.0 / cpu:.0f} | {timed_steps(b['run_name'])} | "
              f"{fmt(b.get('awake'))} | {fmt(b.get('moving'))} | {fmt(b.get('pairs'))} | "
              f"{fmt(b.get('max_pen'))} |")

    pyramids = [n for n in order if n.startswith("Pyramid2D_") and n in medians]
    if pyramids:
        print()
        print("Does the pyramid stand? The top box against its initial pose (m, rad):")
        print()
        print("| benchmark | top_dx after warm-up | top_dy after warm-up | top_dy after timed steps | top_angle |")
        print("|---|---:|---:|---:|---:|")
        for name in pyramids:
            b = medians[name]
            print(f"| {name} | {fmt(b.get('top_dx'))} | {fmt(b.get('top_dy'))} | {fmt(b.get('top_dy_end'))} | "
                  f"{fmt(b.get('top_angle'))} |")

    print()
    print("Ratios of the median CPU time per step:")
    print()
    for wedge, peer, peer_name, goal in PAIRS:
        if wedge not in medians or peer not in medians:
            continue
        ratio = medians[wedge]["cpu_time"] / medians[peer]["cpu_time"]
        verdict = "" if goal is None else (f" (goal <= {goal}: {'met' if ratio <= goal else 'NOT met'})")
        print(f"ratio wedge/{peer_name} = {ratio:.2f}   {wedge} / {peer}{verdict}")
    for name, goal in STEP_GOALS_MS.items():
        if name in medians:
            ms = medians[name]["cpu_time"]
            settled = medians[name].get("settled_s")
            when = "" if settled is None else f", asleep after {settled:.1f} s of warm-up"
            print(f"{name}: {ms:.2f} ms/step (goal <= {goal} ms: {'met' if ms <= goal else 'NOT met'}{when})")
    for name in order:
        if name.startswith("PaperScene/") and name in medians:
            rate = 1000.0 / medians[name]["cpu_time"]
            print(f"{name}: {rate:.0f} steps/s (goal >= {SCENE_GOAL_STEPS_PER_S:.0f}: "
                  f"{'met' if rate >= SCENE_GOAL_STEPS_PER_S else 'NOT met'})")
    for name in order:
        if name in skipped:
            print(f"{name}: skipped ({skipped[name]})")


if __name__ == "__main__":
    main()
