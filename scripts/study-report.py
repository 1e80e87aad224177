#!/usr/bin/env python3
"""Turns the study's CSV files (scripts/study.sh) into docs/study.md and its plots.

usage: study-report.py STUDY_FOLDER OUTPUT.md

Reads STUDY_FOLDER/{plate_press,needle_press}-matrix.csv and plate_press-mesh.csv, writes the
markdown tables to OUTPUT.md and, when gnuplot is installed, the plots next to it as
study-error-time.png, study-tunnelling.png and study-fig11.png. Standard library only."""
import csv
import math
import os
import shutil
import subprocess
import sys
from collections import OrderedDict, defaultdict

ALGORITHMS = ["stock-A", "stock-B", "stock-E", "ray-only", "paper", "swept"]
NAMES = {
    "stock-A": "stock A (defaults)",
    "stock-B": "stock B (kKHR 1, 10 it.)",
    "stock-E": "stock E (B, skin 0.05)",
    "ray-only": "ThinTool, rays only (Fig. 7 right)",
    "paper": "ThinTool, paper (discrete)",
    "swept": "ThinTool, swept (default)",
}
SPEED = "tools[0].trajectory.speed"


def read(path):
    if not os.path.exists(path):
        return []
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def failed(row):
    return int(row["crossed_nodes"]) > 0 or int(row["tool_inside_steps"]) > 0


def mean(values):
    values = [v for v in values if v is not None and not math.isnan(v)]
    return sum(values) / len(values) if values else float("nan")


def num(text):
    return float(text) if text not in ("", None) else float("nan")


def fmt(value, digits=3):
    if value is None or math.isnan(value):
        return "-"
    if value == 0:
        return "0"
    return f"{value:.{digits}g}"


def pareto(points):
    """The points no other point beats in both time and error (lower is better)."""
    front = []
    best = float("inf")
    for t, e in sorted(points):
        if e < best:
            front.append((t, e))
            best = e
    return front


def matrix_tables(rows_by_tool):
    lines = [
        "| tool | algorithm | failing cases | crossed nodes (sum) | runs ending inside | max pen. (mm) | "
        "RMS pen. (mm, mean) | force error (mean) | us/step (mean) | tool us/step (mean) |",
        "|---|---|---|---|---|---|---|---|---|---|",
    ]
    for tool, rows in rows_by_tool.items():
        for algorithm in ALGORITHMS:
            mine = [r for r in rows if r["algorithm"] == algorithm]
            if not mine:
                continue
            lines.append(
                "| %s | %s | %d of %d | %d | %d | %s | %s | %s | %s | %s |"
                % (
                    tool,
                    NAMES[algorithm],
                    sum(failed(r) for r in mine),
                    len(mine),
                    sum(int(r["crossed_nodes"]) for r in mine),
                    sum(int(r["ends_inside"]) for r in mine),
                    fmt(max(num(r["max_penetration_m"]) for r in mine) * 1000),
                    fmt(mean(num(r["rms_penetration_m"]) * 1000 for r in mine)),
                    fmt(mean(num(r["force_error"]) for r in mine)),
                    fmt(mean(num(r["us_per_step"]) for r in mine), 4),
                    fmt(mean(num(r["tool_us_per_step"]) for r in mine), 3) if algorithm.startswith(("ray", "paper", "swept")) else "-",
                )
            )
    return lines


def tunnelling(rows_by_tool):
    """Share of the (tool, step) cases that failed, per algorithm and speed."""
    rates = defaultdict(dict)
    speeds = sorted({num(r[SPEED]) for rows in rows_by_tool.values() for r in rows})
    for algorithm in ALGORITHMS:
        for speed in speeds:
            cases = [r for rows in rows_by_tool.values() for r in rows if r["algorithm"] == algorithm and num(r[SPEED]) == speed]
            if cases:
                rates[algorithm][speed] = sum(failed(r) for r in cases) / len(cases)
    return speeds, rates


def mesh_table(rows):
    faces = sorted({int(r["soft_faces"]) for r in rows})
    lines = ["| algorithm | " + " | ".join(f"{f:,} faces" for f in faces) + " |", "|---|" + "---|" * len(faces)]
    for algorithm in ALGORITHMS:
        cells = []
        for f in faces:
            match = [r for r in rows if r["algorithm"] == algorithm and int(r["soft_faces"]) == f]
            if not match:
                cells.append("-")
                continue
            r = match[0]
            cell = fmt(num(r["us_per_step"]), 4)
            if not algorithm.startswith("stock"):
                cell += " (" + fmt(num(r["tool_us_per_step"]), 3) + ")"
            cell += " ✗" if failed(r) else ""
            cells.append(cell)
        if any(c != "-" for c in cells):
            lines.append(f"| {NAMES[algorithm]} | " + " | ".join(cells) + " |")
    return lines


def gnuplot(script, folder):
    if shutil.which("gnuplot") is None:
        return False
    subprocess.run(["gnuplot"], input=script, text=True, check=True, cwd=folder)
    return True


def plots(folder, study, rows_by_tool, speeds, rates, mesh_rows):
    data = os.path.join(study, "plot-data")
    os.makedirs(data, exist_ok=True)
    # Error against time: one point per run, one file per algorithm, and the front over all runs.
    points = []
    for algorithm in ALGORITHMS:
        with open(os.path.join(data, f"points-{algorithm}.dat"), "w") as f:
            for rows in rows_by_tool.values():
                for r in rows:
                    if r["algorithm"] != algorithm:
                        continue
                    t = num(r["us_per_step"])
                    e = int(r["crossed_nodes"]) + int(r["tool_inside_steps"]) / max(1, int(r["steps"]))
                    points.append((t, e))
                    f.write(f"{t} {e + 0.01} {num(r['rms_penetration_m']) * 1000 + 0.001}\n")
    with open(os.path.join(data, "front.dat"), "w") as f:
        for t, e in pareto(points):
            f.write(f"{t} {e + 0.01}\n")
    with open(os.path.join(data, "tunnelling.dat"), "w") as f:
        f.write("speed " + " ".join(ALGORITHMS) + "\n")
        for speed in speeds:
            f.write(f"{speed} " + " ".join(str(rates.get(a, {}).get(speed, float("nan"))) for a in ALGORITHMS) + "\n")
    with open(os.path.join(data, "mesh.dat"), "w") as f:
        faces = sorted({int(r["soft_faces"]) for r in mesh_rows})
        f.write("faces " + " ".join(f"{a} {a}-tool" for a in ALGORITHMS) + "\n")
        for n in faces:
            cells = []
            for a in ALGORITHMS:
                match = [r for r in mesh_rows if r["algorithm"] == a and int(r["soft_faces"]) == n]
                cells.append(match[0]["us_per_step"] if match else "nan")
                cells.append(match[0]["tool_us_per_step"] if match and not a.startswith("stock") else "nan")
            f.write(f"{n} " + " ".join(cells) + "\n")

    rel = os.path.relpath(data, folder)
    plot_points = ", ".join(
        f"'{rel}/points-{a}.dat' using 1:2 with points pt 7 ps 0.8 title '{NAMES[a]}'" for a in ALGORITHMS
    )
    plot_pen = ", ".join(f"'{rel}/points-{a}.dat' using 1:3 with points pt 7 ps 0.8 title '{NAMES[a]}'" for a in ALGORITHMS)
    matrix_script = f"""
set terminal pngcairo size 1400,560 font ',10'
set output 'study-error-time.png'
set multiplot layout 1,2 title 'Error against run time: one point per run (plate and needle, 4 steps, 5 speeds, 128-face ball)'
set logscale xy
set xlabel 'stepSimulation wall time per step (us)'
set ylabel 'crossed nodes + share of steps with the tool inside (+0.01)'
set key top right font ',8'
plot {plot_points}, '{rel}/front.dat' using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front'
set ylabel 'RMS penetration (mm, +0.001)'
plot {plot_pen}
unset multiplot

set terminal pngcairo size 900,560 font ',10'
set output 'study-tunnelling.png'
unset logscale
set logscale x
set title 'Tunnelling rate against speed: share of (tool, step) cases with a crossed node or the tool inside'
set xlabel 'tool speed (m/s)'
set ylabel 'failing share'
set yrange [-0.05:1.05]
set key outside right font ',8'
plot for [i=2:{len(ALGORITHMS) + 1}] '{rel}/tunnelling.dat' using 1:i with linespoints lw 2 title columnheader(i)
"""
    mesh_script = f"""
set terminal pngcairo size 900,560 font ',10'
set output 'study-fig11.png'
set key outside right font ',8'
set logscale xy
set autoscale y
set title "Time per step against soft-body triangles (the paper's Fig. 11): plate at 1 m/s, 1/60 s"
set xlabel 'soft-body triangles'
set ylabel "us per step (solid: stepSimulation; dashed: ThinTool's share)"
plot for [i=0:{len(ALGORITHMS) - 1}] '{rel}/mesh.dat' using 1:(column(2*i+2)) with linespoints lw 2 title columnheader(2*i+2), \\
     for [i=3:{len(ALGORITHMS) - 1}] '{rel}/mesh.dat' using 1:(column(2*i+3)) with linespoints dt 2 lw 2 title columnheader(2*i+3)
"""
    script = (matrix_script if rows_by_tool else "") + (mesh_script if mesh_rows else "")
    return gnuplot(script, folder) if script else False


def main():
    study, output = sys.argv[1], sys.argv[2]
    rows_by_tool = OrderedDict()
    for tool, name in (("plate", "plate_press"), ("needle", "needle_press")):
        rows = read(os.path.join(study, f"{name}-matrix.csv"))
        if rows:
            rows_by_tool[tool] = rows
    mesh_rows = read(os.path.join(study, "plate_press-mesh.csv"))
    speeds, rates = tunnelling(rows_by_tool)
    all_rows = [r for rows in rows_by_tool.values() for r in rows]
    algorithms = [a for a in ALGORITHMS if any(r["algorithm"] == a for r in all_rows)]
    steps = []
    for r in sorted(all_rows, key=lambda r: -num(r["dt"])):
        name = "1/%d" % round(1 / num(r["dt"]))
        if name not in steps:
            steps.append(name)
    folder = os.path.dirname(os.path.abspath(output))
    plotted = plots(folder, study, rows_by_tool, speeds, rates, mesh_rows)

    out = [
        "# The evaluation study",
        "",
        "Written by `./scripts/study.sh` (the runs, through `thintool_run`) and `scripts/study-report.py`",
        "(these tables and the plots) from the CSV files in `docs/study/`, one row per run. Accuracy is the",
        "ground truth's (`eval/GroundTruth.h`), time is `stepSimulation`'s wall time and ThinTool's share of it,",
        "from the same runs. A case fails when a node crossed the tool or the tool's centre was inside the ball.",
        "",
        "## The matrix: %d algorithms x %d steps (%s s) x %d speeds (%s m/s), %s"
        % (len(algorithms), len(steps), ", ".join(steps), len(speeds), ", ".join(fmt(v) for v in speeds),
           " and ".join(rows_by_tool)),
        "",
        "The paper's 128-face ball. Force error: RMS of |F - F_ref| over the run, over the reference's peak,",
        "against the reference run `scripts/study.sh` names (swept detection at 1/1000 s on the 512-face",
        "ball at the same speed; ThinTool's Hunt–Crossley force, stock Bullet reports none).",
        "",
    ]
    out += matrix_tables(rows_by_tool)
    out += ["", "Failing share by speed (over the tools and steps):", ""]
    out.append("| algorithm | " + " | ".join(f"{fmt(s)} m/s" for s in speeds) + " |")
    out.append("|---|" + "---|" * len(speeds))
    for algorithm in algorithms:
        if rates.get(algorithm):
            out.append(f"| {NAMES[algorithm]} | " + " | ".join(fmt(rates[algorithm].get(s, float('nan')), 2) for s in speeds) + " |")
    if mesh_rows:
        out += [
            "",
            "## Cost against the soft body's size (the paper's Fig. 11)",
            "",
            "The plate at 1 m/s and 1/60 s on Bullet's ellipsoid of 128 to 65,536 faces (`exact_hull`: every point",
            "of its hull a node): `stepSimulation`'s wall time per step in us, ThinTool's own share in brackets;",
            "✗ marks a failing run.",
            "",
        ]
        out += mesh_table(mesh_rows)
    if plotted:
        out += ["", "## Plots", ""]
        if rows_by_tool:
            out += ["![error against time](study-error-time.png)", "", "![tunnelling against speed](study-tunnelling.png)", ""]
        if mesh_rows:
            out += ["![time against triangles](study-fig11.png)"]
    with open(output, "w") as f:
        f.write("\n".join(out) + "\n")


if __name__ == "__main__":
    main()
