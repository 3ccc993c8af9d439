#!/usr/bin/env python3
"""New / old per cell of fetic-bench-scale's tables, from the runs of scripts/bench_tables.sh.

    scripts/compare_tables.py OUT [--threshold 1.10] [--rows-by-place FILE...]
                                  [--rename OLD=NEW ...] [--sum FILE:A+B ...]

OUT holds OUT/<part>/<round>.<slot>.<old|new>/ (CSVs and time.txt). A round of a part is
old, new, new, old: its pairs are slot 1 with slot 2 and slot 4 with slot 3, each a run
that finished (exit status 0). Printed as Markdown: per part the pairs, the median
whole-process wall and CPU time new / old (min-max) and the peaks; then per CSV and row (matched by
row name) the median new / old (min-max) of every time column - a header ending in " s"
or " ms", and every column of setup.csv - in bold where the median is above the
threshold. Cells whose old and new values are both 0 are left out of a cell's ratios.

Rows whose names changed between the versions: --rename OLD=NEW replaces the text OLD
in the old rows' names (e.g. "one factor=double factors"); --rows-by-place FILE matches
FILE's rows by their place among the rows that share the scene (the name up to its last
", "): the first against the first, the second against the second. Columns are matched
by name, with the renames in COLUMN_RENAMES. --sum FILE:A+B adds the column "A + B" to
FILE's table, for work that moved from one column to another between the versions (since
b7e8ea2 the Dirichlet interiors' factors are made in "K_j factors", no longer in
"preconditioner": --sum "setup.csv:K_j factors+preconditioner").

For the last check (docs/BENCHMARKS.md), with b4f7ef1's and main's fetic-bench-scale:
    scripts/bench_tables.sh bench-old bench-new runs 2
    scripts/compare_tables.py runs --rows-by-place setup.csv apply_F.csv bytes.csv \
        --sum "setup.csv:K_j factors+preconditioner"
"""
import argparse
import csv
import os
import re
import statistics
import sys

# Old column name -> new, where a column was renamed without changing what it times.
COLUMN_RENAMES = {"coarse and power method": "coarse and norm estimate"}
ALL_TIME_FILES = {"setup.csv"}  # every column after the scene is seconds
ORDINALS = ["1st", "2nd", "3rd", "4th"]


def read_time(run):
    """(wall s, peak kB, CPU s or None) of a run that finished, else None. time.txt holds
    "wall peak status" or "wall peak user system status" (its last line)."""
    try:
        with open(os.path.join(run, "time.txt")) as f:
            fields = f.read().strip().split("\n")[-1].split()
    except OSError:
        return None
    if len(fields) not in (3, 5) or fields[-1] != "0":
        return None
    cpu = float(fields[2]) + float(fields[3]) if len(fields) == 5 else None
    return float(fields[0]), int(fields[1]), cpu


def pairs_of(part_dir):
    """[(old run, new run)] of the finished pairs, in order of rounds."""
    runs = {}
    for name in os.listdir(part_dir):
        m = re.fullmatch(r"(\d+)\.(\d)\.(old|new)", name)
        if m:
            runs[(int(m.group(1)), int(m.group(2)))] = os.path.join(part_dir, name)
    pairs = []
    for r in sorted({r for r, _ in runs}):
        for o, n in ((1, 2), (4, 3)):
            a, b = runs.get((r, o)), runs.get((r, n))
            if a and b and a.endswith("old") and b.endswith("new") and read_time(a) and read_time(b):
                pairs.append((a, b))
    return pairs


def number(cell):
    """The leading number of a cell ("0.52 (12 it)" -> 0.52), or None."""
    m = re.match(r"\s*(-?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?)", cell)
    return float(m.group(1)) if m else None


def read_csv(path, renames, by_place, sums=()):
    """{row key: {column: text}} and the column order of the file, with a column
    "A + B" added for every (file, [A, B]) of `sums` that names this file."""
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    header = [COLUMN_RENAMES.get(h, h) for h in rows[0]]
    added = [columns for file, columns in sums if file == os.path.basename(path)]
    for columns in added:
        places = [header.index(c) if c in header else None for c in columns]
        header.append(" + ".join(columns))
        for row in rows[1:]:
            values = [number(row[i]) if i is not None and i < len(row) else None for i in places]
            row.append("-" if None in values else repr(sum(values)))
    table, seen = {}, {}
    for row in rows[1:]:
        name = row[0]
        for old, new in renames:
            name = name.replace(old, new)
        if by_place:
            scene = name.rsplit(", ", 1)[0]
            seen[scene] = seen.get(scene, 0) + 1
            name = scene + ", " + ORDINALS[seen[scene] - 1]
        table[name] = dict(zip(header, row))
    return table, header


def is_time(file, column):
    if column == "scene":
        return False
    return file in ALL_TIME_FILES or column.endswith(" s") or column.endswith(" ms")


def ratio_text(ratios):
    med = statistics.median(ratios)
    return med, "%.2f (%.2f-%.2f)" % (med, min(ratios), max(ratios))


def cell_ratios(pairs, file, renames, by_place, sums):
    """{row: {column: [new / old per pair]}}, rows and columns in the new file's order."""
    cells, rows, columns = {}, [], []
    for old_run, new_run in pairs:
        paths = [os.path.join(run, file) for run in (old_run, new_run)]
        if not all(os.path.exists(p) for p in paths):
            continue
        old, _ = read_csv(paths[0], renames, by_place, sums)
        new, header = read_csv(paths[1], [], by_place, sums)
        columns = [c for c in header if is_time(file, c)]
        rows = [r for r in new if r in old]
        for row in rows:
            for column in columns:
                a = number(old[row].get(column, "-"))
                b = number(new[row].get(column, "-"))
                if a is None or b is None or (a == 0 and b == 0):
                    continue
                value = float("inf") if a == 0 else b / a
                cells.setdefault(row, {}).setdefault(column, []).append(value)
    return cells, rows, columns


def print_cells(part, file, pairs, threshold, renames, by_place, sums):
    cells, rows, columns = cell_ratios(pairs, file, renames, by_place, sums)
    if not cells:
        return []
    flagged = []
    print("\n`%s` / %s (%d pairs):\n" % (part, file, len(pairs)))
    print("| row | " + " | ".join(columns) + " |")
    print("|---" * (len(columns) + 1) + "|")
    for row in rows:
        texts = []
        for column in columns:
            ratios = cells.get(row, {}).get(column)
            if not ratios:
                texts.append("-")
                continue
            med, text = ratio_text(ratios)
            if med > threshold:
                text = "**" + text + "**"
                flagged.append((part, file, row, column, text))
            texts.append(text)
        print("| " + row + " | " + " | ".join(texts) + " |")
    return flagged


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("out")
    parser.add_argument("--threshold", type=float, default=1.10)
    parser.add_argument("--rows-by-place", nargs="*", default=[], metavar="FILE")
    parser.add_argument("--rename", action="append", default=[], metavar="OLD=NEW")
    parser.add_argument("--sum", action="append", default=[], metavar="FILE:A+B")
    args = parser.parse_args()
    renames = [tuple(r.split("=", 1)) for r in args.rename]
    sums = [(s.split(":", 1)[0], s.split(":", 1)[1].split("+")) for s in args.sum]
    parts = sorted(d for d in os.listdir(args.out) if os.path.isdir(os.path.join(args.out, d)))
    print("| part | pairs | whole process wall, new / old | CPU (user + system), new / old "
          "| wall old / new (medians) | peak old / new |")
    print("|---|---|---|---|---|---|")
    all_pairs = {}
    for part in parts:
        pairs = pairs_of(os.path.join(args.out, part))
        all_pairs[part] = pairs
        if not pairs:
            continue
        times = [(read_time(a), read_time(b)) for a, b in pairs]
        _, wall = ratio_text([b[0] / a[0] for a, b in times])
        cpu_ratios = [b[2] / a[2] for a, b in times if a[2] and b[2]]
        cpu = "%s (%d pairs)" % (ratio_text(cpu_ratios)[1], len(cpu_ratios)) if cpu_ratios else "-"
        print("| %s | %d | %s | %s | %.1f / %.1f s | %.0f / %.0f MB |" % (
            part, len(pairs), wall, cpu,
            statistics.median(a[0] for a, _ in times), statistics.median(b[0] for _, b in times),
            max(a[1] for a, _ in times) / 1024, max(b[1] for _, b in times) / 1024))
    flagged = []
    for part in parts:
        pairs = all_pairs[part]
        if not pairs:
            continue
        files = sorted(f for f in os.listdir(pairs[0][1]) if f.endswith(".csv"))
        for file in files:
            flagged += print_cells(part, file, pairs, args.threshold, renames,
                                   file in args.rows_by_place, sums)
    print("\nMedians above %.2f: %d" % (args.threshold, len(flagged)))
    for part, file, row, column, text in flagged:
        print("- %s / %s / %s / %s: %s" % (part, file, row, column, text.strip("*")))
    return 0


if __name__ == "__main__":
    sys.exit(main())
