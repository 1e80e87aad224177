#!/usr/bin/env python3
"""Prints the real-time table (docs/results/evaluation.md): stock Bullet's whole step against ThinTool's.

Runs benchmarks/bullet/WholeStepBench.cpp's rows (WholeStep/Stock, WholeStep/ThinTool and
WholeStep/ThinToolScan, BulletSettings::scanFaces, at each <faces>/<depth mm>) with repetitions in random order and keeps each row's fastest repetition, as
handler-table.py does, then prints one markdown row per size and depth, and for each step budget
the largest of the balls whose mean step fits it. Needs a Release build in ./build (see README):

    ./scripts/step-table.py [repetitions, 3 by default]
"""
import json
import subprocess
import sys

repetitions = sys.argv[1] if len(sys.argv) > 1 else "3"
output = subprocess.run(
    ["./build/benchmarks/thintool_benchmarks", "--benchmark_filter=WholeStep/",
     f"--benchmark_repetitions={repetitions}", "--benchmark_enable_random_interleaving=true",
     "--benchmark_format=json"],
    check=True, capture_output=True, text=True).stdout
fastest = {}
for row in json.loads(output)["benchmarks"]:
    if row.get("run_type") != "iteration":
        continue
    _, name, faces, depth = row["run_name"].split("/")[:4]
    key = (name, int(faces), int(depth))
    best = fastest.setdefault(key, dict(row))
    for counter in ("stepUs", "stageUs", "lastWordUs"):
        if counter in row:
            best[counter] = min(best[counter], row[counter])


def number(value):
    return f"{value:,.0f}" if value >= 100 else (f"{value:.1f}" if value >= 10 else f"{value:.2f}")


print("| faces, depth | stock E: step (µs) | ThinTool: step (µs) | ratio to stock "
      "| ThinTool's clocks: stage + last word (µs) | ThinTool scanning: step (µs) | ratio to stock "
      "| its clocks: stage + last word (µs) |")
print("|---|---|---|---|---|---|---|---|")
sizes = sorted({(faces, depth) for (_, faces, depth) in fastest}, key=lambda k: (k[1], k[0]))
for faces, depth in sizes:
    stock = fastest[("Stock", faces, depth)]["stepUs"]
    tool = fastest[("ThinTool", faces, depth)]
    scan = fastest[("ThinToolScan", faces, depth)]
    print(f"| {faces:,}, {depth} mm | {number(stock)} | {number(tool['stepUs'])} | {tool['stepUs'] / stock:.2f} "
          f"| {number(tool['stageUs'])} + {number(tool['lastWordUs'])} "
          f"| {number(scan['stepUs'])} | {scan['stepUs'] / stock:.2f} "
          f"| {number(scan['stageUs'])} + {number(scan['lastWordUs'])} |")
print()
for budget in (1000, 1e6 / 60):
    for depth in sorted({depth for (_, _, depth) in fastest}):
        fits = {}
        for name in ("Stock", "ThinTool", "ThinToolScan"):
            within = [faces for (n, faces, d), row in fastest.items()
                      if n == name and d == depth and row["stepUs"] <= budget]
            fits[name] = f"{max(within):,} faces" if within else "none of these balls"
        print(f"- {budget / 1000:.1f} ms budget, {depth} mm deep: stock E {fits['Stock']}, "
              f"ThinTool {fits['ThinTool']}, scanning {fits['ThinToolScan']}")
