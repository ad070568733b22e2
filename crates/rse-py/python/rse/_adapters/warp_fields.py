"""Host samples into a model's height fields, one way for every adapter:
rows written into a flat host array (``write_rows``: a ``MjModel``'s
``hfield_data``) or copied into a Warp array (``copy_rows``: MuJoCo Warp,
``rse.newton``; on a GPU in one upload) at given starts, and a geom
pointed at a field per world (``geom_dataid`` batched per world). A
reset's runs into several arrays at once: ``rse._adapters.uploads``."""

from __future__ import annotations

import functools
from collections.abc import Iterable
from typing import Any, Optional

import numpy as np


def write_rows(data: np.ndarray, rows: np.ndarray, pairs: Iterable[tuple[int, int]]) -> None:
    """Writes row ``r`` of ``rows`` (one row a field) into the flat host
    array ``data`` (a ``MjModel``'s ``hfield_data``, a numpy view of a Warp
    array) at ``start``, for each ``(r, start)`` of ``pairs``."""
    rows = rows.reshape(len(rows), -1)
    size = rows.shape[1]
    for r, start in pairs:
        data[int(start) : int(start) + size] = rows[r]


def copy_rows(dst: Any, rows: np.ndarray, pairs: Iterable[tuple[int, int]], *, scatter: Optional[bool] = None) -> None:
    """Copies row ``r`` of ``rows`` (float32, one row a field) into the Warp
    array ``dst`` (a model's ``hfield_data``, Newton's elevations) at
    ``start``, for each ``(r, start)`` of ``pairs``. On a GPU in one
    upload: the rows named are gathered on the host, sent in one copy with
    their starts, and one kernel (``scatter_rows``) writes them in place;
    a copy per field (as before: 2·82 a step at 4096 envs resetting every
    50 steps) cost a driver round trip each. On the CPU device the rows go
    into a numpy view of ``dst``'s memory, with no kernel to launch.
    ``scatter`` forces the one way or the other (tests)."""
    import warp as wp

    pairs = [(int(r), int(start)) for r, start in pairs]
    if not pairs:
        return
    rows = np.asarray(rows).reshape(len(rows), -1)
    if scatter is None:
        scatter = not dst.device.is_cpu
    if not scatter:
        write_rows(flat_view(dst, "dst"), rows.astype(np.float32, copy=False), pairs)
        return
    gathered = np.ascontiguousarray(rows[[r for r, _ in pairs]], dtype=np.float32)
    device = dst.device
    source: Any = wp.array(gathered, dtype=wp.float32, device=device)
    starts: Any = wp.array(np.array([start for _, start in pairs], dtype=np.int32), dtype=wp.int32, device=device)
    wp.launch(scatter_rows_kernel(), dim=gathered.shape, inputs=[source, starts], outputs=[dst], device=device)


@functools.lru_cache(maxsize=None)
def scatter_rows_kernel() -> Any:
    """The Warp kernel of ``copy_rows``: element ``i`` of row ``r`` of
    ``src`` to ``dst[starts[r] + i]``, a thread each. Made on first use, so
    that importing rse needs no Warp."""
    import warp as wp

    @wp.kernel
    def scatter_rows(src: wp.array2d(dtype=wp.float32), starts: wp.array(dtype=wp.int32), dst: wp.array(dtype=wp.float32)):  # type: ignore[valid-type]
        r, i = wp.tid()  # type: ignore[misc]
        dst[starts[r] + i] = src[r, i]

    return scatter_rows


def flat_view(array: Any, argument: str) -> np.ndarray:
    """A numpy view of a CPU Warp array's memory, one dimension; a
    ``ValueError`` naming ``argument`` where it is not one block."""
    full = array.numpy()
    view = full.reshape(-1)
    if not np.shares_memory(view, full):
        raise ValueError(f"{argument}: a Warp array of one contiguous block was expected")
    return view


def route_per_world(m: Any, gid: int, first: int) -> None:
    """Points geom ``gid`` of world ``w`` of the device model ``m`` at
    height field ``first + w`` (``geom_dataid`` batched per world, one row
    a world), leaving every other geom's routing as it is."""
    import warp as wp

    dataid = m.geom_dataid.numpy()
    dataid[:, gid] = first + np.arange(dataid.shape[0])
    wp.copy(m.geom_dataid, wp.array(dataid, dtype=int, device=m.geom_dataid.device))
