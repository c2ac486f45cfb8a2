r"""Is my surface sticky? Eq. 10 of Pastewka & Robbins (2014) for a measured scan (SI).

It reads and detrends the scan, finds the instrument's limits, computes the
scale-dependent statistics and returns the verdict of Eq. 10 against the smallest
roughness scale (how it is swept and why: :mod:`~roughcontact.topography.sweep`), the
verdict under the other kappa_rep, every note and, on request, the simulation.

The pieces live in their own modules and are importable from here as before:
:mod:`~roughcontact.topography.sweep` (:class:`Verdict`, :func:`stickiness_verdict`),
:mod:`~roughcontact.topography.result` (:class:`StickResult`, :data:`UNITS`),
:mod:`~roughcontact.topography.fitrange` (where the spectrum is good),
:mod:`~roughcontact.topography.notes` (what the user is told).
"""

from __future__ import annotations

import numpy as np

from .._validate import ParameterError, positive
from ..criterion import parse_quantity
from ..theory.pastewka_robbins import KAPPA_REP
from ._text import length_text as _length_text
from .fitrange import good_range, self_affine_problem
from .notes import PAPER_WALL_KAPPA_REP, kappa_rep_check, notes_for
from .result import UNITS, StickResult
from .statistics import FIT_LONG_FRACTION, FIT_SHORT_PIXELS, scale_statistics
from .sweep import HURST_SIGMAS, Verdict, stickiness_verdict

__all__ = [
    "PAPER_WALL_KAPPA_REP",
    "UNITS",
    "StickResult",
    "Verdict",
    "_length_text",
    "stick",
    "stickiness_verdict",
]


def _length(name, value):
    if value is None:
        return None
    return positive(name, parse_quantity(value, "length", name))


def stick(
    scan,
    *,
    modulus,
    work_of_adhesion,
    interaction_range="0.5 nm",
    poisson=None,
    tip_radius=None,
    channel=None,
    detrend="plane",
    kappa_rep=KAPPA_REP,
    atomic_spacing="0.3 nm",
    pixel_size=None,
    height_unit=None,
    periodic=False,
    reliability_cutoff=None,
    fit_range=None,
    hurst_sigmas: float = HURST_SIGMAS,
    simulate: bool = False,
    simulate_size: int = 256,
    simulate_seeds: int = 3,
    simulate_progress=None,
    fill_missing=None,
    counter_modulus=None,
    counter_poisson=None,
    outliers="remove",
) -> StickResult:
    """Is this measured surface sticky? Pastewka & Robbins (2014), Eq. 10, for a scan.

    Reads the scan (filling a few missing points, see ``fill_missing``), detrends it,
    computes its PSD and scale-dependent slope and curvature
    (:mod:`roughcontact.topography.statistics`), finds the wavelengths between the
    instrument's resolution limit or noise floor and a quarter of the scan
    (:func:`~roughcontact.topography.fitrange.good_range`; the measured scale moves up
    to the limit found), fits the Hurst exponent there, and evaluates Eq. 10 for every
    smallest roughness scale from the measured scale down to the atomic spacing
    (:func:`stickiness_verdict`). When the spectrum there is not self-affine (H outside
    (0, 1) or a poor fit) nothing is extrapolated: the verdict is the measured scale's.
    The verdict is repeated with the other kappa_rep (2, the continuum hard wall, and
    :data:`PAPER_WALL_KAPPA_REP`, the paper's wall, or the simulation's own).

    Parameters
    ----------
    scan : path-like or Topography
        An instrument, ``.npy`` or text file (read by ``load_topography``) or a
        ``Topography`` in metres.
    modulus : float or str
        The scanned body's plane-strain modulus E/(1 - nu^2) (without ``poisson``) or its
        Young's modulus E (with it) [Pa], e.g. ``"10 MPa"``; against a rigid
        counter-surface unless ``counter_modulus`` is given.
    work_of_adhesion : float or str
        w [J/m^2], e.g. ``"50 mJ/m^2"``.
    interaction_range : float or str
        Delta_r [m], default ``"0.5 nm"``.
    poisson : float, optional
        Poisson ratio in (-1, 0.5]: ``modulus`` is then Young's modulus.
    tip_radius : float or str, optional
        Radius of the scanning probe [m]: sets the reliability cutoff (below which the
        tip cannot follow the surface) through ``reliability_cutoff(topo, tip_radius)``
        (Sanner et al. 2022); without it, the radius stored in the file if any. The
        cutoff length is taken as the shortest reliable wavelength, as SurfaceTopography
        does (its PSD keeps ``q < 2 pi/cutoff``).
    channel : str, optional
        The data channel of a multi-channel file.
    detrend : str
        How to detrend before the analysis (``detrend(topo, mode=...)``), default
        ``"plane"``.
    kappa_rep : float
        The non-adhesive prefactor, default 2 (the paper's choice).
    atomic_spacing : float or str
        a0 [m], the smallest roughness scale considered, default ``"0.3 nm"``.
    pixel_size, height_unit : optional
        For files without units (``.npy``, text): grid spacing [m] and the heights' unit.
    periodic : bool
        Whether a file's scan is one period of a periodic surface (no window).
    reliability_cutoff : float or str, optional
        The shortest reliable wavelength [m], instead of ``tip_radius``; the user's word:
        no search for the instrument's limits in the PSD then.
    fit_range : (float, float), optional
        Wavelengths [m] of the Hurst fit (default: from the measured scale, after the
        instrument's limits, or 4 pixels, to a quarter of the scan).
    hurst_sigmas : float
        Half-width of the H band in standard errors, default 2 (about 95 %), at most 10.
    simulate : bool
        Also run the paper's simulation on synthetic surfaces continuing the scan's
        spectrum down to ``atomic_spacing`` (:func:`~.simulate.simulate_stickiness`;
        seconds to minutes; the wall has the ``interaction_range`` asked for and
        ``l_a/a0 = w/(E* a0)`` in :data:`~.simulate.ADHESION_RANGE_GIVEN`).
    simulate_size, simulate_seeds : int
        Sites per axis of the synthetic surfaces (default 256, in [64, 1024]) and their
        number (default 3, in [1, 32]).
    simulate_progress : callable, optional
        ``simulate_progress(k, seeds)`` before realisation k.
    fill_missing : bool or None
        Missing points (NaN or masked by the instrument): None (default) fills up to
        :data:`~roughcontact.topography.read.MISSING_FILL_MAX` of the scan by harmonic
        interpolation, with a note, and refuses more; True fills any fraction (with a
        note stating it); False refuses any.
    outliers : {"remove", "keep"}
        Spikes, sentinel values and isolated pixels (the rule of
        :mod:`roughcontact.topography.outliers`): "remove" (default) treats them as
        missing points (filled by harmonic interpolation, under ``fill_missing``'s
        limit), "keep" analyses them as heights; either way they are counted in a note
        and in ``to_dict()["outliers"]``.
    counter_modulus, counter_poisson : float or str, optional
        The counter-surface's Young's modulus and Poisson ratio (or its plane-strain
        modulus without ``counter_poisson``): ``1/E* = (1-nu1^2)/E1 + (1-nu2^2)/E2``
        (:func:`roughcontact.moduli.composite_modulus`). Default: rigid.

    Returns
    -------
    StickResult
        ``.sticky`` (True, False or None), ``.margin``, ``.verdict``, ``.to_dict()``.
    """
    from ..moduli import composite_modulus
    from .topography import Topography

    moduli = composite_modulus(modulus, poisson, counter_modulus, counter_poisson)
    if simulate:
        from .simulate import check_options

        check_options(simulate_size, simulate_seeds)  # before any work
    tip = _length("tip_radius", tip_radius)
    given_cutoff = _length("reliability_cutoff", reliability_cutoff)
    if tip is not None and given_cutoff is not None:
        raise ParameterError("give tip_radius or reliability_cutoff, not both")
    topo = _read(
        scan, channel, pixel_size, height_unit, periodic, fill_missing, Topography, outliers
    )
    from .._plausibility import check_heights

    check_heights(topo.heights, "scan")  # |h| past 1e150 is out of range, not "flat"
    raw = float(np.std(topo.heights))
    topo = _detrend(topo, detrend)
    if not float(np.std(topo.heights)) > 1e-12 * raw:  # what is left is round-off
        raise ParameterError(f"scan is flat after detrend={detrend!r}: no roughness to analyse")
    notes = []
    from .fitrange import clamp_fit_range

    fit_range, clamped = clamp_fit_range(fit_range, topo.pixel_size, topo.shape)
    if clamped:
        notes.append(clamped)
    cutoff, tip_source, cutoff_source = given_cutoff, "not used", "reliability_cutoff"
    if cutoff is None:
        from .prepare import reliability_cutoff as tip_cutoff

        reliability = tip_cutoff(topo, tip)
        if reliability.all_scales:
            raise ParameterError(f"scan: {reliability.message}")
        cutoff, tip, tip_source = (
            reliability.cutoff,
            reliability.tip_radius,
            reliability.tip_radius_source,
        )
        cutoff_source = "tip radius" if cutoff is not None else "none (Nyquist wavelength)"
        notes.append(_tip_note(topo, reliability))
    stats, good, problem, cutoff_source = _statistics(
        topo, cutoff, fit_range, detect=given_cutoff is None, source=cutoff_source
    )
    problem = problem or self_affine_problem(stats.fit)
    common = {
        "work_of_adhesion": work_of_adhesion,
        "contact_modulus": moduli.contact_modulus,
        "interaction_range": interaction_range,
        "atomic_spacing": atomic_spacing,
        "hurst_sigmas": hurst_sigmas,
        "no_extrapolation": problem,
    }
    v = stickiness_verdict(stats, kappa_rep=kappa_rep, **common)
    m = v.measured
    nu = np.nan if poisson is None else float(parse_quantity(poisson, "dimensionless", "poisson"))
    inputs = {
        "contact_modulus": m.contact_modulus,
        "youngs_modulus": np.nan if poisson is None else float(
            parse_quantity(modulus, "pressure", "modulus")),
        "poisson": nu,
        "counter_modulus": None if counter_modulus is None else moduli.counter,
        "counter_poisson": None if counter_poisson is None else float(
            parse_quantity(counter_poisson, "dimensionless", "counter_poisson")),
        "contact_modulus_formula": moduli.text,
        "work_of_adhesion": m.work_of_adhesion,
        "interaction_range": m.interaction_range,
        "kappa_rep": m.kappa_rep,
        "kappa_rep_note": "the paper's choice kappa_rep = 2 (PNAS 2014, Fig. 4)"
        if m.kappa_rep == KAPPA_REP
        else "given",
        "atomic_spacing": m.atomic_spacing,
        "adhesion_length": m.adhesion_length,
        "tip_radius": tip,
        "tip_radius_source": tip_source,
        "reliability_cutoff_source": cutoff_source,
        "detrend": detrend,
        "hurst_sigmas": float(hurst_sigmas),
        "fill_missing": fill_missing,
        "outliers": outliers,
    }  # fmt: skip
    simulation = None
    if simulate and problem:
        notes.append(
            "simulation not run: its synthetic surfaces continue the fitted spectrum below "
            "the measured scale, and there is no self-affine spectrum to continue"
        )
    elif simulate:
        from .simulate import simulate_stickiness

        simulation = simulate_stickiness(
            stats,
            contact_modulus=m.contact_modulus,
            work_of_adhesion=m.work_of_adhesion,
            atomic_spacing=m.atomic_spacing,
            interaction_range=m.interaction_range,
            size=simulate_size,
            seeds=simulate_seeds,
            progress=simulate_progress,
        )
    check = kappa_rep_check(
        v, stats, common, simulation, lambda k: stickiness_verdict(stats, kappa_rep=k, **common)
    )
    hysteresis = None
    if simulation is not None:
        from .hysteresis import simulation_hysteresis

        hysteresis = simulation_hysteresis(
            simulation, atomic_spacing=m.atomic_spacing, contact_modulus=m.contact_modulus,
            scan_area=float(np.prod(topo.pixel_size) * np.prod(topo.shape))
            if len(topo.shape) == 2 else None,
        )  # fmt: skip
    from .modelchecks import model_checks

    checks = model_checks(stats, v)
    return StickResult(
        model_checks=checks,
        criteria=_criteria(stats, m, inputs["youngs_modulus"], simulation),
        hysteresis=hysteresis,
        topography=topo,
        statistics=stats,
        verdict=v,
        inputs=inputs,
        notes=tuple(
            notes
            + notes_for(topo, stats, v, good, moduli, check)
            + [checks["monti_sanner_pastewka"]["text"]]
        ),
        simulation=simulation,
        good_range=good,
        kappa_rep_check=check,
    )


def _tip_note(topo, reliability) -> str:
    """Where the tip radius of the reliability cutoff came from, or that none is stated."""
    info = getattr(topo, "info", {}) or {}
    stated = info.get("tip_radius_stated") or {}
    if reliability.tip_radius_source == "argument":
        return f"reliability (tip radius given): {reliability.message}"
    if reliability.tip_radius_source == "file":
        return (
            f"reliability (tip radius stated in the file, {stated.get('text', '?')!r}, used "
            f"for the cutoff, Sanner et al. 2022): {reliability.message}"
        )
    if stated.get("unreadable"):
        return (
            f"the file states a tip radius {stated.get('text')!r} whose unit is not a length: "
            "not used; give --tip-radius (tip_radius=) for a tip-based reliability cutoff"
        )
    what = "the file states" if info.get("format") not in ("npy", "text", None) else (
        "a .npy or text file states"
    )
    return (
        f"{what} no tip or stylus radius: no tip-based reliability cutoff; give "
        "--tip-radius (tip_radius=) if you know it"
    )


def _criteria(stats, measured, youngs_modulus, simulation) -> dict:
    """The field's criteria side by side at the measured scale (:mod:`roughcontact.stickiness`)."""
    from ..stickiness import criteria_table
    from ..stickiness.inputs import inputs_from_scale_statistics

    inputs = inputs_from_scale_statistics(
        stats, contact_modulus=measured.contact_modulus,
        work_of_adhesion=measured.work_of_adhesion,
        interaction_range=measured.interaction_range, youngs_modulus=youngs_modulus,
    )  # fmt: skip
    table = criteria_table(inputs, simulated=None if simulation is None else simulation.verdict)
    table["scale"] = float(stats.measured_scale)
    return table


def _statistics(topo, cutoff, fit_range, *, detect, source):
    """The scan's statistics with the measured scale and fit range between the
    instrument's limits (:func:`~.fitrange.good_range`; only when the reliability
    cutoff was not given). Returns ``(stats, good_range, problem, cutoff_source)``."""
    kw = {"periodic": topo.periodic, "fit_range": fit_range}
    stats = scale_statistics(topo.heights, topo.pixel_size, reliability_cutoff=cutoff, **kw)
    if not detect:
        return stats, None, "", source
    size = min(n * a for n, a in zip(topo.shape, topo.pixel_size, strict=True))
    long = size / FIT_LONG_FRACTION
    if fit_range is not None:
        long = max(long, float(fit_range[1]))
    good = good_range(stats.psd, stats.measured_scale, long)
    if good.short <= stats.measured_scale * (1 + 1e-9):
        return stats, good, "", source
    problem = ""
    if not good.usable:
        problem = (
            f"less than an octave of the spectrum lies between the instrument's limits "
            f"({_length_text(good.short)} to {_length_text(good.long)})"
        )
        kw["fit_range"] = stats.fit.scale_range
        new_cutoff = min(good.short, size / FIT_LONG_FRACTION)
    else:
        new_cutoff = good.short
        if fit_range is None:
            kw["fit_range"] = (max(good.short, FIT_SHORT_PIXELS * max(topo.pixel_size)), long)
    stats = scale_statistics(topo.heights, topo.pixel_size, reliability_cutoff=new_cutoff, **kw)
    what = "noise floor" if good.noise_floor is not None else "resolution limit"
    return stats, good, problem, f"instrument {what} (detected in the PSD)"


def _read(scan, channel, pixel_size, height_unit, periodic, fill_missing, Topography, outliers):
    """The scan as a Topography in metres (a file read by ``load_topography``), its
    outliers removed or kept (:mod:`.outliers`)."""
    from .outliers import OUTLIER_MODES

    if outliers not in OUTLIER_MODES:
        raise ParameterError(
            f"outliers must be one of {', '.join(OUTLIER_MODES)}, got {outliers!r}"
        )
    if isinstance(scan, Topography):
        if channel is not None or pixel_size is not None or height_unit is not None:
            raise ParameterError(
                "channel, pixel_size and height_unit apply to a file, not to a Topography"
            )
        topo = _topography_outliers(scan, outliers, fill_missing)
    else:
        from .read import load_topography

        px = pixel_size
        given = [] if px is None else list(px) if isinstance(px, (tuple, list)) else [px]
        bare = [str(p).strip() for p in given if isinstance(p, str) and _is_number(p)]
        if px is not None and not isinstance(px, (tuple, list)):
            px = _length("pixel_size", px)
        elif px is not None:
            px = tuple(_length("pixel_size", p) for p in px)
        topo = load_topography(
            scan, channel=channel, periodic=bool(periodic), pixel_size=px,
            height_unit=height_unit, fill_missing=fill_missing, outliers=outliers,
        )  # fmt: skip
    if topo.length_unit != "m":
        raise ParameterError(
            "scan has no length unit (lattice units): give pixel_size (m) and height_unit "
            "for a file without units, e.g. pixel_size='10 nm', height_unit='nm'"
        )
    if not isinstance(scan, Topography) and topo.info.get("format") in ("npy", "text"):
        topo = _plausible_units(topo, bare, height_unit)
    return topo


def _is_number(text) -> bool:
    try:
        float(str(text).strip())
    except ValueError:
        return False
    return True


def _plausible_units(topo, bare, height_unit):
    """A .npy/text file's units are the caller's: the bounds of an instrument file's
    (:func:`roughcontact._plausibility.check_metres`) refuse absurd ones, and a bare
    number given as a length (metres) is said next to the result."""
    import dataclasses

    from .._plausibility import check_metres

    hint = ""
    if bare:
        hint = (
            f"; pixel_size {', '.join(repr(b) for b in bare)} has no unit and was read as "
            f"metres: give e.g. '{bare[0]} nm' (--pixel-size '{bare[0]} nm')"
        )
    if height_unit is None:
        hint += "; the heights were read as metres (no height_unit, --height-unit, given)"
    try:
        check_metres(topo.heights, topo.pixel_size, "scan")
    except ParameterError as exc:
        raise ParameterError(f"{exc}{hint}") from None
    if not bare:
        return topo
    px = ", ".join(dict.fromkeys(_length_text(a) for a in topo.pixel_size))
    warning = (
        f"pixel_size {', '.join(repr(b) for b in bare)} was given without a unit: read as "
        f"metres (pixel size {px}); if you meant another unit, give it (e.g. "
        f"--pixel-size '{bare[0]} nm')"
    )
    return dataclasses.replace(topo, info={**topo.info, "units_warning": warning})


def _topography_outliers(topo, outliers, fill_missing):
    """A Topography given in Python: its outliers found, and removed (filled as missing
    points) or kept, as for a file."""
    import dataclasses

    from .missing import missing_policy
    from .outliers import find_outliers

    found, report = find_outliers(topo.heights, periodic=topo.periodic)
    removed = outliers == "remove" and report["points"] > 0
    report = {**report, "action": "removed" if removed else "kept", "unit": topo.length_unit}
    info = {**topo.info, "outliers": report}
    if not removed:
        return dataclasses.replace(topo, info=info)
    data = np.ma.masked_array(topo.heights, mask=found)
    values, new = missing_policy(
        "scan", data, fill_missing, topo.periodic, info, outliers=report["points"]
    )
    return dataclasses.replace(topo, heights=values, info=new)


def _detrend(topo, mode):
    from .prepare import detrend

    return detrend(topo, mode=mode)
