#!/usr/bin/env python3
"""Prints README's table of stock Bullet's soft-rigid handler against ThinTool's collision stage.

Runs benchmarks/bullet/HandlerBench.cpp's rows (StockHandler, ThinToolHandler,
ThinToolPaperHandler at each <faces>/<margin mm>) with repetitions and takes the medians, then
prints one markdown row per size and margin. Needs a Release build in ./build (see README):

    ./scripts/handler-table.py [repetitions]
"""
import json
import subprocess
import sys

repetitions = sys.argv[1] if len(sys.argv) > 1 else "3"
output = subprocess.run(
    ["./build/benchmarks/thintool_benchmarks", "--benchmark_filter=Handler/",
     f"--benchmark_repetitions={repetitions}", "--benchmark_report_aggregates_only=true",
     "--benchmark_format=json"],
    check=True, capture_output=True, text=True).stdout
medians = {}
for row in json.loads(output)["benchmarks"]:
    if row.get("aggregate_name") == "median":
        name, faces, margin = row["run_name"].split("/")[:3]
        medians[(name, int(faces), int(margin))] = row

print("| faces, margin | stock | ThinTool: stage / detection | ratio to stock: stage / detection "
      "| paper: stage / detection | ThinTool faces gathered (meeting the swept box) | swept tests "
      "| stock nodes in its box |")
print("|---|---|---|---|---|---|---|---|")


def number(value):
    return f"{value:,.0f}" if value >= 100 else (f"{value:.1f}" if value >= 10 else f"{value:.2f}")


sizes = sorted({(faces, margin) for (_, faces, margin) in medians}, key=lambda k: (-k[1], k[0]))
for faces, margin in sizes:
    stock = medians[("StockHandler", faces, margin)]
    tool = medians[("ThinToolHandler", faces, margin)]
    paper = medians[("ThinToolPaperHandler", faces, margin)]
    base = stock["real_time"]
    print(f"| {faces:,}, {margin} mm | {number(base)} | {number(tool['real_time'])} / {number(tool['detectUs'])} "
          f"| {tool['real_time'] / base:.2f} / {tool['detectUs'] / base:.2f} "
          f"| {number(paper['real_time'])} / {number(paper['detectUs'])} "
          f"| {tool['facesNear']:,.0f} ({tool['facesInSweptBox']:,.0f}) | {tool['tests']:,.0f} "
          f"| {stock['nodesNear']:,.0f} |")
