"""Host samples into a model's height fields, one way for every adapter:
rows written into a flat host array (``write_rows``: a ``MjModel``'s
``hfield_data``) or copied into a Warp array (``copy_rows``: MuJoCo Warp,
mjlab, ``rse.newton``) at given starts, and a geom pointed at a field per
world (``geom_dataid`` batched per world)."""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

import numpy as np


def write_rows(data: np.ndarray, rows: np.ndarray, pairs: Iterable[tuple[int, int]]) -> None:
    """Writes row ``r`` of ``rows`` (one row a field) into the flat host
    array ``data`` (a ``MjModel``'s ``hfield_data``, a numpy view of a Warp
    array) at ``start``, for each ``(r, start)`` of ``pairs``."""
    rows = rows.reshape(len(rows), -1)
    size = rows.shape[1]
    for r, start in pairs:
        data[int(start) : int(start) + size] = rows[r]


def copy_rows(dst: Any, rows: np.ndarray, pairs: Iterable[tuple[int, int]]) -> None:
    """Copies row ``r`` of ``rows`` (float32, one row a field) into the Warp
    array ``dst`` (a model's ``hfield_data``, Newton's elevations) at
    ``start``, for each ``(r, start)`` of ``pairs``. On the CPU device into
    a numpy view of ``dst`` (its memory: a plain copy, no kernel launch
    per field); on a GPU one ``wp.copy`` per field from ``rows`` wrapped
    in place (no copy on the host)."""
    import warp as wp

    if len(rows) == 0:
        return
    rows = np.ascontiguousarray(rows, dtype=np.float32).reshape(len(rows), -1)
    size = rows.shape[1]
    if dst.device.is_cpu:
        full = dst.numpy()
        view = full.reshape(-1)
        if not np.shares_memory(view, full):
            raise ValueError("dst: a Warp array of one contiguous block was expected")
        write_rows(view, rows, pairs)
        return
    source: Any = wp.array(rows.reshape(-1), dtype=float, device="cpu", copy=False)
    for r, start in pairs:
        wp.copy(dst, source, dest_offset=int(start), src_offset=int(r) * size, count=size)


def route_per_world(m: Any, gid: int, first: int) -> None:
    """Points geom ``gid`` of world ``w`` of the device model ``m`` at
    height field ``first + w`` (``geom_dataid`` batched per world, one row
    a world), leaving every other geom's routing as it is."""
    import warp as wp

    dataid = m.geom_dataid.numpy()
    dataid[:, gid] = first + np.arange(dataid.shape[0])
    wp.copy(m.geom_dataid, wp.array(dataid, dtype=int, device=m.geom_dataid.device))
