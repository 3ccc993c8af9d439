#!/usr/bin/env python3
"""The distributed solve's benchmark: start-up cost, strong and weak scaling, memory per
process, and the solve under a competing load. Every figure is read from
`fetic solve --profile` (per process: time in local solves, neighbour exchanges,
reductions, gathers and the coarse problem; messages, bytes; coarse size; peak memory)
and reported as ratios against a reference measured in the same run.

    bench/mpi_scaling.py [--build build] [--preset quick|full] [--method feti-c|feti|mprgp]
                         [--out DIR] [--only startup strong weak memory load]

quick: ~100,000 unknowns for the strong scaling, weak scaling to 4 processes (a few
minutes). full: the ~1,000,000-unknown scene of fetic-bench-scale (25 pairs of
200x48-element plane struts in 10x2 subdomains), weak scaling to 8 processes, memory of 4
processes against one (about 15 minutes and 3 GB).
"""

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

MPIRUN = ["mpirun", "--allow-run-as-root", "--oversubscribe"]
METHOD = "feti-c"  # --method


def run(command, env=None, check=True):
    started = time.perf_counter()
    done = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                          env=env)
    seconds = time.perf_counter() - started
    if check and done.returncode != 0:
        sys.exit(f"failed ({done.returncode}): {' '.join(command)}\n{done.stdout}\n{done.stderr}")
    return seconds, done


def generate(fetic, path, pairs, elements, subdomains, seed=1):
    if not os.path.exists(path):
        run([fetic, "generate", "--pairs", str(pairs), "--elements", elements,
             "--subdomains", subdomains, "--seed", str(seed), "-o", path])
    return path


def solve_profile(fetic, scene, ranks, out_dir, extra=(), env=None):
    """One solve on `ranks` processes (1: without mpirun); returns its profile."""
    profile = os.path.join(out_dir, f"profile_{METHOD}_{os.path.basename(scene)}_{ranks}.json")
    command = [fetic, "solve", scene, "--method", METHOD, "--quiet", "--profile", profile,
               *extra]
    if ranks > 1:
        command = MPIRUN + ["-np", str(ranks)] + command
    wall, _ = run(command, env=env)
    with open(profile) as f:
        result = json.load(f)
    result["wall_seconds"] = wall
    return result


def per_iteration(profile, field):
    it = max(1, profile["iterations"])
    return [p[field] / it for p in profile["processes"]]


def table(header, rows):
    print("| " + " | ".join(header) + " |")
    print("|" + "---|" * len(header))
    for row in rows:
        print("| " + " | ".join(str(x) for x in row) + " |")
    print()


def startup(fetic, scenes_dir, repeat):
    two_bars = os.path.join(scenes_dir, "two_bars.toml")
    plain, forced = [], []
    forced_env = dict(os.environ, FETIC_FORCE_MPI_INIT="1")
    for _ in range(repeat):
        plain.append(run([fetic, "solve", two_bars, "--quiet"])[0])
        forced.append(run([fetic, "solve", two_bars, "--quiet"], env=forced_env)[0])
    a, b = statistics.median(plain), statistics.median(forced)
    print("### Start-up (fetic solve scenes/two_bars.toml, median of %d)\n" % repeat)
    table(["run", "seconds", "ratio"],
          [["plain start (MPI not initialized: today's default)", f"{a:.3f}", "1.00"],
           ["MPI_Init in singleton mode (what initializing always would cost)", f"{b:.3f}",
            f"{b / a:.1f}"]])


def strong(fetic, scene, out_dir, max_ranks):
    print(f"### Strong scaling: {os.path.basename(scene)}\n")
    base = None
    rows = []
    for ranks in range(1, max_ranks + 1):
        p = solve_profile(fetic, scene, ranks, out_dir)
        if base is None:
            base = p
        it = max(1, p["iterations"])
        slowest = lambda f: max(x[f] for x in p["processes"]) / it * 1e3
        rows.append([ranks, p["iterations"], f"{p['solve_seconds']:.2f}",
                     f"{base['solve_seconds'] / p['solve_seconds']:.2f}",
                     f"{p['solve_seconds'] / it * 1e3:.1f}",
                     f"{slowest('local_seconds'):.1f}", f"{slowest('exchange_seconds'):.2f}",
                     f"{slowest('reduction_seconds'):.2f}", f"{slowest('gather_seconds'):.2f}",
                     f"{slowest('coarse_seconds'):.2f}"])
    table(["processes", "iterations", "solve s", "speed-up", "ms / iteration", "local solves",
           "exchange", "reductions", "gathers", "coarse"], rows)


def weak(fetic, out_dir, ranks_list, pairs_per_rank):
    print(f"### Weak scaling: {pairs_per_rank} pairs of 100x24-element plane struts "
          "(5x1 subdomains each) per process\n")
    rows = []
    for ranks in ranks_list:
        scene = generate(fetic, os.path.join(out_dir, f"weak_{ranks}.toml"),
                         pairs_per_rank * ranks, "100,24", "5,1")
        p = solve_profile(fetic, scene, ranks, out_dir)
        it = max(1, p["iterations"])
        procs = p["processes"]
        rows.append([ranks, int(sum(x["unknowns"] for x in procs)), p["iterations"],
                     f"{max(x['messages'] for x in procs) / it:.1f}",
                     f"{max(x['bytes'] for x in procs) / it / 1024:.1f}",
                     f"{max(x['reductions'] for x in procs) / it:.1f}",
                     f"{max(x['gathers'] for x in procs) / it:.1f}",
                     f"{max(x['gathered_bytes'] for x in procs) / it / 1024:.1f}",
                     int(procs[0]["coarse_size"]), int(procs[0]["coarse_nonzeros"]),
                     int(max(x["coarse_factorizations"] for x in procs)),
                     f"{max(x['coarse_seconds'] for x in procs) / it * 1e3:.2f}",
                     f"{p['solve_seconds']:.2f}"])
    table(["processes", "unknowns", "iterations", "messages / it", "KiB sent / it",
           "reductions / it", "gathers / it", "KiB gathered / it", "coarse size",
           "coarse nonzeros", "coarse factorizations", "coarse ms / it", "solve s"], rows)


def memory(fetic, scene, out_dir, ranks):
    print(f"### Peak resident memory per process: {os.path.basename(scene)}\n")
    serial = solve_profile(fetic, scene, 1, out_dir)
    serial_peak = serial["processes"][0]["peak_resident_bytes"]
    distributed = solve_profile(fetic, scene, ranks, out_dir)
    rows = [["1 (serial)", f"{serial_peak / 2**20:.0f}", "1.00",
             f"{serial['processes'][0]['factor_memory_bytes'] / 2**20:.0f}"]]
    for p in distributed["processes"]:
        rows.append([f"rank {p['rank']} of {ranks}", f"{p['peak_resident_bytes'] / 2**20:.0f}",
                     f"{p['peak_resident_bytes'] / serial_peak:.2f}",
                     f"{p['factor_memory_bytes'] / 2**20:.0f}"])
    table(["process", "peak resident MiB", "of the serial peak", "factor MiB"], rows)


def competing_load(fetic, scenes, out_dir, repeat):
    print("### A competing load: one busy-looping process holds a core\n")
    rows = []
    for scene in scenes:
        quiet = statistics.median(
            solve_profile(fetic, scene, 1, out_dir)["solve_seconds"] for _ in range(repeat))
        spinner = subprocess.Popen([sys.executable, "-c", "while True: pass"])
        try:
            time.sleep(0.2)
            busy = statistics.median(
                solve_profile(fetic, scene, 1, out_dir)["solve_seconds"] for _ in range(repeat))
        finally:
            spinner.kill()
        rows.append([os.path.basename(scene), f"{quiet * 1e3:.2f}", f"{busy * 1e3:.2f}",
                     f"{busy / quiet:.2f}"])
    table(["scene", "quiet ms", "one core busy ms", "ratio (cores available: 2 -> 1)"], rows)


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", default="build")
    parser.add_argument("--preset", choices=["quick", "full"], default="quick")
    parser.add_argument("--method", choices=["feti-c", "feti", "mprgp"], default="feti-c")
    parser.add_argument("--out", default=None, help="keep scenes and profiles here")
    parser.add_argument("--only", nargs="*", default=None,
                        help="startup strong weak memory load (default: all)")
    args = parser.parse_args()
    global METHOD
    METHOD = args.method
    fetic = os.path.abspath(os.path.join(args.build, "fetic"))
    scenes_dir = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scenes")
    out_dir = args.out or tempfile.mkdtemp(prefix="fetic_mpi_bench_")
    os.makedirs(out_dir, exist_ok=True)
    full = args.preset == "full"
    wanted = set(args.only or ["startup", "strong", "weak", "memory", "load"])
    print(f"method: {METHOD}; machine: {os.cpu_count()} cores, {os.uname().machine}; "
          f"load average before: {os.getloadavg()[0]:.2f}\n")
    big = (generate(fetic, os.path.join(out_dir, "big.toml"), 25, "200,48", "10,2") if full
           else generate(fetic, os.path.join(out_dir, "medium.toml"), 10, "100,24", "5,1"))
    if "startup" in wanted:
        startup(fetic, scenes_dir, 11)
    if "strong" in wanted:
        strong(fetic, big, out_dir, 2)
    if "weak" in wanted:
        weak(fetic, out_dir, [1, 2, 4, 8] if full else [1, 2, 4], 2)
    if "memory" in wanted:
        memory(fetic, big, out_dir, 4)
    if "load" in wanted:
        competing_load(fetic, [os.path.join(scenes_dir, "thesis.toml"),
                               os.path.join(scenes_dir, "plane_pair.toml"), big],
                       out_dir, 5 if not full else 3)
    print(f"profiles and scenes in {out_dir}; load average after: {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
