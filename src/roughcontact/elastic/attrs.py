"""Rebuild a substrate from the attributes it wrote (:meth:`ElasticOperator.to_attrs`).

A path file records its substrate as flat attributes, among them the kind tag
``substrate``, which begins with the kind's name (``"Substrate(shape=(256, 256), ..."``).
:func:`substrate_from_attrs` looks the name up among the registered kinds and calls the
kind's ``from_attrs``; a new kind of substrate registers itself with
:func:`register_substrate_kind` and is then read back wherever paths are analysed.
Attributes without the tag (files of early versions) describe a :class:`Substrate`.
"""

from __future__ import annotations

import re

from .._validate import ParameterError
from .operator import ElasticOperator
from .substrate import Substrate

__all__ = ["register_substrate_kind", "substrate_from_attrs", "substrate_kind"]

_KINDS: dict[str, type] = {"Substrate": Substrate}
_NAME = re.compile(r"\s*([A-Za-z_][A-Za-z0-9_]*)\s*\(")


def register_substrate_kind(cls: type, name: str | None = None) -> type:
    """Make :func:`substrate_from_attrs` rebuild ``cls`` (an :class:`ElasticOperator` with
    ``to_attrs`` and a ``from_attrs`` classmethod) from attributes whose kind tag begins
    with ``name`` (default: the class's name). Returns ``cls``, so it serves as a decorator."""
    if not callable(getattr(cls, "from_attrs", None)):
        raise ParameterError(f"a substrate kind needs a from_attrs classmethod; {cls!r} has none")
    _KINDS[name or cls.__name__] = cls
    return cls


def substrate_kind(attrs) -> str:
    """The kind's name in the tag ``attrs["substrate"]``; "Substrate" when there is no tag."""
    tag = attrs.get("substrate")
    if tag is None:
        return "Substrate"
    match = _NAME.match(str(tag))
    if match is None:
        raise ParameterError(
            f"substrate attribute {str(tag)[:60]!r} does not begin with a kind name and '(' "
            f"(known kinds: {', '.join(sorted(_KINDS))})"
        )
    return match.group(1)


def substrate_from_attrs(attrs) -> ElasticOperator:
    """The substrate described by ``attrs`` (a mapping, e.g. a path dataset's ``attrs``).

    Dispatches on the kind tag (:func:`substrate_kind`) to the kind's ``from_attrs``,
    which accepts the attribute sets of earlier versions as well (for :class:`Substrate`:
    no ``periodic``, no ``thickness``/``poisson``/``base``). Units as in ``to_attrs``.

    Raises
    ------
    ParameterError
        For an unknown kind, or attributes that lack what the kind needs.
    """
    name = substrate_kind(attrs)
    if name not in _KINDS:
        raise ParameterError(
            f"substrate kind {name!r} is unknown; known kinds: {', '.join(sorted(_KINDS))} "
            "(register a new one with roughcontact.elastic.register_substrate_kind)"
        )
    return _KINDS[name].from_attrs(attrs)
