"""The layer every framework module of ``rse`` stands on: what rse.mjx,
rse.mujoco_warp, rse.newton, rse.playground, rse.genesis, rse.isaaclab and
rse.mjlab (and rse.mujoco, rse.gym) would otherwise each write again. Pure
Python over ``rse._rse``; no framework is imported at import time.

- ``ids``: env ids as a framework hands them (None, a slice, a mask, a
  tensor, a list) as a checked list.
- ``fields``: the layout an adapter needs, a height field found by name in
  a compiled MuJoCo model and its size checked against the envs'.
- ``pool``: the envs' height fields and their geom in an ``MjSpec``, and
  their samples copied into a compiled model.
- ``world_rows``: per-world rows of ``hfield_data`` for batched models
  (MJX, Playground).
- ``tiles``: what a framework's sub-terrain config shares: its rse fields,
  the scheme fitted to a tile, the tile's world index and terrain, flat
  patches, the launcher's rank.
- ``mjcf``: every MJCF text rse writes or edits from Python.
- ``private``: each framework's private API that an adapter uses, with the
  versions it was checked against, and the check that says so when a
  release removes one.
- ``mjlab``: everything rse does in mjlab (a package of its own).
"""
