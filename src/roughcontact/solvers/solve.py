"""The single entry point: ``solve(heights, substrate, interaction, load= | offset=)``."""

from __future__ import annotations

from .._validate import ParameterError
from ..interactions.hardwall import HardWall
from .polonsky_keer import polonsky_keer
from .smooth import minimize_energy

__all__ = ["solve"]


def solve(
    heights,
    substrate,
    interaction=None,
    *,
    load=None,
    offset=None,
    initial=None,
    tol=1e-8,
    max_iter=5000,
    callback=None,
):
    """Solve one contact state of a rigid rough surface on an elastic substrate.

    Parameters
    ----------
    heights : (nx, ny) array
        Heights ``h`` of the rigid surface (length); it sits at ``z = d - h``, so maxima
        of ``h`` are the summits touching first.
    substrate : Substrate
        Elastic substrate (shape must match ``heights``).
    interaction : HardWall or a smooth law (e.g. SmoothLJ93), optional
        The surface interaction (default: :class:`HardWall`). The hard wall is solved by
        constrained conjugate gradients, smooth laws by Green's-function-preconditioned
        energy minimisation.
    load : float, optional
        Load control: mean pressure :math:`\\bar p = N/A_0` (same units as the contact
        modulus; > 0 pushes the bodies together).
    offset : float, optional
        Displacement control: offset ``d`` (length); gap ``g = d - h + w``.
    initial : ContactResult, optional
        Warm start from a previous state.
    tol : float
        Convergence tolerance (the solver's measure; see its documentation).
    max_iter : int
        Iteration cap; a solve that reaches it returns ``converged=False``.
    callback : callable, optional
        ``callback(iteration, residual)``; return True to stop early.

    Returns
    -------
    ContactResult
        With ``converged``, ``iterations``, ``residual`` and ``message`` — never silent.
    """
    interaction = HardWall() if interaction is None else interaction
    if isinstance(interaction, HardWall):
        return polonsky_keer(
            heights,
            substrate,
            load=load,
            offset=offset,
            initial=initial,
            tol=tol,
            max_iter=max_iter,
            callback=callback,
        )
    if getattr(interaction, "hard_core", True):
        raise ParameterError(
            f"interaction {getattr(interaction, 'name', interaction)!r} needs a bound-constrained "
            "adhesive solver, which is not available yet; use lj93smooth or lj93"
        )
    if (load is None) == (offset is None):
        raise ParameterError("give exactly one of load (mean pressure) or offset")
    if load is not None:
        raise ParameterError(
            "load control for adhesive interactions is not available yet; use offset= "
            "(displacement control, stable through jumps)"
        )
    return minimize_energy(
        heights,
        substrate,
        interaction,
        offset=offset,
        initial=initial,
        tol=tol,
        max_iter=max_iter,
        callback=callback,
    )
