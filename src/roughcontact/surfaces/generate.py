"""Random self-affine rough surfaces by Fourier filtering."""

from __future__ import annotations

import math

import numpy as np

from .._backend import irfft2, rfft2
from .._validate import (
    HURST,
    PIXEL_SIZE,
    ParameterError,
    fits_in_memory,
    heights2d,
    positive,
    shape2d,
    surface_seed,
)
from .statistics import statistics

__all__ = ["BYTES_PER_SITE", "self_affine"]

#: Peak memory of :func:`self_affine` per grid site (bytes; measured 52 with the
#: statistics of the result another 28 on top): the white noise, its spectrum, the
#: wavevectors, the filter and the heights, all float64 or complex128.
BYTES_PER_SITE = 64


def self_affine(
    shape,
    *,
    hurst: float,
    rms_slope: float | None = None,
    rms_height: float | None = None,
    short_cutoff: float,
    long_cutoff: float | None = None,
    rolloff: bool = True,
    pixel_size: float = 1.0,
    seed=None,
) -> np.ndarray:
    r"""Generate a periodic, self-affine random height map by Fourier filtering.

    Each Fourier component gets a random phase and a normally distributed amplitude
    (the FFT of Gaussian white noise, i.e. a complex Gaussian per wavevector whose
    modulus has mean proportional to the filter ``phi(q)``), with (Pastewka & Robbins
    2014, Methods)::

        phi(q) = 0                     for q > q_s = 2 pi / short_cutoff
        phi(q) = q^(-1-H)              for q_L <= q <= q_s,  q_L = 2 pi / long_cutoff
        phi(q) = q_L^(-1-H)            for q < q_L   (rolloff=True; 0 if rolloff=False)
        phi(0) = 0

    so that the power spectrum ``C(q) ~ phi(q)^2 ~ q^(-2(1+H))`` between the cutoffs.
    The result is real (Hermitian spectrum: the white noise is real), periodic with
    period ``L = n * pixel_size`` along each axis, has zero mean, and is rescaled so that
    the requested ``rms_slope`` or ``rms_height`` holds exactly as computed by
    :func:`roughcontact.surfaces.statistics` with ``method="spectral"``. Nyquist modes
    (row ``nx/2`` / column ``ny/2`` for even sizes, reachable only when
    ``short_cutoff == 2 * pixel_size``) are left empty, so the spectral and the
    continuum definitions of the slope agree for every generated surface.

    Parameters
    ----------
    shape : int or (int, int)
        Grid size ``(nx, ny)``; an int gives a square grid.
    hurst : float
        Hurst exponent H, ``0 < H <= 1``.
    rms_slope : float, optional
        Target ``h'_rms = <|grad h|^2>^(1/2)`` (PNAS 2014, Eq. 1), > 0 [dimensionless].
    rms_height : float, optional
        Target ``h_rms`` [length], > 0. Give exactly one of ``rms_slope``, ``rms_height``.
    short_cutoff : float
        Short-wavelength cutoff lambda_s [length], ``>= 2 * pixel_size``.
    long_cutoff : float, optional
        Long-wavelength cutoff / roll-off wavelength lambda_L [length],
        ``short_cutoff < long_cutoff <= max(nx, ny) * pixel_size``. Default
        ``min(nx, ny) * pixel_size / 2`` (the paper uses ``L = 2 lambda_L``).
    rolloff : bool, optional
        If True (default) the filter is constant for ``q < q_L``; otherwise zero there.
    pixel_size : float, optional
        Grid spacing a0 [length], in [1e-25, 1e25]. Default 1.
    seed : int, numpy.random.Generator, SeedSequence or None
        Passed to :func:`numpy.random.default_rng`; the same seed gives the same surface.
        Integers must be >= 0.

    Returns
    -------
    ndarray of float64, shape (nx, ny)
        Heights h [length]; larger h is closer to the substrate (summits are maxima).

    Raises
    ------
    ParameterError
        For out-of-range parameters (the message names the parameter and its range); for
        a grid whose generation needs more memory than is available
        (:data:`BYTES_PER_SITE` per site); for a target ``rms_height``/``rms_slope`` so
        large that the heights' rms overflows.

    References
    ----------
    L. Pastewka and M. O. Robbins, PNAS 111, 3298 (2014), Methods.
    S. B. Ramisetti et al., J. Phys.: Condens. Matter 23, 215004 (2011) (Fourier filtering).
    """
    nx, ny = shape2d("shape", shape)
    a = PIXEL_SIZE.check("pixel_size", pixel_size)
    H = HURST.check("hurst", hurst)
    seed = surface_seed("seed", seed)
    if (rms_slope is None) == (rms_height is None):
        raise ParameterError(
            "exactly one of rms_slope, rms_height must be given "
            f"(got rms_slope={rms_slope!r}, rms_height={rms_height!r})"
        )
    if rms_slope is not None:
        target, which = positive("rms_slope", rms_slope), "rms_slope"
    else:
        target, which = positive("rms_height", rms_height), "rms_height"
    lam_s = positive("short_cutoff", short_cutoff)
    if lam_s < 2 * a:
        raise ParameterError(
            f"short_cutoff must be >= 2*pixel_size = {2 * a} (the Nyquist wavelength), "
            f"got {short_cutoff!r}"
        )
    size_max = max(nx, ny) * a
    if long_cutoff is None:
        lam_L = min(nx, ny) * a / 2
    else:
        lam_L = positive("long_cutoff", long_cutoff)
    if not (lam_s < lam_L <= size_max * (1 + 1e-12)):
        raise ParameterError(
            f"long_cutoff must satisfy short_cutoff = {lam_s} < long_cutoff <= system size "
            f"{size_max}, got {lam_L}"
            + (" (the default min(nx, ny)*pixel_size/2)" if long_cutoff is None else "")
        )

    fits_in_memory(
        "shape", (nx, ny), BYTES_PER_SITE * nx * ny, f"a {nx}x{ny} surface", BYTES_PER_SITE
    )
    try:
        rng = np.random.default_rng(seed)
    except (TypeError, ValueError) as err:
        raise ParameterError(
            f"seed must be an integer >= 0, a Generator or None, got {seed!r} ({err})"
        ) from None
    noise = rng.standard_normal((nx, ny))
    F = rfft2(noise)

    qx = 2 * np.pi * np.fft.fftfreq(nx, d=a)[:, None]
    qy = 2 * np.pi * np.fft.rfftfreq(ny, d=a)[None, :]
    q = np.sqrt(qx**2 + qy**2)
    q_s, q_L = 2 * np.pi / lam_s, 2 * np.pi / lam_L
    tol = 1e-12
    with np.errstate(divide="ignore"):
        phi = np.where(q >= q_L * (1 - tol), q ** (-1.0 - H), q_L ** (-1.0 - H) if rolloff else 0.0)
    phi[q > q_s * (1 + tol)] = 0.0
    phi[0, 0] = 0.0
    if nx % 2 == 0:
        phi[nx // 2, :] = 0.0
    if ny % 2 == 0:
        phi[:, ny // 2] = 0.0
    if not np.any(phi > 0):
        raise ParameterError(
            f"no wavevector of the {nx}x{ny} grid lies between the cutoffs "
            f"(short_cutoff={lam_s}, long_cutoff={lam_L}, rolloff={rolloff}); "
            "widen the band or enlarge the grid"
        )
    h = np.asarray(irfft2(F * phi, (nx, ny)), dtype=np.float64)
    h -= h.mean()

    s = statistics(h, pixel_size=a, method="spectral")
    current = s.rms_slope if which == "rms_slope" else s.rms_height
    if not current > 0 or not math.isfinite(current):
        raise ParameterError(
            f"cannot normalise to {which}: the filtered surface has {which} = {current}"
        )
    h *= target / current
    try:
        heights2d("heights", h)
    except ParameterError as err:
        raise ParameterError(f"{which} = {target!r} is too large: {err}") from None
    return h
