"""Host arrays sent to a torch device without the host waiting for the
copy: what a reset hands a simulation on a GPU (mjlab's origins, Genesis's
reset tiles)."""

from __future__ import annotations

from typing import Any


def to_device(values: Any, like: Any) -> Any:
    """Host ``values`` as a tensor of ``like``'s device and dtype: on a
    GPU through pinned memory, copied without the host waiting for it
    (torch's pinned allocator keeps the buffer until the copy is done)."""
    import torch

    host = torch.from_numpy(values).to(like.dtype)
    if like.device.type == "cpu":
        return host
    return host.pin_memory().to(like.device, non_blocking=True)
