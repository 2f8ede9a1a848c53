"""Bad and extreme model files, and extreme options, through ``info``, ``snapshot`` and
``export-mesh``: each must be refused (exit 2) in under 5 s and 500 MB, or finish (exit 0)
in under 30 s. Prints every run's status, seconds and peak memory, and the worst of each.

    .venv/bin/python benchmarks/bad_files.py [--python PYTHON] [--only WORD] [--limit S]

``--python`` runs another installation's biceps (a checkout of main with its own venv,
say). Each run is a process of its own, killed past ``--limit`` seconds (60) or 6 GB.
The edges of the bounds (named "edge: ...") must finish in under 30 s and 2 GB; long work
(named "long: ...", which shows its progress and stops on ctrl+c) in under 2 GB.
The files are written afresh into a temporary folder: the classes of issue 28 (a file's
whole cost: muscles, nodes, triangles; geometry that makes no sense; text that makes the
error locator or the parser slow; bounds at their edges).
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
ELBOW = (ROOT / "configs" / "elbow.toml").read_text()
BICEPS = (ROOT / "configs" / "biceps.toml").read_text()


def biceps(**tables: str) -> str:
    """configs/biceps.toml with each ``table=lines`` at the top of its ``[table]``, each key
    of theirs taken out of the file's own lines."""
    keys = {line.split("=")[0].strip() for lines in tables.values() for line in lines.splitlines()}
    text = "".join(line for line in BICEPS.splitlines(keepends=True)
                   if line.split("=")[0].strip() not in keys)
    for table, lines in tables.items():
        text = text.replace(f"[{table}]\n", f"[{table}]\n{lines}", 1)
    return text

DRIVER = """[muscle]
name = "BIClong"
flexion = 0.0
nodes = [[0.3, 0.0], [1.8, 1.55], [0.35, 0.0]]
"""

KILL_BYTES = 6 << 30
REFUSED_SECONDS, REFUSED_BYTES, DONE_SECONDS, EDGE_BYTES = 5.0, 500 << 20, 30.0, 2 << 30


def nodes(count: int) -> str:
    """A profile of ``count`` nodes, thin ends and a belly, as TOML."""
    rows = []
    for i in range(count):
        t = i / (count - 1)
        belly = 4 * t * (1 - t)
        rows.append(f"[{0.3 + 1.5 * belly:.3g},{1.4 * belly:.3g}]")
    return "nodes = [" + ",".join(rows) + "]\n"


def companion(name: str, count: int = 11, origin=(11.65, 1.0, 0.87),
              insertion=(2.39, -0.32, 0.09), wrap: bool = True) -> str:
    text = (f"[muscles.{name}]\nflexion = 0.0\n{nodes(count)}origin = {list(origin)}\n"
            f"insertion = {list(insertion)}\n")
    return text + ('wrap = "front"\nwrap_radius = 1.27\n' if wrap else "")


def many(count: int, each: int) -> str:
    return DRIVER + "".join(companion(f"m{i}", each) for i in range(count))


FILES = {
    # A file's whole cost.
    "10,000 muscles": lambda: many(10_000, 11),
    "100 muscles": lambda: many(100, 11),
    "17 muscles": lambda: laid(17, 11),
    "3 muscles of 7,000 nodes": lambda: laid(3, 7_000),
    "6 muscles of 1,112 nodes": lambda: laid(6, 1_112),
    "12 muscles of 19,990 nodes": lambda: many(11, 19_990).replace(
        DRIVER, DRIVER.replace("nodes = [[0.3, 0.0], [1.8, 1.55], [0.35, 0.0]]\n",
                               nodes(19_990))),
    "6 muscles of 20,000 nodes": lambda: many(5, 20_000),
    "20,000 nodes at 1,024 segments": lambda: (
        "[muscle]\nlength = 33.0\n" + nodes(20_000) + "[render]\nsegments = 1024\n"),
    "20,000 nodes": lambda: "[muscle]\nlength = 33.0\n" + nodes(20_000),
    # Geometry that makes no anatomical sense.
    "an origin 1e7 cm up a humerus": lambda: DRIVER + companion("far", origin=(1e7, 1.0, 0.87)),
    "an insertion 500 cm past the hand": lambda: DRIVER + companion(
        "long", insertion=(525.4, 0.0, 0.0), wrap=False),
    "every muscle on one path": lambda: DRIVER + "".join(
        companion(f"same{i}") for i in range(6)),
    "both attachments at the elbow": lambda: DRIVER + companion(
        "nowhere", origin=(0.0, 0.0, 0.0), insertion=(0.0, 0.0, 0.0), wrap=False),
    "a flexion range 1e-9 degrees wide": lambda: (
        "[muscle]\nflexion = 60.0\nnodes = [[0.35, 0.0], [2.08, 2.05], [0.35, 0.0]]\n"
        "[skeleton]\nflexion_range = [60.0, 60.000000001]\n"),
    "a humerus of 150 cm": lambda: biceps(skeleton="upper_arm = 150.0\n"),
    "a forearm of 1,000 cm": lambda: biceps(skeleton="forearm = 1000.0\n"),
    "a humerus of 1e6 cm": lambda: biceps(skeleton="upper_arm = 1e6\n"),
    "a humerus of 1e6 cm with companions": lambda: ELBOW.replace(
        "[skeleton]\n", "[skeleton]\nupper_arm = 1e6\n"),
    "a view yaw of 1e308 degrees": lambda: biceps(view="yaw = 1e308\n"),
    # Text that is slow to read or to locate an error in.
    "a 3 MB line": lambda: BICEPS + "# " + "x" * 3_000_000 + "\n",
    "a 3 MB comment of brackets": lambda: BICEPS + "# " + "[" * 3_000_000 + "\n",
    "a table-like line in a multi-line string": lambda: biceps(
        muscle='note = """\n' + "[muscle]\nlength = 1\n" * 100_000 + '"""\n'),
    "a string of 3 MB of brackets": lambda: ('note = """' + "[" * 3_000_000 + '"""\n'
                                             + BICEPS),
    "a line of 100,000 spaces": lambda: BICEPS + " " * 100_000 + "\nbad = 1\n",
    "an unknown key of 10,000 letters": lambda: biceps(muscle="k" * 10_000 + " = 1\n"),
    "a muscle's name with a space": lambda: biceps(muscle='name = "a b"\n'),
    "min_length 31 and max_length 30.999": lambda: biceps(
        muscle="min_length = 31.0\nmax_length = 30.999\n"),
    # Bounds at their edges: each must finish (exit 0).
    "edge: 20,000 nodes at 50 segments": lambda: (
        "[muscle]\nlength = 33.0\n" + nodes(20_000) + "[render]\nsegments = 50\n"),
    "edge: 16 muscles of 156 nodes": lambda: laid(16, 156),
    "edge: 6 muscles of 1,111 nodes": lambda: laid(6, 1_111),
    "edge: bones 4 to 1": lambda: scaled(4 * 25.4 / 29.1, 1.0),
    "edge: bones of 1e6 cm": lambda: scaled(999_999 / 30.15, 999_999 / 25.4),
    "edge: bones of 5e-6 cm": lambda: scaled(5e-6 / 29.1, 5.1e-6 / 25.4),  # (1e-6 between)
    "edge: radii and growth of 1e4": lambda: (
        "[muscle]\nlength = 33.0\nnodes = [[1e4, 0.0], [1e4, 1e4], [1e4, 0.0]]\n"),
    "edge: radii of 1e-6": lambda: (
        "[muscle]\nlength = 1e-5\nnodes = [[1e-6, 0.0], [1e-6, 1e-6], [1e-6, 0.0]]\n"
        "[skeleton]\nupper_arm = 1e-5\norigin_to_elbow = 1e-5\nforearm = 1e-5\n"
        "elbow_to_insertion = 2e-6\norigin_lateral = 0.0\ninsertion_lateral = 0.0\n"
        "insertion_forward = 1e-6\n"),
    "edge: a light and an offset 1e8 cm away, scale 0.01": lambda: biceps(
        view="scale = 0.01\noffset = [1e8, -1e8, 1e8]\n", light="position = [1e8, 1e8, -1e8]\n"),
    "edge: scale 100, turned 360 degrees": lambda: biceps(
        view="scale = 100.0\nyaw = 360.0\npitch = -360.0\nroll = 360.0\n"),
    "edge: segments 1024, supersampling 4": lambda: biceps(
        render="segments = 1024\nssaa = 4\nshading = \"phong\"\n"),
}


def laid(muscles: int, each: int) -> str:
    """A driver and companions, ``muscles`` in all, of ``each`` nodes, side by side."""
    return DRIVER.replace("nodes = [[0.3, 0.0], [1.8, 1.55], [0.35, 0.0]]\n", nodes(each)) + \
        "".join(companion(f"m{i}", each, origin=(8.0 + i, 1.0 + 0.1 * i, 0.87))
                for i in range(muscles - 1))


def scaled(up: float, fore: float) -> str:
    """A single-muscle model with its upper arm ``up`` and its forearm ``fore`` times an
    adult's, the attachments with them, the muscle too as far as a radius may go."""
    r = min(max(up, 1e-6 / 0.35), 1e4 / 2.0)
    return (f"[muscle]\nflexion = 60.0\nnodes = [[{0.35 * r}, 0.0], [{2.0 * r}, {2.0 * r}], "
            f"[{0.35 * r}, 0.0]]\n[skeleton]\nupper_arm = {29.1 * up}\n"
            f"origin_to_elbow = {30.15 * up}\norigin_lateral = {-2.2 * up}\n"
            f"forearm = {25.4 * fore}\nelbow_to_insertion = {4.987 * fore}\n"
            f"insertion_forward = {0.753 * fore}\ninsertion_lateral = {2.18 * fore}\n")

COMMANDS = {
    "info": lambda path, out: ["info", path],
    "snapshot": lambda path, out: ["snapshot", path, "-o", out / "arm.png"],
    "export-mesh": lambda path, out: ["export-mesh", path, "-o", out / "arm.obj"],
}

# Options at their edges, on the bundled model.
OPTIONS = {
    "--length 1e308": ["info", "--length", "1e308"],
    "snapshot 8192x8192 --ssaa 4": ["snapshot", "--size", "8192x8192", "--ssaa", "4", "-o",
                                    "{out}/big.png"],
    "animate 10,000 frames 640x360": ["animate", "--frames", "10000", "--size", "640x360",
                                      "-o", "{out}/flex.gif"],
    "sweep --step 1e-308": ["sweep", "--step", "1e-308"],
    "edge: snapshot 8192x8192": ["snapshot", "--size", "8192x8192", "-o", "{out}/big.png"],
    "edge: snapshot 4096x4096 --ssaa 3": ["snapshot", "--size", "4096x4096", "--ssaa", "3",
                                          "--shading", "phong", "-o", "{out}/big.png"],
    "long: sweep of 20,000 angles, elbow": ["sweep", "elbow", "--step", "0.0065"],
    "long: animate 998 frames of 640x360": ["animate", "--frames", "998", "--loop", "--size",
                                            "640x360", "-o", "{out}/flex.gif"],
    "export-mesh --segments 1024 elbow": ["export-mesh", "elbow", "--segments", "1024", "-o",
                                          "{out}/arm.glb"],
}


def run(python: str, argv: list[str],
        limit: float) -> tuple[int | None, float, float, int, str]:
    """``biceps ARGV`` in a process of its own: (status or None if killed, seconds, CPU
    seconds, peak bytes, its last line on stderr)."""
    start = time.perf_counter()
    process = subprocess.Popen([python, "-m", "biceps", *map(str, argv)],
                               stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    killed, done = threading.Event(), threading.Event()

    def watch() -> None:  # (not process.poll(), which would reap it before wait4 can)
        while not done.wait(0.1):
            if time.perf_counter() - start > limit or _rss(process.pid) > KILL_BYTES:
                killed.set()
                process.kill()
                return

    watcher = threading.Thread(target=watch, daemon=True)
    watcher.start()
    stderr = process.stderr.read().decode(errors="replace")
    _, status, usage = os.wait4(process.pid, 0)
    done.set()
    process.returncode = os.waitstatus_to_exitcode(status)
    seconds = time.perf_counter() - start
    watcher.join()
    last = stderr.strip().splitlines()[-1] if stderr.strip() else ""
    return (None if killed.is_set() else process.returncode, seconds,
            usage.ru_utime + usage.ru_stime, usage.ru_maxrss * 1024, last)


def _rss(pid: int) -> int:
    try:
        with open(f"/proc/{pid}/status") as status:
            for line in status:
                if line.startswith("VmRSS:"):
                    return int(line.split()[1]) * 1024
    except OSError:
        pass
    return 0


def verdict(name: str, status: int | None, seconds: float, peak: int) -> str:
    """"ok" if the run did as it must: a long job (named "long: ...", work that shows its
    progress) finished in under 2 GB, an edge (named "edge: ...") in under 30 s and 2 GB, and
    anything else either that or a refusal in under 5 s and 500 MB. ``seconds`` are CPU
    seconds, all threads together: on a machine others share, wall time says more about
    them than about this; on one of its own, the wall time is at most this."""
    if name.startswith("long"):
        return "ok" if status == 0 and peak < EDGE_BYTES else "FAIL"
    if status == 2 and seconds < REFUSED_SECONDS and peak < REFUSED_BYTES \
            and not name.startswith("edge"):
        return "ok"
    if status == 0 and seconds < DONE_SECONDS and peak < EDGE_BYTES:
        return "ok"
    return "FAIL"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--python", default=sys.executable)
    parser.add_argument("--only", help="only the files or options whose name has this")
    parser.add_argument("--limit", type=float, default=60.0)
    args = parser.parse_args()
    rows = []
    with tempfile.TemporaryDirectory(prefix="biceps-bad-") as folder:
        folder = Path(folder)
        jobs = []
        for number, (name, make) in enumerate(FILES.items()):
            if args.only and args.only not in name:
                continue
            path = folder / f"file{number}.toml"
            path.write_text(make())
            for command, argv in COMMANDS.items():
                jobs.append((name, command, argv))
        for name, argv in OPTIONS.items():
            if not args.only or args.only in name:
                jobs.append((name, argv[0], lambda path, out, argv=argv: [
                    part.replace("{out}", str(out)) for part in argv]))
        for name, command, argv in jobs:
            out = folder / "out"
            out.mkdir(exist_ok=True)
            path = folder / f"file{list(FILES).index(name)}.toml" if name in FILES else None
            status, seconds, cpu, peak, last = run(args.python, argv(path, out), args.limit)
            for made in out.iterdir():
                made.unlink()
            rows.append((name, command, status, seconds, cpu, peak, last))
            shown = "killed" if status is None else str(status)
            print(f"{verdict(name, status, cpu, peak):<5}{name[:40]:<41}{command:<12}"
                  f"{shown:>6}{seconds:>7.1f} s{cpu:>7.1f} s{peak / (1 << 20):>7.0f} MB  "
                  f"{last[:100]}", flush=True)
    failed = sum(verdict(row[0], row[2], row[4], row[5]) != "ok" for row in rows)
    print(f"\n{len(rows)} runs (status, wall and CPU seconds, peak memory), {failed} outside "
          f"the goal; load average {os.getloadavg()[0]:.1f}. The worst of each kind:")
    for kind, rows_of_kind in kinds(rows).items():
        if rows_of_kind:
            most_cpu = max(rows_of_kind, key=lambda row: row[4])
            most_wall = max(rows_of_kind, key=lambda row: row[3])
            most_memory = max(rows_of_kind, key=lambda row: row[5])
            print(f"{kind} ({len(rows_of_kind)} runs): the most CPU {most_cpu[4]:.1f} s "
                  f"({most_cpu[0]}, {most_cpu[1]}); the most wall time {most_wall[3]:.1f} s "
                  f"({most_wall[0]}, {most_wall[1]}); the most memory "
                  f"{most_memory[5] / (1 << 20):.0f} MB ({most_memory[0]}, {most_memory[1]})")


def kinds(rows: list[tuple]) -> dict[str, list[tuple]]:
    """The runs by what each must do: refused, finished, an edge finished, long work; and
    those that did neither (killed, or another status)."""
    grouped: dict[str, list[tuple]] = {"refused (exit 2)": [], "accepted and finished": [],
                                       "edges": [], "long work": [], "neither": []}
    for row in rows:
        name, status = row[0], row[2]
        if name.startswith("edge"):
            grouped["edges"].append(row)
        elif name.startswith("long"):
            grouped["long work"].append(row)
        elif status == 2:
            grouped["refused (exit 2)"].append(row)
        elif status == 0:
            grouped["accepted and finished"].append(row)
        else:
            grouped["neither"].append(row)
    return grouped

if __name__ == "__main__":
    main()
