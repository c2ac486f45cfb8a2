"""The package's exception for bad input, in a module that imports nothing of ours.

:class:`ParameterError` is raised by the lowest layers (:mod:`roughcontact._backend`) as
well as the checks of :mod:`roughcontact._validate`; it lives here so that the dependency
between those two runs one way only (``_validate`` imports ``_backend``, never back).
It stays importable as ``roughcontact.ParameterError`` and
``roughcontact._validate.ParameterError``.
"""

from __future__ import annotations

__all__ = ["ParameterError"]


class ParameterError(ValueError):
    """A parameter is outside its accepted range; the message names both."""
