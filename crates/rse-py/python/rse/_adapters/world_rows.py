"""Per-world rows of a model's ``hfield_data``, for simulators that batch
a model field per world (MJX under ``jax.vmap``, Playground through
Brax's ``randomization_fn``): row ``w`` is the model's whole field data
with world ``w``'s terrain in the rse field."""

from __future__ import annotations

from typing import Any

import numpy as np


def world_rows(hfield_data: Any, adr: int, samples: np.ndarray) -> np.ndarray:
    """float32 ``(len(samples), len(hfield_data))``: ``hfield_data``
    repeated once per world, world ``w``'s ``samples[w]`` (flattened) at
    ``adr``. When the rse field is the model's only one, the samples
    themselves."""
    worlds = len(samples)
    flat = np.asarray(samples, dtype=np.float32).reshape(worlds, -1)
    size = flat.shape[1]
    if size == len(hfield_data):
        return flat
    rows = np.repeat(np.asarray(hfield_data, dtype=np.float32)[None], worlds, axis=0)
    rows[:, adr : adr + size] = flat
    return rows
