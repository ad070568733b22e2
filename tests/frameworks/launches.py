"""Kernel launches made by code run inside ``Launches()``: every
dispatched torch operation that computes on a tensor's data (not a view,
not an allocation) and every Warp ``launch``, by name. On a GPU each is a
kernel launched from Python outside mjlab's captured graphs: some
microseconds of the host's time and a gap on the device (1.1 ms a step for
the thirty-odd tensor ops ``bound_near_robots`` was, at 4096 envs on an
H200). On the CPU, where the tests run, they are counted, not timed."""

from __future__ import annotations

from typing import Any

import torch
import warp as wp
from torch.utils._python_dispatch import TorchDispatchMode

aten = torch.ops.aten

NO_KERNEL = {
    aten.empty.memory_format,
    aten.empty_strided.default,
    aten.empty_like.default,
    aten.detach.default,
    aten.lift_fresh.default,
    aten.sym_size.int,
    aten.sym_stride.int,
    aten.sym_numel.default,
    aten.is_same_size.default,
}
"""Dispatched operations that launch no kernel: allocations and metadata
(views are told by ``is_view``)."""


class Launches(TorchDispatchMode):
    """Records the kernels launched while active (``self.found``: one name
    each, ``torch: aten.add.Tensor`` or ``warp: near_boxes``)."""

    def __init__(self) -> None:
        super().__init__()
        self.found: list[str] = []
        self._launch: Any = None

    def __torch_dispatch__(self, func: Any, types: Any, args: Any = (), kwargs: Any = None) -> Any:
        if not func.is_view and func not in NO_KERNEL:
            self.found.append(f"torch: {func}")
        return func(*args, **(kwargs or {}))

    def __enter__(self) -> Launches:
        self._launch = wp.launch

        def launch(kernel: Any, *args: Any, **kwargs: Any) -> Any:
            self.found.append(f"warp: {kernel.func.__name__}")
            return self._launch(kernel, *args, **kwargs)

        wp.launch = launch
        return super().__enter__()

    def __exit__(self, *exc: Any) -> None:
        super().__exit__(*exc)
        wp.launch = self._launch
