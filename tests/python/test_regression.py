"""Regressions of the Python package, found by the hardening rounds: Python
never aborts the interpreter. Every allocation sized by a caller's number is estimated and refused first,
naming the argument; one `EnvTerrains` shared by threads raises a clear
error instead of pyo3's borrow error; arrays changed in place (their dtype
set anew) are refused, not read past their end."""

from __future__ import annotations

import threading
import warnings

import numpy as np
import pytest
import rse

TINY = rse.Scheme.from_csv("# size: 2x2\ntype,height\nrandom,0..3\n")


def available_bytes() -> int:
    with open("/proc/meminfo") as f:
        for line in f:
            if line.startswith("MemAvailable:"):
                return int(line.split()[1]) * 1024
    raise AssertionError("no MemAvailable")


def test_a_pool_larger_than_memory_is_a_memory_error_naming_num_envs() -> None:
    # 10**8 envs of a 2x2 scheme: 3.6 GB of samples, and a terrain each
    # (some 35 GB in all); this aborted the interpreter with a failed
    # 15 GB allocation. On a machine with that much free it would be built.
    if available_bytes() > 40 << 30:
        pytest.skip("this machine has the memory the pool needs")
    with pytest.raises(MemoryError, match=r"^num_envs: a pool of 100000000 environments"):
        rse.EnvTerrains(TINY, 10**8, oversample=1)
    # Past what any machine has: refused by its shape, as a ValueError.
    with pytest.raises(ValueError, match="^num_envs"):
        rse.EnvTerrains(TINY, 10**10, oversample=1)
    # The interpreter goes on, and a small pool still works.
    assert rse.EnvTerrains(TINY, 4).samples.shape[0] == 4


def test_other_counts_are_estimated_before_they_are_allocated() -> None:
    if available_bytes() > 100 << 30:
        pytest.skip("this machine has the memory asked for")
    with pytest.raises(MemoryError, match=r"^amount: 1000000000000 terrains"):
        rse.generate_batch(TINY, 10**12)
    # No row past one a cell: a huge n asks for no more than the terrain holds.
    terrain = TINY.generate()
    cells = terrain.heights.size
    assert terrain.flat_patches(4_000_000_000).shape == (cells, 3)
    assert terrain.flat_patches(2).shape == (2, 3)


@pytest.mark.parametrize(
    ("name", "dtype"),
    [("difficulty", np.float32), ("samples", np.float16), ("origins", np.int8), ("episode", np.int32)],
)
def test_arrays_changed_in_place_are_refused_naming_them(name: str, dtype: type) -> None:
    envs = rse.EnvTerrains(TINY, 4)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)
        # The same bytes read as another type: float64 difficulties as
        # twice as many float32 (read as float64, past the array's end).
        getattr(envs, name).dtype = dtype
    with pytest.raises(ValueError, match=rf"^{name}: the array was changed in place"):
        envs.reset([0])
    # Refused before anything changed: env 0 is still at episode 0.
    fresh = rse.EnvTerrains(TINY, 4)
    assert np.array_equal(envs.terrain(0).heights, fresh.terrain(0).heights)
    if name == "difficulty":
        with pytest.raises(ValueError, match="^difficulty"):
            envs.difficulty = [0.5] * 4
    # Untouched arrays still reset.
    fresh.reset([1, 2])
    assert fresh.episode.tolist() == [0, 1, 1, 0]


def test_threads_sharing_a_pool_get_a_clear_error_never_a_borrow_error() -> None:
    scheme = rse.Scheme.load("schemes/six_obstacles.csv")
    envs = rse.EnvTerrains(scheme, 256, oversample=2)
    points = np.zeros((256, 64, 2))
    errors: list[BaseException] = []
    resets = 0
    stop = threading.Event()

    def resetting() -> None:
        nonlocal resets
        while not stop.is_set():
            try:
                envs.reset(np.arange(256))
                resets += 1
            except BaseException as e:  # noqa: BLE001 - every kind is checked below
                errors.append(e)

    worker = threading.Thread(target=resetting)
    worker.start()
    try:
        for _ in range(400):
            try:
                envs.heights_at(np.arange(256), points)
                envs.terrain(3)
            except BaseException as e:  # noqa: BLE001
                errors.append(e)
    finally:
        stop.set()
        worker.join()
    assert errors, "the calls never met: nothing tested"
    for e in errors:
        assert isinstance(e, RuntimeError), repr(e)
        assert "another thread is using this object" in str(e), str(e)
    # Every reset that returned counted its episode, whole.
    assert envs.episode.tolist() == [resets] * 256


def test_check_of_a_folder_chain_thousands_deep_is_a_fault_not_a_segfault(tmp_path) -> None:
    # A 6000-level chain inside a world overflowed the stack: the command
    # line exited 134 and `rse.check` took the interpreter down with it.
    rse.write_worlds(TINY, tmp_path / "out", amount=1, targets=["obj"])
    deep = tmp_path / "out" / "world_0000"
    made = 0
    while made < 6000:
        try:
            (deep / "d").mkdir()
        except OSError:
            break  # PATH_MAX reached: deep enough
        deep = deep / "d"
        made += 1
    try:
        assert made > 1000
        report = rse.check(tmp_path / "out")
        assert not report.ok
        said = " ".join(f.message for w in report.worlds for f in w.faults)
        assert "folders deep: not listed" in said, said
    finally:
        # Removed here, deepest first: pytest's own clean-up of old temporary
        # folders (shutil.rmtree) recurses once a level, and would overflow.
        for _ in range(made):
            deep.rmdir()
            deep = deep.parent
