#!/usr/bin/env python3
"""Frame rate while hovering over the picture, and screenshots with pinned items.

Run in an X server (the window needs one):
    xvfb-run -a -s "-screen 0 1600x1000x24" python3 bench/gui_hover.py --fetic build/fetic --out hover

For each scene (the thesis scene, a generated 2,000-pair bar scene, a generated
100,000-unknown plane scene) it starts `fetic gui`, locates a contact pair or a node
(script `locate`), moves the pointer back and forth over the picture with xdotool until the
window reports a `hover` event (200 frames over the picture: frame rate, pick query time,
index build time), clicks the located item to pin it and saves a window screenshot.
Prints one table row per scene. Nothing here is asserted: it is a measurement.
"""
import argparse
import json
import os
import subprocess
import sys
import time


def events(path):
    out = []
    if os.path.exists(path):
        with open(path) as f:
            for line in f:
                try:
                    out.append(json.loads(line))
                except json.JSONDecodeError:
                    pass
    return out


def wait_event(path, name, seconds, after=0):
    deadline = time.time() + seconds
    while time.time() < deadline:
        found = [e for e in events(path)[after:] if e.get("event") == name]
        if found:
            return found[0]
        time.sleep(0.05)
    return None


def xdotool(*args):
    return subprocess.run(["xdotool", *args], check=True, capture_output=True, text=True).stdout


def measure(fetic, scene, what, out, name):
    state = os.path.join(out, name + "_state.jsonl")
    script = os.path.join(out, name + "_script.txt")
    shot = os.path.join(out, name + "_pinned.png")
    for path in (state, shot):
        if os.path.exists(path):
            os.remove(path)
    with open(script, "w") as f:
        f.write("wait\nlocate %s\n" % what)
    app = subprocess.Popen([fetic, "gui", scene, "--state-file", state, "--script", script,
                            "--size", "1280x800", "--screenshot-dir", out])
    try:
        located = wait_event(state, "located", 300)
        if not located or not located.get("found"):
            raise RuntimeError("%s: %s not located" % (name, what))
        window = xdotool("search", "--sync", "--onlyvisible", "--name", "fetic - ").split()[0]
        x, y = round(located["x"]), round(located["y"])
        view = wait_event(state, "ready", 60)["view"]
        left, width, height = view[0], view[2], view[3]
        hover = None
        step = 0
        deadline = time.time() + 120
        while hover is None and time.time() < deadline:
            # Sweep the pointer over the picture's middle band, 40 moves per xdotool call.
            moves = []
            for _ in range(40):
                px = left + 20 + (step * 37) % (width - 40)
                py = height // 3 + (step * 23) % (height // 3)
                moves += ["mousemove", "--window", window, str(px), str(py)]
                step += 1
            xdotool(*moves)
            hover = next((e for e in events(state) if e.get("event") == "hover"), None)
        xdotool("mousemove", "--window", window, str(x), str(y))
        time.sleep(0.5)
        xdotool("click", "1")
        picked = wait_event(state, "picked", 60)
        xdotool("mousemove", "--window", window, str(left + width - 5), str(height - 5))
        time.sleep(0.5)
        shots = len([e for e in events(state) if e.get("event") == "screenshot"])
        xdotool("key", "--window", window, "w")  # W: window screenshot (docs/WINDOW.md)
        shot = wait_event(state, "screenshot", 30, 0) if shots == 0 else None
        if shot:
            os.replace(shot["path"], os.path.join(out, name + "_pinned.png"))
        return hover, picked
    finally:
        app.terminate()
        app.wait(60)


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--fetic", default="build/fetic")
    parser.add_argument("--out", default="hover")
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    bars = os.path.join(args.out, "bars2000.toml")
    plane = os.path.join(args.out, "plane100k.toml")
    subprocess.run([args.fetic, "generate", "--model", "bar", "--pairs", "2000", "-o", bars],
                   check=True)
    subprocess.run([args.fetic, "generate", "--model", "plane", "--pairs", "10", "--elements",
                    "100,24", "--subdomains", "5,1", "-o", plane], check=True)
    here = os.path.dirname(os.path.abspath(__file__))
    scenes = [("thesis", os.path.join(here, "..", "scenes", "thesis.toml"), "pair:25"),
              ("bars2000", bars, "pair:1000"),
              ("plane100k", plane, "node:0:1262")]
    print("| scene | items indexed | frames/s hovering | pick query median / max ms | index build ms | picked |")
    print("|---|---|---|---|---|---|")
    for name, scene, what in scenes:
        hover, picked = measure(args.fetic, scene, what, args.out, name)
        if hover is None:
            print("| %s | - | no hover event | - | - | - |" % name)
            continue
        print("| %s | %s | %.1f | %.3f / %.3f | %.1f | %s |" % (
            name, hover.get("index_items"), hover.get("frames_per_second", 0),
            hover.get("query_ms_median", 0), hover.get("query_ms_max", 0),
            hover.get("index_build_ms", 0),
            (picked or {}).get("kind", "-")))
        sys.stdout.flush()


if __name__ == "__main__":
    main()
