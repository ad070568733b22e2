"""Worlds by the hundred thousand on a Ray cluster: ``rse.write_worlds``'s
shards as Ray tasks, all writing into one folder every node sees
(docs/guide.md, "Many machines")::

    import ray, rse, rse.ray

    ray.init(address="auto")                    # the cluster
    counts = rse.ray.write_worlds(rse.Scheme.load("schemes/nist_hill.csv"), "/shared/worlds",
                                  amount=100_000, shards=256, targets="mujoco")

Shard ``K/N`` is one task (``rse.write_worlds(..., shard="K/N")``), placed
by Ray's own scheduler on a node with ``cpus_per_task`` free CPUs, spread
over the nodes by default (``scheduling_strategy="SPREAD"``: the writes,
not only the CPU work, are shared out). A task
whose worker or node dies is retried by Ray (``max_retries``), and the
retried shard ends as if nothing happened: a batch resumes where it
stopped (finished worlds are kept, unfinished ones were never in place).
So the tree is the one a single ``rse-gen batch`` writes, byte for byte.
The driver gathers progress as shards finish: ``progress(done, shards,
counts)`` after each, counts summed so far. More shards than CPUs make the
progress finer and the cluster's load more even; a shard's folders never
touch another's, so any number of them run at once.
"""

from __future__ import annotations

import os
from typing import Any, Callable, Optional

from rse._rse import Scheme

__all__ = ["write_worlds"]

COUNTS = ("written", "skipped", "replaced", "bytes")


BUSY_WAIT_S = 60.0
"""How long a retried shard waits for its killed attempt's lock."""


def _write_shard(scheme_csv: str, out: str, shard: str, options: dict[str, Any]) -> dict[str, int]:
    """One shard, in a Ray worker: the scheme travels as its CSV text. A
    retry can start while the killed attempt's process is still dying and
    holds the shard's lock: it waits for the lock (up to ``BUSY_WAIT_S``)."""
    import time

    import rse

    scheme = rse.Scheme.from_csv(scheme_csv)
    deadline = time.monotonic() + BUSY_WAIT_S
    while True:
        try:
            return rse.write_worlds(scheme, out, shard=shard, **options)
        except rse.ShardBusyError:
            if time.monotonic() > deadline:
                raise
            time.sleep(0.2)


def write_worlds(
    scheme: Scheme,
    out: "str | os.PathLike[str]",
    *,
    shards: Optional[int] = None,
    cpus_per_task: int = 1,
    max_retries: int = 3,
    progress: Optional[Callable[[int, int, dict[str, int]], None]] = None,
    scheduling_strategy: Any = "SPREAD",
    **options: Any,
) -> dict[str, int]:
    """Writes ``scheme``'s worlds into ``out`` (a folder every node of the
    Ray cluster sees, the same path on each) as ``rse.write_worlds`` does,
    in ``shards`` Ray tasks (default: four per CPU of the cluster), each
    given ``cpus_per_task`` CPUs and as many worker threads, placed by
    ``scheduling_strategy`` (Ray's; default ``"SPREAD"``); ``options``
    are ``rse.write_worlds``'s (``amount``, ``seed``, ``targets``, ``mesh``,
    ``template``, ...; a template folder must be on every node too).
    Returns the counts summed over the shards. Call ``ray.init`` first."""
    import ray

    if not ray.is_initialized():
        raise RuntimeError("ray: not initialized; call ray.init() (or ray.init(address=...)) first")
    for key in ("shard", "jobs"):
        if key in options:
            raise ValueError(f"{key}: rse.ray chooses each task's {key} (give shards= and cpus_per_task=)")
    if cpus_per_task < 1:
        raise ValueError(f"cpus_per_task: {cpus_per_task}; expected at least 1")
    if shards is None:
        shards = max(1, 4 * int(ray.cluster_resources().get("CPU", 1)) // cpus_per_task)
    if shards < 1:
        raise ValueError(f"shards: {shards}; expected at least 1")
    task = ray.remote(
        num_cpus=cpus_per_task,
        max_retries=max_retries,
        retry_exceptions=False,
        scheduling_strategy=scheduling_strategy,
    )(_write_shard)
    text, folder = scheme.to_csv(), os.fspath(out)
    pending = [task.remote(text, folder, f"{k}/{shards}", {**options, "jobs": cpus_per_task}) for k in range(shards)]
    totals = dict.fromkeys(COUNTS, 0)
    done = 0
    while pending:
        finished, pending = ray.wait(pending, num_returns=1)
        for counts in ray.get(finished):
            for key in COUNTS:
                totals[key] += counts[key]
            done += 1
        if progress is not None:
            progress(done, shards, dict(totals))
    return totals
