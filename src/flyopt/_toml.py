"""The one TOML reader of flyopt: ``tomllib`` of Python 3.11+, ``tomli`` (the same library) on 3.10.

Every module reads TOML through ``from flyopt._toml import tomllib``, so the
choice of reader is made here once. It imports nothing from flyopt.
"""

import sys

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - exercised only on Python 3.10
    import tomli as tomllib

__all__ = ["tomllib"]
