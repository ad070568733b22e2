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


def tree(root: Path) -> dict[str, bytes]:
    return {str(p.relative_to(root)): p.read_bytes() for p in sorted(root.rglob("*")) if p.is_file()}


@pytest.fixture(scope="module")
def cluster():
    nodes = Cluster(initialize_head=True, head_node_args={"num_cpus": 1})
    nodes.add_node(num_cpus=1)
    ray.init(address=nodes.address, log_to_driver=False)
    nodes.wait_for_nodes()
    assert len([n for n in ray.nodes() if n["Alive"]]) == 2, "two nodes"
    yield nodes
    ray.shutdown()
    nodes.shutdown()


def test_shards_as_ray_tasks_give_the_tree_of_one_run(cluster, tmp_path) -> None:
    scheme = rse.Scheme.load(SCHEMES / "nist_hill.csv")
    alone, spread = tmp_path / "alone", tmp_path / "spread"
    rse.write_worlds(scheme, alone, amount=24, targets=TARGETS)
    seen = []
    counts = rse.ray.write_worlds(
        scheme, spread, amount=24, targets=TARGETS, shards=6, progress=lambda *args: seen.append(args)
    )
    assert counts["written"] == 24 and counts["skipped"] == 0
    assert [done for done, _, _ in seen] == list(range(1, 7)) and all(n == 6 for _, n, _ in seen)
    assert seen[-1][2] == counts, "the driver's progress sums the shards"
    tasks = list_tasks(filters=[("func_or_class_name", "=", "_write_shard")], limit=1000)
    nodes = {t.node_id for t in tasks if t.node_id}
    assert len(nodes) == 2, "both nodes ran shards"
    assert tree(spread) == tree(alone)


def test_a_worker_killed_mid_shard_is_retried_and_the_tree_is_the_same(cluster, tmp_path) -> None:
    # Big enough that the two shards are still writing when the kill comes.
    scheme = rse.Scheme.load(SCHEMES / "six_obstacles.csv")
    amount = 400
    alone, spread = tmp_path / "alone", tmp_path / "spread"
    rse.write_worlds(scheme, alone, amount=amount, targets=TARGETS)
    result: dict = {}
    run = threading.Thread(
        target=lambda: result.update(rse.ray.write_worlds(scheme, spread, amount=amount, targets=TARGETS, shards=2))
    )
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
    assert not run.is_alive() and result, "rse.ray.write_worlds returned"
    attempts = [t.attempt_number for t in list_tasks(filters=[("func_or_class_name", "=", "_write_shard")], limit=1000)]
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
