#!/usr/bin/env python3
"""Prints the real-time table (docs/results/evaluation.md): stock Bullet's whole step against ThinTool's.

Runs benchmarks/bullet/WholeStepBench.cpp's rows (WholeStep/Stock, WholeStep/ThinTool and
WholeStep/ThinToolScan, BulletSettings::scanFaces, at each <faces>/<depth mm>) with repetitions in
random order and keeps each row's fastest repetition (scripts/benchmark_rows.py), then prints one
markdown row per size and depth, for each step budget the largest of the balls whose mean step
fits it, and a second table of the collision work in the same steps: the ball's pairs in Bullet's
dispatcher for both (stock's handler; ThinTool's collision stage), with ThinTool's last word added
to its pairs. Needs a Release build in ./build (see README):

    ./scripts/step-table.py [repetitions, 3 by default]
"""
import sys

from benchmark_rows import fastest_rows, number

repetitions = sys.argv[1] if len(sys.argv) > 1 else "3"
figures = ("stepUs", "stageUs", "lastWordUs", "sharedPassUs", "pairsUs", "heldPairsUs", "heldLastWordUs")
fastest = {(name, int(faces), int(depth)): row
           for (_, name, faces, depth, *_), row in fastest_rows("WholeStep/", repetitions, figures).items()}
print("| faces, depth | stock E: step (µs) | ThinTool: step (µs) | ratio to stock "
      "| ThinTool's clocks: stage + last word (of which shared with Bullet) (µs) "
      "| ThinTool scanning: step (µs) | ratio to stock | its clocks (µs) |")
print("|---|---|---|---|---|---|---|---|")
sizes = sorted({(faces, depth) for (_, faces, depth) in fastest}, key=lambda k: (k[1], k[0]))
for faces, depth in sizes:
    stock = fastest[("Stock", faces, depth)]["stepUs"]
    tool = fastest[("ThinTool", faces, depth)]
    scan = fastest[("ThinToolScan", faces, depth)]
    print(f"| {faces:,}, {depth} mm | {number(stock)} | {number(tool['stepUs'])} | {tool['stepUs'] / stock:.2f} "
          f"| {number(tool['stageUs'])} + {number(tool['lastWordUs'])} ({number(tool['sharedPassUs'])}) "
          f"| {number(scan['stepUs'])} | {scan['stepUs'] / stock:.2f} "
          f"| {number(scan['stageUs'])} + {number(scan['lastWordUs'])} ({number(scan['sharedPassUs'])}) |")
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

print()
print("| faces, depth | stock: the ball's pairs (µs) | ThinTool: its pairs + last word (µs) | ratio to stock "
      "| second half of the hold: stock (µs) | ThinTool (µs) | ratio to stock |")
print("|---|---|---|---|---|---|---|")
for faces, depth in sizes:
    stock = fastest[("Stock", faces, depth)]
    tool = fastest[("ThinTool", faces, depth)]
    whole = tool["pairsUs"] + tool["lastWordUs"]
    held = tool["heldPairsUs"] + tool["heldLastWordUs"]
    print(f"| {faces:,}, {depth} mm | {number(stock['pairsUs'])} "
          f"| {number(tool['pairsUs'])} + {number(tool['lastWordUs'])} | {whole / stock['pairsUs']:.2f} "
          f"| {number(stock['heldPairsUs'])} | {number(tool['heldPairsUs'])} + {number(tool['heldLastWordUs'])} "
          f"| {held / stock['heldPairsUs']:.2f} |")
