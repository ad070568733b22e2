"""Random Step Environments (NIST stepfields) for robot simulators.

The generator lives in Rust (``rse._rse``); this package re-exports it.
"""

from rse._rse import __version__

__all__ = ["__version__"]
