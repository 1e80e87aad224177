#!/usr/bin/env python3
"""Prints the table (docs/results/evaluation.md) of stock Bullet's soft-rigid handler against ThinTool's collision stage.

Runs benchmarks/bullet/HandlerBench.cpp's rows (StockHandler, ThinToolHandler,
ThinToolPaperHandler at each <faces>/<margin mm>, and the same scene's StockHandler<World> and
ThinToolHandler<World> rows in the soft multibody and the deformable world) with repetitions in
random order and keeps each row's fastest repetition (each time figure on its own,
scripts/benchmark_rows.py), then prints one markdown row per size and margin, and a second table of
the stage and the last word in each world. Needs a Release build in ./build (see README):

    ./scripts/handler-table.py [repetitions, 5 by default]
"""
import sys

from benchmark_rows import fastest_rows, number

repetitions = sys.argv[1] if len(sys.argv) > 1 else "5"
figures = ("real_time", "detectUs", "lastWordUs", "sharedPassUs", "guardUs")
fastest = {(name, int(faces), int(margin)): row
           for (name, faces, margin, *_), row
           in fastest_rows("Handler(SoftMultiBody|Deformable)?/", repetitions, figures).items()}
print("| faces, margin | stock | ThinTool: stage / detection | ratio to stock: stage / detection "
      "| last word (of which shared with Bullet; energy guard) | ratio to stock: stage + last word, + its own part "
      "| paper: stage / detection | ThinTool faces gathered (meeting the swept box) "
      "| faces its walk met | swept tests | stock nodes in its box |")
print("|---|---|---|---|---|---|---|---|---|---|---|")
sizes = sorted({(faces, margin) for (_, faces, margin) in fastest}, key=lambda k: (-k[1], k[0]))
for faces, margin in sizes:
    stock = fastest[("StockHandler", faces, margin)]
    tool = fastest[("ThinToolHandler", faces, margin)]
    paper = fastest[("ThinToolPaperHandler", faces, margin)]
    base = stock["real_time"]
    print(f"| {faces:,}, {margin} mm | {number(base)} | {number(tool['real_time'])} / {number(tool['detectUs'])} "
          f"| {tool['real_time'] / base:.2f} / {tool['detectUs'] / base:.2f} "
          f"| {number(tool['lastWordUs'])} ({number(tool['sharedPassUs'])}; {number(tool['guardUs'])}) "
          f"| {(tool['real_time'] + tool['lastWordUs']) / base:.2f}, "
          f"{(tool['real_time'] + tool['lastWordUs'] - tool['sharedPassUs']) / base:.2f} "
          f"| {number(paper['real_time'])} / {number(paper['detectUs'])} "
          f"| {tool['facesNear']:,.0f} ({tool['facesInSweptBox']:,.0f}) | {tool['facesWalked']:,.0f} "
          f"| {tool['tests']:,.0f} "
          f"| {stock['nodesNear']:,.0f} |")

print()
print("| faces, margin | world | stock | ThinTool's stage | ratio to stock | last word "
      "| ratio to stock: stage + last word |")
print("|---|---|---|---|---|---|---|")
worlds = (("btSoftRigidDynamicsWorld", ""), ("btSoftMultiBodyDynamicsWorld", "SoftMultiBody"),
          ("btDeformableMultiBodyDynamicsWorld", "Deformable"))
world_sizes = {(faces, margin) for (name, faces, margin) in fastest if name.endswith("SoftMultiBody")}
for faces, margin in sorted(world_sizes):
    for world, suffix in worlds:
        stock = fastest[("StockHandler" + suffix, faces, margin)]["real_time"]
        tool = fastest[("ThinToolHandler" + suffix, faces, margin)]
        print(f"| {faces:,}, {margin} mm | {world} | {number(stock)} | {number(tool['real_time'])} "
              f"| {tool['real_time'] / stock:.2f} | {number(tool['lastWordUs'])} "
              f"| {(tool['real_time'] + tool['lastWordUs']) / stock:.2f} |")
