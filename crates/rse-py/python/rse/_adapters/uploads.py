"""A reset's rows into several Warp arrays of one device at once
(``Uploads``: mjlab's reset event writes its envs' exact and coarse
samples into ``hfield_data`` and their geoms' boxes into ``geom_aabb``):
on a GPU through small pinned buffers, in sends of a bounded size, two
copies and one kernel each; on the CPU straight into numpy views."""

from __future__ import annotations

import dataclasses
import functools
from collections.abc import Callable, Iterator
from typing import Any, Optional, Union

import numpy as np

from rse._adapters.warp_fields import flat_view, write_rows


@dataclasses.dataclass(frozen=True)
class Filled:
    """Rows that write themselves: ``size`` values each, the rows ``part``
    (a slice of the block's rows) written by ``fill(data, starts, part)``
    into the flat float32 numpy array ``data``, row ``part.start + i`` from
    ``starts[i]`` (``EnvTerrains._copy_fields``: a reset's envs' fields,
    copied from the pool on a thread each)."""

    size: int
    fill: Callable[[np.ndarray, np.ndarray, slice], None]


Block = tuple[int, np.ndarray, Union[np.ndarray, Filled], Optional[Union[np.ndarray, list[int]]]]
"""What ``Uploads.write`` writes: ``(target, starts, rows, picks)``: row
``picks[i]`` of ``rows`` (float32, 2-D, one row a run; row ``i`` where
``picks`` is None, and always for ``Filled`` rows) into target
``target`` from element ``starts[i]``, for each ``i``: a reset's envs'
fields, or their geoms' boxes."""

Piece = tuple[Block, slice]
"""Part of one send of ``Uploads``: the rows ``slice`` of a ``Block``."""


def row_size(rows: Union[np.ndarray, Filled]) -> int:
    """Values in each of ``rows`` (a 2-D array, one row a run, or
    ``Filled``)."""
    return rows.size if isinstance(rows, Filled) else int(rows.shape[1])


class Uploads:
    """A reset's blocks of float32 rows (its envs' samples, their geoms'
    boxes) written into up to ``TARGETS`` flat float32 Warp arrays of one
    device at once, in the order of Warp's stream (the simulation's). On a
    GPU the rows and their places are gathered (numpy, a copy a block)
    into pinned host buffers kept from call to call (so the host does not
    wait for them, and allocates nothing), go up in two copies, and one
    kernel writes every row in place; before, each array took its own two
    uploads from pageable memory and a kernel (at 4096 envs on an H200 a
    reset of 4 envs took 3.5 ms of the host's time), and each row was
    packed in a loop of its own. The buffers hold at most ``limit`` values
    (or one row, where a row is longer): a larger write goes up in several
    sends, each waiting for the last one's copy before it refills the
    buffer. Kept whole, they held twice the largest write ever made, and
    the scene's first write is every env's fields: 1 GiB on the device and
    1 GiB pinned at 4096 envs, twice the terrains themselves. On the CPU
    device the rows go into numpy views of the targets' memory;
    ``kernel=True`` takes the GPU's way there too (tests), from host
    buffers that are not pinned."""

    TARGETS = 2

    LIMIT = 1 << 20
    """Values (float32) the buffers hold at most: 4 MiB on the device and 4
    MiB pinned, about 32 of the default stepfield's envs a send (a step's
    resets at 4096 envs and 1 s episodes, 82 envs, go up in three). Kept
    small so that the terrains at 4096 envs stay within 0.5 GiB."""

    def __init__(self, *, kernel: Optional[bool] = None, limit: int = LIMIT) -> None:
        self.kernel = kernel
        self.limit = limit
        self._host: Any = None
        self._places_host: Any = None
        self._values: Any = None
        self._places: Any = None
        self._sent: Any = None

    def write(self, targets: list[Any], blocks: list[Block]) -> None:
        """Writes each block of ``blocks`` (``Block``) into
        ``targets[target]`` (flat float32 Warp arrays of one device, at
        most ``TARGETS``)."""
        if len(targets) > self.TARGETS:
            raise ValueError(f"targets: at most {self.TARGETS} arrays, got {len(targets)}")
        blocks = [(t, np.asarray(starts, dtype=np.int64).reshape(-1), rows, picks) for t, starts, rows, picks in blocks if len(starts)]
        if not blocks:
            return
        device = targets[0].device
        if not (device.is_cuda if self.kernel is None else self.kernel):
            views = [flat_view(t, "targets") for t in targets]
            for t, starts, rows, picks in blocks:
                if isinstance(rows, Filled):
                    rows.fill(views[t], starts, slice(0, len(starts)))
                else:
                    write_rows(views[t], rows, zip(range(len(starts)) if picks is None else picks, starts))
            return
        for pieces in self._sends(blocks):
            self._send(targets, pieces)

    def _sends(self, blocks: list[Block]) -> Iterator[list[Piece]]:
        """``blocks`` cut into sends (``cut``), each a list of ``(block,
        rows)``."""
        for send in cut([(row_size(rows), len(starts)) for _, starts, rows, _ in blocks], self.limit):
            yield [(blocks[b], part) for b, part in send]

    def _send(self, targets: list[Any], pieces: list[Piece]) -> None:
        """``write`` the GPU's way, one send: the rows gathered into the
        pinned host buffer, their places beside them, two copies up and
        one kernel."""
        import warp as wp

        device = targets[0].device
        sizes = [row_size(block[2]) for block, _ in pieces]
        counts = [part.stop - part.start for _, part in pieces]
        count = sum(counts)
        self._reserve(device, sum(n * size for n, size in zip(counts, sizes)), count)
        if self._sent is not None:
            # The last send's copies read these buffers: done long since
            # between resets; within a write, the copy just queued.
            wp.synchronize_event(self._sent)
        host, places = self._host.numpy(), self._places_host.numpy().reshape(-1, 4)
        offset = r = 0
        for ((t, all_starts, rows, picks), part), size, n in zip(pieces, sizes, counts):
            starts = all_starts[part]
            if isinstance(rows, Filled):
                rows.fill(host, offset + size * np.arange(n), part)
            elif picks is None:
                host[offset : offset + n * size].reshape(n, size)[...] = rows[part]
            else:
                np.take(rows, np.asarray(picks[part], dtype=np.int64), axis=0, out=host[offset : offset + n * size].reshape(n, size))
            places[r : r + n] = np.stack([offset + size * np.arange(n), starts, np.full(n, size), np.full(n, t)], axis=1)
            offset += n * size
            r += n
        wp.copy(self._values, self._host, count=offset)
        wp.copy(self._places, self._places_host, count=4 * count)
        padded = list(targets) + [targets[0]] * (self.TARGETS - len(targets))
        wp.launch(write_runs_kernel(), dim=(count, max(sizes)), inputs=[self._values, self._places, *padded], device=device)
        if device.is_cuda:
            self._sent = wp.get_stream(device).record_event()

    def _reserve(self, device: Any, values: int, runs: int) -> None:
        """Buffers for at least ``values`` values and ``runs`` runs, grown
        when too small to twice what is asked, up to ``limit`` values (and
        as many runs: one value a run at most)."""
        import warp as wp

        if self._host is None or self._host.shape[0] < values or self._values.device != device:
            size = grown(values, self.limit)
            self._release()
            self._host = wp.empty(size, dtype=wp.float32, device="cpu", pinned=device.is_cuda)
            self._values = wp.empty(size, dtype=wp.float32, device=device)
        if self._places_host is None or self._places_host.shape[0] < 4 * runs or self._places.device != device:
            size = 4 * grown(runs, self.limit)
            self._release()
            self._places_host = wp.empty(size, dtype=wp.int32, device="cpu", pinned=device.is_cuda)
            self._places = wp.empty(size, dtype=wp.int32, device=device)

    def _release(self) -> None:
        """Waits for the last send's copies (they read the buffers about to
        be let go) and forgets them."""
        import warp as wp

        if self._sent is not None:
            wp.synchronize_event(self._sent)
            self._sent = None

    def device_bytes(self) -> int:
        """Bytes the buffers hold on the targets' device (0 where the rows
        went into numpy views: the CPU device)."""
        return sum(int(a.capacity) for a in (self._values, self._places) if a is not None)


def cut(blocks: list[tuple[int, int]], limit: int) -> Iterator[list[tuple[int, slice]]]:
    """Blocks of ``(row size, rows)`` cut into sends of at most ``limit``
    values each (a row longer than that alone), in order: each send a list
    of ``(block index, its rows)``."""
    send: list[tuple[int, slice]] = []
    room = limit
    for b, (size, n) in enumerate(blocks):
        i = 0
        while size and i < n:
            take = min(n - i, room // size)
            if take == 0:
                if send:
                    yield send
                    send, room = [], limit
                    continue
                take = 1  # a row longer than the limit goes alone
            send.append((b, slice(i, i + take)))
            room = max(0, room - take * size)
            i += take
    if send:
        yield send


def grown(asked: int, limit: int) -> int:
    """What ``Uploads`` grows a buffer to when ``asked`` does not fit it:
    twice that, up to ``limit`` (and never less than asked)."""
    return max(asked, min(2 * asked, limit))


def staging(blocks: list[tuple[int, int]], limit: int = 0) -> tuple[int, int]:
    """The values and runs ``Uploads`` (``limit``: its default) holds
    buffers for after writing blocks of ``(row size, rows)``, from none:
    what a scene's first write, every env's rows, leaves it."""
    limit = limit or Uploads.LIMIT
    values = runs = 0
    for send in cut(blocks, limit):
        v = sum((part.stop - part.start) * blocks[b][0] for b, part in send)
        r = sum(part.stop - part.start for _, part in send)
        if v > values:
            values = grown(v, limit)
        if r > runs:
            runs = grown(r, limit)
    return values, runs


@functools.lru_cache(maxsize=None)
def write_runs_kernel() -> Any:
    """The Warp kernel of ``Uploads``: element ``i`` of run ``r`` (at
    ``places[r] = (offset, start, length, target)``) from ``values`` to
    its target, a thread each. Made on first use, so that importing rse
    needs no Warp."""
    import warp as wp

    @wp.kernel
    def write_runs(
        values: wp.array(dtype=wp.float32),  # type: ignore[valid-type]
        places: wp.array(dtype=wp.int32),  # type: ignore[valid-type]
        dst0: wp.array(dtype=wp.float32),  # type: ignore[valid-type]
        dst1: wp.array(dtype=wp.float32),  # type: ignore[valid-type]
    ):
        r, i = wp.tid()  # type: ignore[misc]
        if i < places[4 * r + 2]:
            value = values[places[4 * r] + i]
            at = places[4 * r + 1] + i
            target = places[4 * r + 3]
            if target == 0:
                dst0[at] = value
            else:
                dst1[at] = value

    return write_runs
