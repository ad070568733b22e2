"""``rse.check`` from Python: the same verdicts and faults as
``rse-gen check --json`` on the same folders, typed for matching."""

import json
import subprocess
from pathlib import Path

import pytest
import rse
from conftest import SCHEMES, rse_gen_path


def write(out: Path, amount: int = 3) -> Path:
    scheme = rse.Scheme.load(SCHEMES / "six_obstacles.csv")
    rse.write_worlds(scheme, out, amount=amount, targets="obj,gazebo,mujoco,urdf")
    return out


def cli_report(*paths: Path) -> dict:
    done = subprocess.run(
        [str(rse_gen_path()), "check", "--json", *map(str, paths)],
        capture_output=True,
        text=True,
    )
    assert done.returncode in (0, 1), done.stderr
    return json.loads(done.stdout)


def test_a_good_batch_and_one_world_are_ok(tmp_path: Path) -> None:
    batch = write(tmp_path / "b")
    report = rse.check(batch)
    assert report.ok and bool(report)
    assert (report.checked, report.failed) == (3, 0)
    assert all(w.ok and w.faults == [] and w.hashed_only == [] for w in report.worlds)
    assert [w.index for w in report.worlds] == [0, 1, 2]
    one = rse.check(batch / "world_0001")
    assert one.checked == 1 and one.ok


def test_a_damaged_world_gives_typed_faults_as_the_cli_does(tmp_path: Path) -> None:
    batch = write(tmp_path / "b")
    heightmap = batch / "world_0002" / "heightmap.csv"
    lines = heightmap.read_text().splitlines()
    cells = lines[3].split(",")
    cells[5] = str(int(cells[5]) + 1)
    lines[3] = ",".join(cells)
    heightmap.write_text("\n".join(lines) + "\n")
    (batch / "world_0000" / "mujoco" / "extra.txt").write_text("x")

    report = rse.check(batch)
    assert not report.ok and report.failed == 2
    bad = {Path(w.world).name: w for w in report.worlds if not w.ok}
    height = [f for f in bad["world_0002"].faults if f.kind == "height_differs"]
    assert len(height) == 1
    assert height[0].file == "heightmap.csv"
    assert (height[0].details["x"], height[0].details["y"]) == (5, 3)
    assert height[0].details["found"] == height[0].details["expected"] + 1
    assert [f.kind for f in bad["world_0000"].faults] == ["unexpected"]
    assert str(bad["world_0000"].faults[0]) == (
        "mujoco/extra.txt: not a file of the world regenerated from rse.json"
    )

    cli = cli_report(batch)
    assert (cli["checked"], cli["failed"]) == (report.checked, report.failed)
    for ours, theirs in zip(report.worlds, cli["worlds"]):
        assert [(f.kind, f.file, f.message) for f in ours.faults] == [
            (f["kind"], f.get("file"), f["message"]) for f in theirs["faults"]
        ]


def test_physics_reports_the_smoke_test(tmp_path: Path) -> None:
    batch = write(tmp_path / "b", amount=1)
    report = rse.check(batch, physics=True)
    assert report.ok, [str(f) for w in report.worlds for f in w.faults]
    # obj and gazebo collide the mesh (one file's bytes, tested once), mujoco
    # and urdf (auto: boxes) the box set: each exact collider is tested.
    physics = report.worlds[0].physics
    assert [p["collider"] for p in physics] == [
        "mesh gazebo/rse_terrain/meshes/terrain.obj",
        "boxes",
    ]
    assert all(p["bodies"] == 20 and p["errors"] == [] for p in physics)


def test_batch_faults_and_bad_paths(tmp_path: Path) -> None:
    batch = write(tmp_path / "b", amount=1)
    (batch / ".world_0001.tmp-4242").mkdir()
    report = rse.check(batch)
    assert [f.kind for f in report.batch_faults] == ["leftover"]
    assert not report.ok and report.failed == 0
    with pytest.raises(NotADirectoryError, match="is not a folder"):
        rse.check(tmp_path / "nowhere")
    (tmp_path / "empty").mkdir()
    with pytest.raises(ValueError, match="holds no world"):
        rse.check(tmp_path / "empty")


def test_one_default_seed_everywhere(tmp_path: Path) -> None:
    """A scheme's `# seed:` is the default of the CLI and of every Python
    call alike (Scheme.generate and generate_batch once ignored it)."""
    text = (SCHEMES / "six_obstacles.csv").read_text()
    path = tmp_path / "seeded.csv"
    path.write_text("# seed: 7\n" + text)
    scheme = rse.Scheme.load(path)
    cli = subprocess.run(
        [str(rse_gen_path()), "heightmap", str(path), "--index", "2"],
        capture_output=True,
        text=True,
        check=True,
    ).stdout
    cli_heights = [[int(v) for v in line.split(",")] for line in cli.splitlines()]
    assert scheme.generate(index=2).heights.tolist() == cli_heights
    assert scheme.generate(seed=7, index=2).heights.tolist() == cli_heights
    assert scheme.generate(seed=0, index=2).heights.tolist() != cli_heights
    assert rse.generate_batch(scheme, 3)[2].heights.tolist() == cli_heights
    rse.write_worlds(scheme, tmp_path / "w", amount=3, targets="obj")
    written = (tmp_path / "w" / "world_0002" / "heightmap.csv").read_text()
    assert [
        [int(v) for v in line.split(",")] for line in written.splitlines()
    ] == cli_heights


@pytest.mark.parametrize("budget", [0, -1.0, float("nan"), float("inf")])
def test_a_bad_budget_is_refused_by_the_library_rule(
    tmp_path: Path, budget: float
) -> None:
    """The same rule and words as `rse-gen check --budget` (rse-verify's
    `Budget`); `None` is the default budget."""
    out = write(tmp_path / "batch", amount=1)
    with pytest.raises(ValueError, match=r"budget: `.*` is not a number above 0"):
        rse.check(out, budget=budget)
    assert rse.check(out, budget=None).ok


def test_files_check_can_only_hash_are_hashed_as_they_stream(tmp_path: Path) -> None:
    """A manifest that claims custom templates may list any number of files
    `check` can only hash, each up to the rendered-file cap: they were read
    whole and held together (16 of 60 MB: a gigabyte). Now each is hashed as
    it streams: the peak memory of `rse-gen check` stays far below their sum."""
    import hashlib
    import sys

    batch = tmp_path / "b"
    rse.write_worlds(
        rse.Scheme.from_csv("# size: 20x16\ntype,height\nrandom,2\n"),
        batch,
        amount=1,
        targets="obj",
    )
    world = batch / "world_0000"
    manifest = json.loads((world / "rse.json").read_text())
    manifest["templates"] = "custom"
    size = 60 << 20
    digest = hashlib.sha256(bytes(size)).hexdigest()
    (world / "extra").mkdir()
    for i in range(16):
        with open(world / "extra" / f"big_{i:02}.bin", "wb") as f:
            f.truncate(size)  # sparse: no disk used
        manifest["files"][f"extra/big_{i:02}.bin"] = digest
    # As the generator writes it (sorted file list, two-space indent): rse.json is rebuilt byte for byte.
    manifest["files"] = dict(sorted(manifest["files"].items()))
    (world / "rse.json").write_text(json.dumps(manifest, indent=2) + "\n")
    script = (
        "import resource, subprocess, sys\n"
        "done = subprocess.run(sys.argv[1:], capture_output=True, text=True)\n"
        "print(done.returncode, resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)\n"
        "print(done.stdout + done.stderr)\n"
    )
    done = subprocess.run(
        [sys.executable, "-c", script, str(rse_gen_path()), "check", str(world)],
        capture_output=True,
        text=True,
        timeout=300,
    )
    first, said = done.stdout.split("\n", 1)
    code, peak_kib = map(int, first.split())
    assert code == 0, said
    assert "1 good (1 only by hash)" in said, said
    assert peak_kib < 300 << 10, (
        f"check peaked at {peak_kib >> 10} MiB for 16 files of 60 MiB"
    )
