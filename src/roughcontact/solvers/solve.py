"""The single entry point: ``solve(heights, substrate, interaction, load= | offset=)``."""

from __future__ import annotations

import math

from array_api_compat import is_jax_array  # (looks at sys.modules: imports no jax)

from .._accelerator import routed
from .._validate import MAX_ITER, ParameterError, tolerance
from ..interactions.hardwall import HardWall
from .bounded import minimize_energy_bounded
from .load_control import solve_at_load
from .polonsky_keer import polonsky_keer
from .smooth import minimize_energy

__all__ = ["solve"]


@routed
def solve(
    heights,
    substrate,
    interaction=None,
    *,
    load=None,
    offset=None,
    initial=None,
    tol=None,
    max_iter=5000,
    callback=None,
    device=None,
    dtype=None,
):
    """Solve one contact state of a rigid rough surface on an elastic substrate.

    Parameters
    ----------
    heights : (nx, ny) array
        Heights ``h`` of the rigid surface (length); it sits at ``z = d - h``, so maxima
        of ``h`` are the summits touching first. A JAX array runs the compiled loops
        (one ``jax.jit`` program per solve; periodic substrates, no ``callback``; see
        the README's "Compiled loops (JAX)").
    substrate : Substrate
        Elastic substrate (shape must match ``heights``).
    interaction : HardWall, an interaction law or a registry name, optional
        The surface interaction (default: :class:`HardWall`); a name of
        :func:`roughcontact.interactions.registry.names` (``"hardwall"``) builds that law
        (one that needs parameters says which: build it instead). The hard wall is solved by
        constrained conjugate gradients (Polonsky & Keer, preconditioned by the stiffness
        on the contact set), smooth laws (SmoothLJ93, LennardJones93, soft-core
        Exponential) by block-preconditioned nonlinear CG, hard-core adhesive laws
        (Exponential, MaugisDugdale) by bound-constrained projected CG. Load control for
        adhesive laws locates the offset that carries the load on a stable branch (see
        ``load_control``).
    load : float, optional
        Load control: mean pressure :math:`\\bar p = N/A_0` (same units as the contact
        modulus; > 0 pushes the bodies together).
    offset : float, optional
        Displacement control: offset ``d`` (length); gap ``g = d - h + w``.
    initial : ContactResult or array, optional
        Warm start from a previous state (copied only if it is not on the device the
        solve computes on).
    tol : float, optional
        Convergence tolerance (the solver's measure; see its documentation), in (0, 1).
        Default 1e-8 (float64) or 1e-6 (float32, also the smallest allowed there;
        larger beyond 1024²: :func:`roughcontact.solvers.inputs.default_tolerance`).
    max_iter : int
        Iteration cap (>= 1); a solve that reaches it returns ``converged=False``.
    callback : callable, optional
        ``callback(iteration, residual)``; return True to stop early.
    device : {None, "cpu", "cuda", "cuda:N"}, optional
        Where to compute: ``None`` computes where ``heights`` live: NumPy heights with
        the NumPy loops on the CPU; JAX heights, and arrays of other libraries that speak
        DLPack (CuPy, torch, ...), with the compiled (JAX) loops on their device, the
        result's fields returned in the heights' namespace. ``"cpu"``: the NumPy loops,
        NumPy fields. ``"cuda"`` / ``"cuda:N"``: the compiled loops on JAX's CUDA device N
        (needs ``pip install "jax[cuda12]"``); fields as CuPy arrays when CuPy is
        importable, else JAX arrays on that GPU. A free boundary or a ``callback``, which
        the compiled loops lack, runs the NumPy loops on the host (fields returned the
        same way; a RuntimeWarning says so when the solve was asked of a GPU).
        ``result.to_numpy()`` copies the fields to the host.
    dtype : {None, "float64", "float32"}, optional
        Precision of the computation; default float64. float32 halves memory and FFT
        time; its accuracy floor (measured) is in the README.

    Returns
    -------
    ContactResult
        With ``converged``, ``iterations``, ``residual`` and ``message`` — never silent.
    """
    if tol is not None:
        tolerance("tol", tol)  # (0, 1); the float32 floor is checked with the precision
    max_iter = MAX_ITER.check("max_iter", max_iter)
    interaction = HardWall() if interaction is None else _law(interaction, substrate)
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
            device=device,
            dtype=dtype,
        )
    if (load is None) == (offset is None):
        raise ParameterError("give exactly one of load (mean pressure) or offset")
    minimize = minimize_energy_bounded if interaction.hard_core else minimize_energy
    if is_jax_array(heights):  # the compiled loops (jax is imported only here)
        from ._adhesive_jax import minimize_energy_bounded_jax, minimize_energy_jax

        minimize = minimize_energy_bounded_jax if interaction.hard_core else minimize_energy_jax
    kwargs = {"initial": initial, "tol": tol, "max_iter": max_iter, "callback": callback}
    kwargs |= {"device": device, "dtype": dtype}
    if offset is not None:
        return minimize(heights, substrate, interaction, offset=offset, **kwargs)
    if not math.isfinite(float(load)):
        raise ParameterError(f"load must be finite, got {load!r}")
    if is_jax_array(heights):
        from ._pk_jax import check_jax_inputs

        # the compiled loops' checks first (one line each), then load control's, which runs
        # the compiled loop as its minimiser (the load inside its one minimisation:
        # ``takes_load``; where the NumPy loop falls back to the offset search around nested
        # solves, that search around compiled solves, each warm-started on the device)
        kwargs["dtype"] = check_jax_inputs(heights, substrate, dtype, device, callback)
    return solve_at_load(minimize, heights, substrate, interaction, load=load, **kwargs)


def _law(interaction, substrate):
    """``interaction`` as a law object: a registry name (``"hardwall"``, ...) is built by
    :func:`roughcontact.interactions.registry.make_law` (a law that needs parameters says
    which); anything that is not a law is a one-line ParameterError."""
    if isinstance(interaction, str):
        from ..interactions.registry import make_law

        return make_law(
            interaction,
            contact_modulus=getattr(substrate, "contact_modulus", 1.0),
            pixel_size=getattr(substrate, "pixel_size", 1.0),
        )
    if not isinstance(interaction, HardWall) and not hasattr(interaction, "hard_core"):
        from ..interactions.registry import names

        raise ParameterError(
            "interaction must be a law of roughcontact.interactions (e.g. HardWall(), "
            f"LJ93Smooth(...)) or one of the names {', '.join(names())}, got "
            f"{type(interaction).__name__} {interaction!r}"[:300]
        )
    return interaction
