r"""What every stickiness criterion reads: material, interaction and surface statistics.

One :class:`CriterionInputs` holds the inputs of all criteria in one consistent set of
units (lattice units: lengths in a0, pressures in E*; or SI: m, Pa, J/m^2):

* ``contact_modulus`` E*, ``work_of_adhesion`` w, ``interaction_range`` Δr;
* the spectral moments of the isotropic surface, written with the 2D power spectrum
  C(q) normalised so that :math:`h_{rms}^2 = \int d^2q\, C(q)`:

  .. math::
      M_k = \int d^2q\, |q|^k C(q), \qquad h_{rms}^2 = M_0,\;
      h'^2_{rms} = M_2,\; h''^2_{rms} = M_4,

  and the variance of the half derivative :math:`\langle|\nabla^{1/2}h|^2\rangle = M_1`
  (the elastic energy of full contact is :math:`(E^*/4) M_1`);
* the summit statistics of Nayak and McCool
  (:func:`roughcontact.theory.greenwood_williamson.summit_statistics`, profile moments
  ``m0 = M0``, ``m2 = M2/2``, ``m4 = 3 M4/8``);
* optionally the Hurst exponent H and Young's modulus E (Dahlquist's rule).

:func:`self_affine_inputs` computes the moments in closed form for the self-affine
spectrum of :func:`roughcontact.self_affine` (``C ∝ q^(-2-2H)`` between
``q_L = 2π/L`` and ``q_s = 2π/λs``, constant below ``q_L`` down to ``2π/size`` with the
roll-off, normalised to the given h'rms); :func:`inputs_from_heights` measures them on a
periodic height map (spectral derivatives).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from .._validate import ParameterError, json_ready, positive
from ..spectra import mode_power, moments, separable_hann

__all__ = [
    "CriterionInputs",
    "inputs_from_criterion",
    "inputs_from_heights",
    "inputs_from_scale_statistics",
    "self_affine_inputs",
    "self_affine_moments",
]

UNITS = ("lattice", "SI")


@dataclass(frozen=True)
class CriterionInputs:
    """Inputs of the stickiness criteria, in one consistent set of units.

    Attributes
    ----------
    contact_modulus : float
        E* [pressure].
    work_of_adhesion : float
        w [pressure × length].
    interaction_range : float
        Δr [length] (NaN when unknown: criteria that need it give no verdict).
    rms_height, rms_slope, rms_curvature : float
        h_rms [length], h'_rms [1], h''_rms [1/length].
    half_derivative_variance : float
        :math:`M_1 = \\int d^2q |q| C(q)` [length] (NaN when unknown).
    hurst : float
        Hurst exponent H (NaN when unknown).
    youngs_modulus : float
        E [pressure] for Dahlquist's rule (NaN: E* is used instead).
    units : str
        ``"lattice"`` (a0, E*) or ``"SI"`` (m, Pa, J/m^2).
    source : str
        Where the surface statistics come from, in words.
    """

    contact_modulus: float
    work_of_adhesion: float
    interaction_range: float
    rms_height: float
    rms_slope: float
    rms_curvature: float
    half_derivative_variance: float = math.nan
    hurst: float = math.nan
    youngs_modulus: float = math.nan
    units: str = "lattice"
    source: str = "given"

    def __post_init__(self):
        for name in ("contact_modulus", "work_of_adhesion", "rms_slope"):
            positive(name, getattr(self, name))
        for name in ("interaction_range", "rms_height", "rms_curvature",
                     "half_derivative_variance", "youngs_modulus"):  # fmt: skip
            v = float(getattr(self, name))
            if not (math.isnan(v) or (math.isfinite(v) and v > 0)):
                raise ParameterError(f"{name} must be > 0 and finite (or NaN: unknown), got {v!r}")
        if self.units not in UNITS:
            raise ParameterError(f"units must be one of {UNITS}, got {self.units!r}")

    @property
    def adhesion_length(self) -> float:
        """ℓa = w/E* [length]."""
        return self.work_of_adhesion / self.contact_modulus

    def summits(self):
        """Nayak/McCool :class:`~roughcontact.theory.greenwood_williamson.SummitStatistics`
        (None when h_rms or h''_rms is unknown)."""
        from ..theory.greenwood_williamson import summit_statistics

        if math.isnan(self.rms_height) or math.isnan(self.rms_curvature):
            return None
        return summit_statistics(
            self.rms_height**2, self.rms_slope**2 / 2.0, 3.0 * self.rms_curvature**2 / 8.0
        )

    def with_material(self, **changes) -> CriterionInputs:
        """A copy with some fields changed (e.g. another w or E*)."""
        return replace(self, **changes)

    def to_dict(self) -> dict:
        out = json_ready(self)
        out["adhesion_length"] = self.adhesion_length
        return out


def _power_integral(k: float, a: float, b: float, exponent: float) -> float:
    """∫_a^b q^(k+1) q^exponent dq (the 2π of d²q left out)."""
    p = k + 1.0 + exponent
    if abs(p + 1.0) < 1e-12:
        return math.log(b / a)
    return (b ** (p + 1.0) - a ** (p + 1.0)) / (p + 1.0)


def self_affine_moments(
    *,
    hurst,
    rms_slope=None,
    short_cutoff,
    long_cutoff,
    size=None,
    rolloff=True,
    orders=(0, 1, 2, 4),
    rms_height=None,
) -> dict:
    """Closed-form moments ``M_k = ∫ d²q |q|^k C(q)`` of the self-affine spectrum.

    ``C(q) = C0 (q/q_L)^(-2-2H)`` for ``q_L <= q <= q_s`` and ``C0`` for
    ``2π/size <= q < q_L`` (``rolloff``; nothing below q_L without it), normalised so that
    ``M_2 = h'_rms^2`` (or ``M_0 = h_rms^2`` when ``rms_height`` is given instead).
    Continuum integrals: a periodic grid sums the same spectrum over
    its discrete wavevectors, which differ by a few per cent for a few hundred modes.

    Parameters
    ----------
    hurst : float
        H in (0, 1].
    rms_slope : float
        h'_rms > 0. Give exactly one of ``rms_slope`` and ``rms_height`` [length].
    short_cutoff, long_cutoff : float
        λs < L [length].
    size : float, optional
        The period (system size) [length]; needed with ``rolloff``. Default ``long_cutoff``.
    rolloff : bool
        Constant spectrum below q_L (down to 2π/size).
    orders : sequence of float
        The k to return.

    Returns
    -------
    dict
        ``{k: M_k}`` [length^(2-k)].
    """
    H = positive("hurst", hurst)
    if H > 1:
        raise ParameterError(f"hurst must be in (0, 1], got {hurst!r}")
    if (rms_slope is None) == (rms_height is None):
        raise ParameterError("give exactly one of rms_slope and rms_height")
    lam_s = positive("short_cutoff", short_cutoff)
    lam_L = positive("long_cutoff", long_cutoff)
    if lam_s >= lam_L:
        raise ParameterError(f"short_cutoff ({lam_s}) must be < long_cutoff ({lam_L})")
    size = lam_L if size is None else positive("size", size)
    q_s, q_L, q_min = 2 * math.pi / lam_s, 2 * math.pi / lam_L, 2 * math.pi / size

    def raw(k):
        # C0 = 1 at q_L: C = (q/q_L)^(-2-2H) above, 1 below
        m = q_L ** (2 + 2 * H) * _power_integral(k, q_L, q_s, -2.0 - 2.0 * H)
        if rolloff and q_min < q_L:
            m += _power_integral(k, q_min, q_L, 0.0)
        return 2.0 * math.pi * m

    if rms_slope is not None:
        scale = positive("rms_slope", rms_slope) ** 2 / raw(2)
    else:
        scale = positive("rms_height", rms_height) ** 2 / raw(0)
    return {k: scale * raw(k) for k in orders}


def self_affine_inputs(
    *,
    hurst,
    rms_slope=None,
    short_cutoff,
    long_cutoff,
    contact_modulus,
    work_of_adhesion,
    interaction_range=math.nan,
    size=None,
    rolloff=True,
    youngs_modulus=math.nan,
    units="lattice",
    rms_height=None,
) -> CriterionInputs:
    """:class:`CriterionInputs` of a self-affine surface from its spectrum in closed form
    (:func:`self_affine_moments`: one of ``rms_slope`` and ``rms_height``; lengths,
    pressures in consistent units)."""
    m = self_affine_moments(
        hurst=hurst, rms_slope=rms_slope, short_cutoff=short_cutoff,
        long_cutoff=long_cutoff, size=size, rolloff=rolloff, rms_height=rms_height,
    )  # fmt: skip
    return _from_moments(
        m, contact_modulus=contact_modulus, work_of_adhesion=work_of_adhesion,
        interaction_range=interaction_range, hurst=hurst, youngs_modulus=youngs_modulus,
        units=units, source="self-affine spectrum (closed form)",
    )  # fmt: skip


def _from_moments(m, *, contact_modulus, work_of_adhesion, interaction_range, hurst,
                  youngs_modulus, units, source) -> CriterionInputs:  # fmt: skip
    """:class:`CriterionInputs` from the spectral moments ``m[k] = M_k`` (k = 0, 1, 2, 4)."""
    return CriterionInputs(
        contact_modulus=float(contact_modulus),
        work_of_adhesion=float(work_of_adhesion),
        interaction_range=float(interaction_range),
        rms_height=math.sqrt(m[0]),
        rms_slope=math.sqrt(m[2]),
        rms_curvature=math.sqrt(m[4]),
        half_derivative_variance=m[1],
        hurst=float(hurst),
        youngs_modulus=float(youngs_modulus),
        units=units,
        source=source,
    )


def inputs_from_heights(
    heights,
    *,
    contact_modulus,
    work_of_adhesion,
    interaction_range=math.nan,
    pixel_size=1.0,
    hurst=math.nan,
    youngs_modulus=math.nan,
    units="lattice",
    periodic=True,
) -> CriterionInputs:
    """:class:`CriterionInputs` measured on a height map.

    ``M_k`` are sums over the discrete wavevectors of ``|FFT(h)|^2``
    (:func:`roughcontact.spectra.mode_power` and :func:`~roughcontact.spectra.moments`:
    spectral derivatives; the mean removed), ``heights`` [length] on a grid of ``pixel_size``.
    ``periodic=False`` (a measured scan, a window of a larger surface): the mean plane is
    removed and a 2D Hann window applied, its power loss divided out, so that the edges
    do not add spurious short-wavelength power (the moments are then estimates).
    """
    h = np.asarray(heights, dtype=float)
    if h.ndim != 2 or min(h.shape) < 2 or not np.all(np.isfinite(h)):
        raise ParameterError("heights must be a finite 2D array of at least 2 x 2")
    a = positive("pixel_size", pixel_size)
    nx, ny = h.shape
    h = h - h.mean()
    if not periodic:
        i, j = np.meshgrid(np.arange(nx), np.arange(ny), indexing="ij")
        A = np.column_stack([i.ravel(), j.ravel(), np.ones(h.size)])
        h = h - (A @ np.linalg.lstsq(A, h.ravel(), rcond=None)[0]).reshape(h.shape)
        window = separable_hann(h.shape)
        h = h * window / math.sqrt(float(np.mean(window**2)))
    m = moments(*mode_power(h, (a, a)), orders=(0, 1, 2, 4))
    return _from_moments(
        m, contact_modulus=contact_modulus, work_of_adhesion=work_of_adhesion,
        interaction_range=interaction_range, hurst=hurst, youngs_modulus=youngs_modulus,
        units=units,
        source="height map (spectral moments" + ("" if periodic else ", Hann window") + ")",
    )  # fmt: skip


def inputs_from_criterion(
    result, *, rms_height=None, hurst=None, short_cutoff=None, long_cutoff=None
) -> CriterionInputs:
    """SI :class:`CriterionInputs` from a :class:`roughcontact.criterion.StickinessCriterion`.

    h''rms is the result's (or ``4 h'rms/d_rep`` when d_rep was given). With ``hurst``,
    ``short_cutoff`` and ``long_cutoff`` [m] the spectrum's moments come in closed form,
    normalised to the result's h'rms (h_rms and M_1 then follow; h''rms stays the
    given one); ``rms_height`` [m] overrides h_rms. Without them h_rms and M_1 are
    unknown (NaN) and the criteria that need them give no verdict.
    """
    curv = result.rms_curvature
    if not math.isfinite(curv):
        curv = 4.0 * result.rms_slope / result.d_rep
    h_rms = m1 = math.nan
    H = math.nan
    spectral = (hurst, short_cutoff, long_cutoff)
    if any(v is not None for v in spectral):
        if any(v is None for v in spectral):
            raise ParameterError(
                "give all of hurst, short_cutoff and long_cutoff "
                "(--hurst, --short-cutoff, --long-cutoff) or none"
            )
        H = float(hurst)
        m = self_affine_moments(hurst=H, rms_slope=result.rms_slope,
                                short_cutoff=short_cutoff, long_cutoff=long_cutoff)  # fmt: skip
        h_rms, m1 = math.sqrt(m[0]), m[1]
    if rms_height is not None:
        h_rms = positive("rms_height", rms_height)
    return CriterionInputs(
        contact_modulus=result.contact_modulus,
        work_of_adhesion=result.work_of_adhesion,
        interaction_range=result.interaction_range,
        rms_height=h_rms,
        rms_slope=result.rms_slope,
        rms_curvature=curv,
        half_derivative_variance=m1,
        hurst=H,
        youngs_modulus=result.youngs_modulus,
        units="SI",
        source="roughcontact criterion inputs"
        + (" and the self-affine spectrum (closed form)" if math.isfinite(m1) else ""),
    )


def inputs_from_scale_statistics(
    stats, *, contact_modulus, work_of_adhesion, interaction_range=math.nan,
    youngs_modulus=math.nan,
) -> CriterionInputs:  # fmt: skip
    r""":class:`CriterionInputs` of a measured scan at its measured scale (SI).

    ``stats`` is the scan's :class:`~roughcontact.topography.statistics.ScaleStatistics`
    (windowed PSD, lengths in m): h_rms, h'_rms and h''_rms are its measured values (roughness
    down to ``stats.measured_scale``, the instrument's reliable range), and
    :math:`M_1 = \int d^2q\, |q| C(q)` is summed over the same (windowed) Fourier modes with
    :math:`|q| \le 2\pi/\lambda_c`. For a profile (C1D, isotropy assumed) the 2D moment is
    :math:`M_1 = (\pi/2) \int dq_x |q_x| C^{1D}(q_x)`, since :math:`\langle|\cos\theta|\rangle
    = 2/\pi` over directions. ``contact_modulus``/``youngs_modulus`` [Pa],
    ``work_of_adhesion`` [J/m^2], ``interaction_range`` [m]. Roughness finer than the
    measured scale is not in these inputs: every criterion's verdict is at that scale.
    """
    modes = stats.modes  # each Fourier mode's share p of <h^2> (Parseval), by |q|
    keep = modes.q <= 2 * np.pi / float(stats.measured_scale) * (1 + 1e-12)
    m1 = float(np.sum((modes.q * modes.p)[keep]))
    if modes.dim == 1:
        m1 *= np.pi / 2
    return CriterionInputs(
        contact_modulus=float(contact_modulus),
        work_of_adhesion=float(work_of_adhesion),
        interaction_range=float(interaction_range),
        rms_height=float(stats.rms_height),
        rms_slope=float(stats.rms_slope),
        rms_curvature=float(stats.rms_curvature),
        half_derivative_variance=m1 if m1 > 0 else math.nan,
        hurst=float(stats.fit.hurst) if 0 < float(stats.fit.hurst) < 1 else math.nan,
        youngs_modulus=float(youngs_modulus),
        units="SI",
        source=f"the scan's Fourier modes ({modes.window} window) down to its measured scale",
    )
