"""Env ids as the frameworks hand them to a reset (None for all, a slice,
a boolean mask, a torch tensor, an array or a list), as one checked list
of ints: the one place the adapters read them."""

from __future__ import annotations

from typing import Any

import numpy as np


def env_ids(num_envs: int, given: Any, argument: str = "env_ids") -> list[int]:
    """``given`` as a list of env ids below ``num_envs``: every env when
    ``None``; a ``slice`` of them; a boolean mask of ``num_envs`` (what
    Genesis's tasks reset by); otherwise ints (a torch tensor, on any
    device, an array, a list, one int). A ``ValueError`` naming
    ``argument`` for an id out of range or a mask of another length."""
    if given is None:
        return list(range(num_envs))
    # Raw bytes read as small integers (a memoryview of b"\x00\x03" would be
    # envs 0 and 3), text as nothing: never env ids, whatever buffer holds
    # them (the rule of rse.EnvTerrains.reset).
    if isinstance(given, (bytes, bytearray, memoryview, str)):
        raise ValueError(f"{argument}: expected a sequence of environment numbers, not bytes or text")
    if isinstance(given, slice):
        return list(range(num_envs)[given])
    if hasattr(given, "detach"):  # a torch tensor, maybe on a GPU
        given = given.detach().cpu().numpy()
    array = np.asarray(given)
    if array.dtype == np.bool_:
        if array.shape != (num_envs,):
            raise ValueError(f"{argument}: a mask of shape {array.shape} for {num_envs} envs")
        return np.flatnonzero(array).tolist()
    ids = array.astype(np.int64).ravel()
    bad = ids[(ids < 0) | (ids >= num_envs)]
    if bad.size:
        raise ValueError(f"{argument}: {int(bad[0])} is not an environment (0 to {num_envs - 1})")
    return ids.tolist()
