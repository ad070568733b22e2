"""`check`'s rebuild estimate beside what the rebuild measures: peak memory
(the process's maximum resident set) and time (CPU seconds, user + system,
of `rse-gen check` on the one world) over a table of ordinary and hostile
worlds, each built here. The estimate is what `check --json` reports it held
to the budget before rebuilding; the aim is each within 2x of what it
measures.

Usage: python bench/budget.py [--quick] [--only TEXT] [--rse-gen PATH]   (run by `make bench`)
"""

from __future__ import annotations

import argparse
import hashlib
import json
import os
import resource
import subprocess
import sys
import tempfile
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
ALL = "obj,gazebo,webots,mujoco,urdf,usd"


def scheme(folder: Path, name: str, text: str) -> str:
    path = folder / f"{name}.csv"
    path.write_text(text)
    return str(path)


def worlds(folder: Path, quick: bool) -> list[tuple[str, list[str], str]]:
    """(name, rse-gen arguments that write it, the world folder and any
    flags of `check` after it)."""
    many = "# size: 10x10\ntype,height\n" + "random,1\n" * 200_000
    # Each row builds a table of up to 65,535 odds, every one an erfc (a wide
    # sigma): once priced like 4 cells, it ran 100 times its estimate. Rows
    # alike share one table, priced once.
    head = "# size: 2x2\n# step_height: 0.001\ntype,height,sigma\n"
    tables = head + "".join(f"gaussian,{65535 - i},10000\n" for i in range(400))
    shared = head + "gaussian,65535,10000\n" * 40_000
    table = [
        ("six_obstacles 50x50", ["batch", str(REPO / "schemes/six_obstacles.csv"), "--amount", "1", "--target", ALL], "world_0000"),
        ("nist_hill", ["batch", str(REPO / "schemes/nist_hill.csv"), "--amount", "1", "--target", ALL], "world_0000"),
        ("random,4 300x300", ["batch", scheme(folder, "r4", "# size: 300x300\ntype,height\nrandom,4\n"), "--amount", "1", "--target", ALL], "world_0000"),
        ("random,1000 300x300", ["batch", scheme(folder, "r1000", "# size: 300x300\ntype,height\nrandom,1000\n"), "--amount", "1", "--target", ALL], "world_0000"),
        ("random,4 300x300 blocks", ["batch", scheme(folder, "r4b", "# size: 300x300\ntype,height\nrandom,4\n"), "--amount", "1", "--target", ALL, "--mesh", "blocks"], "world_0000"),
        ("hfield k=1158 on 10x10", ["batch", scheme(folder, "hf", "# size: 10x10\ntype,height\nrandom,3\n"), "--amount", "1", "--target", "mujoco", "--mujoco-collider", "hfield", "--oversample", "1158"], "world_0000"),
        ("200k obstacles on 10x10", ["batch", scheme(folder, "many", many), "--amount", "1", "--target", ALL], "world_0000"),
        ("400 gaussian tables of ~65535 on 2x2", ["batch", scheme(folder, "tables", tables), "--amount", "1", "--target", "obj"], "world_0000"),
        ("40000 gaussian rows sharing a table", ["batch", scheme(folder, "shared", shared), "--amount", "1", "--target", "obj"], "world_0000"),
        ("atlas flat 2x2 of 500x500, 10^6 patches", ["atlas", scheme(folder, "flat", "# size: 500x500\ntype,height\n"), "--rows", "2", "--cols", "2", "--flat-patches", "1000000", "--target", ALL], "atlas"),
        ("atlas nist_hill 10x10, 10^6 patches", ["atlas", str(REPO / "schemes/nist_hill.csv"), "--rows", "10", "--cols", "10", "--flat-patches", "1000000", "--target", ALL], "atlas"),
    ]
    # A world whose mesh was replaced by a hostile OBJ of the same size: a
    # file that differs is not examined further (parsing one cost 15-36 s
    # against an estimate of 1-2 s), so check costs what the rebuild does.
    table.append(
        ("random,4 300x300, its OBJ a same-size bomb", ["batch", scheme(folder, "r4f", "# size: 300x300\ntype,height\nrandom,4\n"), "--amount", "1", "--target", "obj"], "world_0000 !bomb"),
    )
    # The physics smoke test, priced with the rebuild (`check --physics`).
    table += [
        ("physics: six_obstacles, mesh and boxes", ["batch", str(REPO / "schemes/six_obstacles.csv"), "--amount", "1", "--target", "obj,urdf"], "world_0000 --physics"),
        ("physics: random,4 300x300, mesh and boxes", ["batch", scheme(folder, "r4p", "# size: 300x300\ntype,height\nrandom,4\n"), "--amount", "1", "--target", "obj,urdf"], "world_0000 --physics"),
    ]
    # The fifth round: fresh worlds check once failed, and costs it paid
    # unpriced (the mesh MuJoCo and Gazebo classic draw over their boxes,
    # physics on small blocks, files it can only hash, their references).
    wall = "# size: 9x1000\ntype,height,angle,x1,y1,x2,y2\nrandom,1,,,,,\nwall,600,90,4,0,4,999\n"
    r1000 = scheme(folder, "r1000b", "# size: 300x300\ntype,height\nrandom,1000\n")
    table += [
        ("tall wall on 9x1000", ["batch", scheme(folder, "wall", wall), "--amount", "1", "--target", "obj"], "world_0000"),
        ("strip 1x200000 random,1", ["batch", scheme(folder, "strip", "# size: 1x200000\ntype,height\nrandom,1\n"), "--amount", "1", "--target", "obj"], "world_0000"),
        ("random,1000 300x300 mujoco (drawn mesh)", ["batch", r1000, "--amount", "1", "--target", "mujoco"], "world_0000"),
        ("random,1000 300x300 gazebo-classic", ["batch", r1000, "--amount", "1", "--target", "gazebo-classic"], "world_0000"),
        ("physics: 60x60 of 1 cm blocks", ["batch", scheme(folder, "p1", "# size: 60x60\n# block_size: 0.01\ntype,height\nrandom,1\n"), "--amount", "1", "--target", "obj,urdf"], "world_0000 --physics"),
        ("physics: 60x60 of 2 cm blocks", ["batch", scheme(folder, "p2", "# size: 60x60\n# block_size: 0.02\ntype,height\nrandom,1\n"), "--amount", "1", "--target", "obj,urdf"], "world_0000 --physics"),
        # Ramps: a height field writes each ramp's samples again, over its
        # plane (200 ramps over the whole grid).
        ("200 ramps over 300x300, hfield k=4", ["batch", scheme(folder, "ramps", "# size: 300x300\ntype,height,angle,x1,y1,x2,y2\n" + "ramp,20,,0,0,299,299\n" * 200), "--amount", "1", "--target", "mujoco", "--mujoco-collider", "hfield", "--oversample", "4"], "world_0000"),
        # The sixth round: physics priced from the models' triangles and
        # boxes, not per cell (this world was priced 37x over).
        ("physics: flat 1000x1000 of 1 cm blocks", ["batch", scheme(folder, "pflat", "# size: 1000x1000\n# block_size: 0.01\n# base: 0.01\ntype,height\nrandom,0\n"), "--amount", "1", "--target", "obj,urdf"], "world_0000 --physics"),
        ("hashed only: 4 sparse files of 400 MB", ["batch", scheme(folder, "r4s", "# size: 300x300\ntype,height\nrandom,4\n"), "--amount", "1", "--target", "obj"], "world_0000 !sparse"),
        ("hashed only: a 60 MiB MJCF of references", ["batch", scheme(folder, "r4x", "# size: 300x300\ntype,height\nrandom,4\n"), "--amount", "1", "--target", "mujoco"], "world_0000 !references"),
        ("4000 unlisted long-named files, 15 deep", ["batch", str(REPO / "schemes/six_obstacles.csv"), "--amount", "1", "--target", "obj"], "world_0000 !files"),
    ]
    # A cone: every level a thin ring inside a wide disk, the box cover's
    # worst shape (it once grew as R^3.5 and went unpriced: 155 s at R=500).
    cone = "# size: {0}x{0}\ntype,height,angle,x1,y1\npeak,{1},45,{1},{1}\n"
    table += [
        ("cone R=300 on 600x600 mujoco", ["batch", scheme(folder, "cone300", cone.format(600, 300)), "--amount", "1", "--target", "mujoco"], "world_0000"),
        ("cone R=500 on 1000x1000 obj", ["batch", scheme(folder, "cone500", cone.format(1000, 500)), "--amount", "1", "--target", "obj"], "world_0000"),
    ]
    # A user's template looping over the boxes (check --template renders
    # it; it is priced at its fuel, which it nearly spends).
    looping = folder / "looping" / "urdf"
    looping.mkdir(parents=True)
    (looping / "extra.txt.j2").write_text("{% for b in boxes %}{% for i in range(40) %}{% endfor %}{% endfor %}done\n")
    table.append(
        ("a user's template looping 40x a box", ["batch", scheme(folder, "r4t", "# size: 300x300\ntype,height\nrandom,4\n"), "--amount", "1", "--target", "urdf", "--template", str(looping.parent)], f"world_0000 --template {looping.parent} !fuel"),
    )
    # The sixth round: what a user's templates cost beyond their loops.
    # Nested replaces build a 100 MB string inside the fuel (once priced
    # 8 MiB, peaking at 231 MiB); a file copied as it is (not `.j2`); a
    # copied MJCF naming 65,000 files by 880-byte paths (none there: the
    # world fails; its references are read all the same).
    replacing = folder / "replacing" / "urdf"
    replacing.mkdir(parents=True)
    nested = "{% set s = 'aaaaaaaaaa' %}" + "{% set s = s|replace('a', 'aaaaaaaaaa') %}" * 7 + "{{ s|length }}\n"
    (replacing / "extra.txt.j2").write_text(nested)
    verbatim = folder / "verbatim" / "urdf"
    verbatim.mkdir(parents=True)
    with (verbatim / "big.bin").open("wb") as f:
        f.write(b"\1" * (200 << 20))
    naming = folder / "naming" / "mujoco"
    naming.mkdir(parents=True)
    (naming / "extra.xml").write_text(long_references())
    r4 = scheme(folder, "r4u", "# size: 300x300\ntype,height\nrandom,4\n")
    for name, templates, target, marks in [
        ("a user's template: nested replaces, 100 MB", replacing.parent, "urdf", " !fuel"),
        ("a user's file copied as is, 200 MB", verbatim.parent, "urdf", ""),
        ("a user's MJCF of 65,000 880-byte paths", naming.parent, "mujoco", " !fails"),
    ]:
        table.append((name, ["batch", r4, "--amount", "1", "--target", target, "--template", str(templates)], f"world_0000 --template {templates}{marks}"))
    table.append(
        ("hashed only: 65,000 880-byte paths", ["batch", scheme(folder, "r4l", "# size: 300x300\ntype,height\nrandom,4\n"), "--amount", "1", "--target", "mujoco"], "world_0000 !long_references"),
    )
    if not quick:
        table.append(
            ("random,4 1000x1000", ["batch", scheme(folder, "r4k", "# size: 1000x1000\ntype,height\nrandom,4\n"), "--amount", "1", "--target", ALL], "world_0000"),
        )
    return table


def plant_bomb(world: Path) -> None:
    """Replaces the world's mesh by `o a / f 1 2 3` lines, as long as it."""
    obj = world / "meshes/terrain.obj"
    size = obj.stat().st_size
    obj.write_bytes((b"o a\nf 1 2 3\n" * (size // 12 + 1))[:size])


def list_hashed_only(world: Path, files: dict[str, Path]) -> None:
    """Marks the world as rendered from a user's templates (its files are
    then compared by hash alone) and lists `files` in its rse.json with
    their true SHA-256, as a world whose templates wrote them would."""
    manifest_path = world / "rse.json"
    manifest = json.loads(manifest_path.read_text())
    manifest["templates"] = "custom"
    for name, path in files.items():
        digest = hashlib.sha256()
        with path.open("rb") as f:
            while chunk := f.read(1 << 22):
                digest.update(chunk)
        manifest["files"][name] = digest.hexdigest()
    # As rse writes it: files sorted by path, text as is.
    manifest["files"] = dict(sorted(manifest["files"].items()))
    manifest_path.write_text(json.dumps(manifest, indent=2, ensure_ascii=False) + "\n")


def plant_sparse(world: Path) -> None:
    """Four sparse files of 400 MB of zeros (nothing on disk), listed."""
    (world / "extra").mkdir()
    files = {}
    for i in range(4):
        path = world / "extra" / f"f{i}.bin"
        with path.open("wb") as f:
            f.truncate(400 << 20)
        files[f"extra/f{i}.bin"] = path
    list_hashed_only(world, files)


def plant_many_files(world: Path) -> None:
    """4000 empty files of 200-byte names, 15 folders deep: files rse.json
    does not list (each a fault; the report stops at 100), under the
    listing's cap of 4096 entries."""
    deep = world / "/".join(["d" * 16] * 15)
    deep.mkdir(parents=True)
    for i in range(4000):
        (deep / f"{i:04d}{'n' * 196}").touch()


def long_references() -> str:
    """An MJCF naming 65,000 files (under the cap of 65,536) by paths of
    880 bytes, ten folders deep."""
    deep = "/".join(["d" * 86] * 10)
    return "<mujoco>" + "".join(f'<a file="{deep}/{i:05d}.obj"/>' for i in range(65_000)) + "</mujoco>"


def plant_long_references(world: Path) -> None:
    """[long_references] as a file only hashed, listed: the files it names
    are not there, so the world fails (after reading every reference)."""
    path = world / "mujoco" / "extra.xml"
    path.write_text(long_references())
    list_hashed_only(world, {"mujoco/extra.xml": path})


def plant_references(world: Path) -> None:
    """A 60 MiB MJCF naming 3.5 million files, listed: more than a world
    file may name, so the world fails (its estimate is a bound)."""
    path = world / "mujoco" / "extra.xml"
    path.write_text("<mujoco>" + '<a file="x.obj"/>' * (60 * 2**20 // 17) + "</mujoco>")
    list_hashed_only(world, {"mujoco/extra.xml": path})


def repeated_cpu(command: list[str], once: float) -> float:
    """CPU seconds of `command`, averaged over enough runs to fill half a
    second when one run (`once`) is short: /usr/bin/time counts in 10 ms
    ticks, so a check of 20 ms read as 0.01-0.03 s."""
    if once >= 0.2:
        return once
    runs = min(20, max(2, int(0.5 / max(once, 0.01))))
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    for _ in range(runs):
        subprocess.run(command, capture_output=True, check=False)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime) / runs


def measure(rse_gen: str, world: Path, flags: list[str], fails: bool = False) -> tuple[dict, int, float]:
    """The estimate check reports, its peak resident bytes and CPU seconds
    (`fails`: the world is meant to fail)."""
    timing = world.parent / "time.txt"
    command = [rse_gen, "check", str(world), "--json", "--budget", "1000", *flags]
    done = subprocess.run(["/usr/bin/time", "-o", str(timing), "-f", "%M %U %S", *command], capture_output=True, text=True)
    report = json.loads(done.stdout)["worlds"][0]
    if report["ok"] == fails:
        sys.exit(f"{world}: check {'passed' if fails else 'failed'}: {report['faults']}")
    kib, user, system = timing.read_text().split()[-3:]
    return report["estimate"], int(kib) * 1024, repeated_cpu(command, float(user) + float(system))


def curriculum_rows(folder: Path) -> list[tuple[str, list[str]]]:
    """(name, rse-gen check-curriculum arguments)."""
    gentle = "# size: 1000x1000\ntype,height,angle,x1,y1\n" + "".join(f"peak,1000,1,{i * 17 % 1000},{i * 31 % 1000}\n" for i in range(200))
    return [
        ("check-curriculum six_obstacles 10x50", [str(REPO / "schemes/six_obstacles.csv"), "--levels", "10", "--draws", "50"]),
        ("check-curriculum random,4 300x300 10x10", [scheme(folder, "cr4", "# size: 300x300\ntype,height\nrandom,4\n"), "--levels", "10", "--draws", "10"]),
        ("check-curriculum nist_hill 50x100", [str(REPO / "schemes/nist_hill.csv"), "--levels", "50", "--draws", "100"]),
        # The sixth round: 200 gentle peaks, each over the whole grid.
        ("check-curriculum 200 gentle peaks 1000x1000", [scheme(folder, "gentle", gentle), "--levels", "2", "--draws", "2"]),
    ]


def measure_curriculum(rse_gen: str, folder: Path, arguments: list[str]) -> tuple[float, float]:
    """The seconds check-curriculum's refusal prices (under a budget too
    small for anything), and the CPU seconds the check takes."""
    refused = subprocess.run([rse_gen, "check-curriculum", *arguments, "--budget", "1e-12"], capture_output=True, text=True)
    words = refused.stderr.split("would take some ", 1)
    if refused.returncode != 2 or len(words) != 2:
        sys.exit(f"check-curriculum was not refused: {refused.stderr}")
    estimate = float(words[1].split()[0])
    timing = folder / "time.txt"
    command = [rse_gen, "check-curriculum", *arguments]
    subprocess.run(["/usr/bin/time", "-o", str(timing), "-f", "%U %S", *command], check=True, capture_output=True)
    user, system = timing.read_text().split()[-2:]
    return estimate, repeated_cpu(command, float(user) + float(system))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="leave out the 1000x1000 world (a minute)")
    parser.add_argument("--only", default="", help="run only the worlds whose name holds TEXT")
    parser.add_argument("--rse-gen", default=str(REPO / "target/release/rse-gen"))
    args = parser.parse_args()
    if not os.access("/usr/bin/time", os.X_OK):
        sys.exit("bench/budget.py needs /usr/bin/time (Debian: apt-get install time)")
    print("check's estimate (before the rebuild) beside what it measures; aim: each within 2x")
    print(f"{'world':42} {'est MiB':>8} {'peak MiB':>9} {'ratio':>6}   {'est s':>7} {'cpu s':>7} {'ratio':>6}")
    worst = 1.0
    with tempfile.TemporaryDirectory() as tmp:
        for i, (name, command, inside) in enumerate(worlds(Path(tmp), args.quick)):
            if args.only not in name:
                continue
            out = Path(tmp) / f"w{i}"
            target = out / "atlas" if command[0] == "atlas" else out
            subprocess.run([args.rse_gen, *command, "-o", str(target)], check=True, capture_output=True)
            inside, *flags = inside.split()
            world = out / inside
            planted = {
                "!bomb": plant_bomb,
                "!sparse": plant_sparse,
                "!references": plant_references,
                "!long_references": plant_long_references,
                "!files": plant_many_files,
            }
            fails = "!fails" in flags
            fuel = "!fuel" in flags
            flags = [flag for flag in flags if flag not in ("!fails", "!fuel")]
            for mark, plant in planted.items():
                if mark in flags:
                    flags.remove(mark)
                    plant(world)
                    # A bomb and a file naming too many (or missing) files fail check.
                    fails = mark != "!sparse"
            estimate, peak, seconds = measure(args.rse_gen, world, flags, fails=fails)
            memory = estimate["bytes"] / peak
            time = estimate["seconds"] / max(seconds, 0.01)
            if fails:
                # A world that fails is examined less than priced: its
                # estimate is a bound from above, held to at most 2x below.
                worst = max(worst, 1 / memory, 1 / time)
            elif fuel:
                # A user's template is priced at its fuel, which pays for an
                # instruction or 64 bytes alike: what it will spend on which
                # is known only once it has run. Its memory is that bound.
                worst = max(worst, 1 / memory, time, 1 / time)
            else:
                worst = max(worst, memory, 1 / memory, time, 1 / time)
            print(
                f"{name:42} {estimate['bytes'] / 2**20:8.1f} {peak / 2**20:9.1f} {memory:6.2f}   "
                f"{estimate['seconds']:7.2f} {seconds:7.2f} {time:6.2f}"
                + ("   (fails: a bound from above)" if fails else "")
                + ("   (memory: its fuel's bound)" if fuel else "")
            )
            subprocess.run(["rm", "-rf", str(out)], check=True)
        for name, arguments in curriculum_rows(Path(tmp)):
            if args.only not in name:
                continue
            estimate, seconds = measure_curriculum(args.rse_gen, Path(tmp), arguments)
            time = estimate / max(seconds, 0.01)
            worst = max(worst, time, 1 / time)
            print(f"{name:42} {'-':>8} {'-':>9} {'-':>6}   {estimate:7.2f} {seconds:7.2f} {time:6.2f}")
    print(
        f"worst ratio either way: {worst:.2f} (aim: at most 2; a failing world, and a user's template's memory, "
        "may cost less than its estimate, never more)"
    )


if __name__ == "__main__":
    main()
