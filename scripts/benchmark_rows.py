"""What handler-table.py and step-table.py share: running rows of ./build/benchmarks/thintool_benchmarks
with repetitions in random order, keeping each row's fastest repetition of each time figure, and
writing a number as the tables do. On a shared machine whole processes run up to 1.6 times slower
for spells: the random order spreads a spell over every row alike, and the fastest repetition is
the one it spared."""
import json
import subprocess


def fastest_rows(benchmark_filter, repetitions, figures):
    """The rows whose names match benchmark_filter, each as its name's parts after the first, split
    at '/', mapped to its row with the smallest of each of figures over the repetitions."""
    output = subprocess.run(
        ["./build/benchmarks/thintool_benchmarks", f"--benchmark_filter={benchmark_filter}",
         f"--benchmark_repetitions={repetitions}", "--benchmark_enable_random_interleaving=true",
         "--benchmark_format=json"],
        check=True, capture_output=True, text=True).stdout
    fastest = {}
    for row in json.loads(output)["benchmarks"]:
        if row.get("run_type") != "iteration":
            continue
        key = tuple(row["run_name"].split("/"))
        best = fastest.setdefault(key, dict(row))
        for figure in figures:
            if figure in row:
                best[figure] = min(best[figure], row[figure])
    return fastest


def number(value):
    return f"{value:,.0f}" if value >= 100 else (f"{value:.1f}" if value >= 10 else f"{value:.2f}")
