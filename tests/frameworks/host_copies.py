"""Host copies made by code run inside ``HostCopies()``: every torch
operation that moves data between the host and a device or reads a value
into Python, by name. On a GPU each is a synchronising round trip in the
middle of a step; on the CPU, where the tests run, the same calls are
cheap or no-ops, so they are caught where the code asks for them (the
Python call, or torch's dispatch), not by their cost."""

from __future__ import annotations

import contextlib
from collections.abc import Iterator
from typing import Any

import numpy as np
import torch
import warp as wp
from torch.utils._python_dispatch import TorchDispatchMode

aten = torch.ops.aten

READS = {
    aten._local_scalar_dense.default: "a value read into Python (.item(), bool(), float())",
    aten.lift_fresh.default: "a tensor made from host data (torch.tensor)",
}
"""Dispatched operations that are host copies wherever they run."""


class HostCopies(TorchDispatchMode):
    """Records host copies (``self.found``: one line each) made while
    active: the dispatched ``READS``, a ``_to_copy`` or ``copy_`` between
    devices, and the Python calls that copy whatever the device is
    (``Tensor.numpy``, ``.cpu()``, ``.tolist()``, ``.to("cpu")``,
    ``torch.tensor``, ``torch.as_tensor``, ``torch.from_numpy``, Warp's
    ``array.numpy``, ``np.asarray`` of a tensor or Warp array)."""

    def __init__(self) -> None:
        super().__init__()
        self.found: list[str] = []
        self._saved: list[tuple[Any, str, Any]] = []

    def __torch_dispatch__(self, func: Any, types: Any, args: Any = (), kwargs: Any = None) -> Any:
        kwargs = kwargs or {}
        if func in READS:
            self.found.append(f"{func}: {READS[func]}")
        elif func in (aten._to_copy.default, aten.copy_.default):
            source = args[0] if func is aten._to_copy.default else args[1]
            target = kwargs.get("device") if func is aten._to_copy.default else args[0].device
            if isinstance(source, torch.Tensor) and target is not None and torch.device(target) != source.device:
                self.found.append(f"{func}: {source.device} to {target}")
        return func(*args, **kwargs)

    def _patch(self, owner: Any, name: str, why: str, when: Any = None) -> None:
        original = getattr(owner, name)

        def recorded(*args: Any, **kwargs: Any) -> Any:
            if when is None or when(*args, **kwargs):
                self.found.append(f"{getattr(owner, '__name__', owner)}.{name}: {why}")
            return original(*args, **kwargs)

        self._saved.append((owner, name, original))
        setattr(owner, name, recorded)

    def __enter__(self) -> HostCopies:
        def to_host(_tensor: Any, *args: Any, **kwargs: Any) -> bool:
            device = kwargs.get("device", args[0] if args and isinstance(args[0], (str, torch.device)) else None)
            return device is not None and torch.device(device).type == "cpu"

        self._patch(torch.Tensor, "numpy", "a tensor read into numpy")
        self._patch(torch.Tensor, "cpu", "a tensor copied to the host")
        self._patch(torch.Tensor, "tolist", "a tensor read into Python")
        self._patch(torch.Tensor, "to", "a tensor copied to the host", when=to_host)
        self._patch(torch, "tensor", "a tensor made from host data")
        self._patch(torch, "as_tensor", "a tensor made from host data")
        self._patch(torch, "from_numpy", "a tensor made from host data")
        self._patch(wp.array, "numpy", "a Warp array read into numpy")
        self._patch(np, "asarray", "an array read into numpy", when=lambda a, *_, **__: isinstance(a, (torch.Tensor, wp.array)))
        return super().__enter__()

    def __exit__(self, *exc: Any) -> None:
        super().__exit__(*exc)
        for owner, name, original in reversed(self._saved):
            setattr(owner, name, original)
        self._saved.clear()


@contextlib.contextmanager
def as_a_gpu_runs_them(tops: Any) -> Iterator[None]:
    """While active, ``tops`` (an ``EnvTerrainsEvent.exact_tops()``) reads
    the exact tops by a kernel on the device, as on a GPU, where the CPU
    device reads them with ``heights_at`` over the points' own memory."""
    on_host, tops.on_host = tops.on_host, False
    try:
        yield
    finally:
        tops.on_host = on_host
