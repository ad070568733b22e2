"""`rse.ray` on a real Ray cluster of two nodes on this machine (Ray's own
`cluster_utils.Cluster`: a head and a worker node, each its own raylet;
make test-cluster, .venv-cluster): the shards as Ray tasks give the tree
one run gives, byte for byte; a worker killed mid-shard is retried by Ray
and the tree is still that tree. The cluster is started and stopped here."""

from __future__ import annotations

import os
import signal
import threading
import time
from pathlib import Path

import pytest
import ray
import rse
import rse.ray
from ray.cluster_utils import Cluster
from ray.util.state import list_tasks

SCHEMES = Path(__file__).resolve().parents[2] / "schemes"
TARGETS = "obj,gazebo,mujoco,urdf"


def shard_tasks(count: int) -> list:
    """The `_write_shard` tasks Ray's state API reports, once it reports
    `count` of them finished (task events reach it a moment after the
    tasks end)."""
    deadline = time.monotonic() + 60
    while True:
        tasks = list_tasks(filters=[("func_or_class_name", "=", "_write_shard")], limit=1000, detail=True)
        if sum(t.state == "FINISHED" and t.node_id is not None for t in tasks) >= count:
            return tasks
        assert time.monotonic() < deadline, f"Ray reports {tasks}"
        time.sleep(0.5)


def tree(root: Path) -> dict[str, bytes]:
    return {str(p.relative_to(root)): p.read_bytes() for p in sorted(root.rglob("*")) if p.is_file()}


@pytest.fixture(scope="module")
def cluster():
    nodes = Cluster(initialize_head=True, head_node_args={"num_cpus": 1})
    nodes.add_node(num_cpus=1)
    ray.init(address=nodes.address, log_to_driver=False)
    nodes.wait_for_nodes()
    assert len([n for n in ray.nodes() if n["Alive"]]) == 2, "two nodes"
    # A worker process on each node first, as on a cluster that has run
    # anything: a node's first worker takes a second or two to start, and
    # this test's shards take less, so Ray would give them all to the other.
    @ray.remote(num_cpus=1)
    def node() -> str:
        time.sleep(1.0)  # one CPU a node: the second task must go to the other node
        return ray.get_runtime_context().get_node_id()

    assert len(set(ray.get([node.remote() for _ in range(2)]))) == 2, "a worker on each node"
    yield nodes
    ray.shutdown()
    nodes.shutdown()


def test_shards_as_ray_tasks_give_the_tree_of_one_run(cluster, tmp_path) -> None:
    scheme = rse.Scheme.load(SCHEMES / "nist_hill.csv")
    alone, spread = tmp_path / "alone", tmp_path / "spread"
    rse.write_worlds(scheme, alone, amount=60, targets=TARGETS)
    seen = []
    counts = rse.ray.write_worlds(
        scheme, spread, amount=60, targets=TARGETS, shards=6, progress=lambda *args: seen.append(args)
    )
    assert counts["written"] == 60 and counts["skipped"] == 0
    assert [done for done, _, _ in seen] == list(range(1, 7)) and all(n == 6 for _, n, _ in seen)
    assert seen[-1][2] == counts, "the driver's progress sums the shards"
    nodes = {t.node_id for t in shard_tasks(6) if t.node_id}
    assert len(nodes) == 2, "both nodes ran shards"
    assert tree(spread) == tree(alone)


def test_a_worker_killed_mid_shard_is_retried_and_the_tree_is_the_same(cluster, tmp_path) -> None:
    # Big enough that the two shards are still writing when the kill comes.
    scheme = rse.Scheme.load(SCHEMES / "six_obstacles.csv")
    amount = 400
    alone, spread = tmp_path / "alone", tmp_path / "spread"
    rse.write_worlds(scheme, alone, amount=amount, targets=TARGETS)
    result: dict = {}

    def spread_run() -> None:
        try:
            result.update(rse.ray.write_worlds(scheme, spread, amount=amount, targets=TARGETS, shards=2))
        except Exception as e:  # noqa: BLE001 - reported by the assertion below
            result["error"] = e

    run = threading.Thread(target=spread_run)
    run.start()
    killed = None
    deadline = time.monotonic() + 120
    while killed is None and time.monotonic() < deadline:
        finished = [p for p in spread.glob("world_*") if not p.name.startswith(".")] if spread.exists() else []
        running = [t for t in list_tasks(filters=[("state", "=", "RUNNING")]) if t.name == "_write_shard"]
        if len(finished) >= 10 and running and running[0].worker_pid:
            killed = running[0].worker_pid
            os.kill(killed, signal.SIGKILL)
        time.sleep(0.05)
    run.join(timeout=300)
    assert killed is not None, "a shard was killed while it wrote"
    assert not run.is_alive() and "error" not in result and result, f"rse.ray.write_worlds returned: {result.get('error', result)!s}"
    # This test's two shards and the first test's six, each finished once.
    attempts = [t.attempt_number for t in shard_tasks(8) if t.func_or_class_name == "_write_shard"]
    assert max(attempts) >= 1, f"Ray retried the killed shard: {attempts}"
    assert result["written"] + result["skipped"] == amount
    assert result["skipped"] > 0, "the retry resumed: worlds placed before the kill were kept"
    assert tree(spread) == tree(alone), "no leftovers, the same bytes"


def test_misuse_is_named(cluster) -> None:
    scheme = rse.Scheme.load(SCHEMES / "nist_hill.csv")
    with pytest.raises(ValueError, match="^shard"):
        rse.ray.write_worlds(scheme, "/tmp/x", shard="0/2")
    with pytest.raises(ValueError, match="^cpus_per_task"):
        rse.ray.write_worlds(scheme, "/tmp/x", cpus_per_task=0)
