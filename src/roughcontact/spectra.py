r"""The one definition of the power spectrum: Fourier modes, normalisation, windows, bins.

Every spectrum and spectral moment of the package is built from the pieces here:
:func:`roughcontact.surfaces.power_spectrum` and the rms height, slope and curvature of
:func:`roughcontact.surfaces.statistics` (one period of a surface, lattice units), the
windowed spectra of measured scans in :mod:`roughcontact.topography` (SI units) and the
moments the stickiness criteria read (:func:`roughcontact.stickiness.inputs_from_heights`).
Lengths are in any one unit; heights ``h[i, j]`` sit at ``x = i dx, y = j dy``.

**Modes and normalisation.** With the unnormalised DFT ``H(q) = sum_x h(x) exp(-i q.x)``
over ``N`` points and the angular wavevectors ``q = 2 pi fftfreq(n, d)``
(:func:`wavevectors`), each mode's share of the mean square height is (Parseval)::

    p(q) = |H(q)|^2 / N^2,     sum_{q != 0} p(q) = <(h - <h>)^2>       (mode_power)

and the power spectral density is ``C(q) = p(q) / cell`` with ``cell`` the q-space area
``(2 pi/Lx)(2 pi/Ly)`` of one mode (length ``2 pi/L`` for a profile, :func:`mode_cell`).
This is Persson's convention (Persson et al., J. Phys.: Condens. Matter 17, R1 (2005)):
``C(q) = (2 pi)^-2 \int d^2x <h(x) h(0)> exp(-i q.x)``, ``h_rms^2 = \int d^2q C(q)``.

**Moments.** ``M_k = sum_q |q|^k p(q) = \int d^2q |q|^k C(q)``: ``M_0 = h_rms^2``,
``M_2 = <|grad h|^2> = h'_rms^2``, ``M_4 = <(lap h)^2> = h''_rms^2`` (:func:`moments`).
On one period :func:`periodic_moments` evaluates ``M_0, M_2, M_4`` on any array-API
array with one convention for the **Nyquist mode**: for an even number of points along
an axis, ``cos(pi x/a0)`` has a first derivative that vanishes on every grid point, so its
*first* derivative is taken as zero (``qx = 0`` on the Nyquist row for ``M_2``, likewise
``qy``), while ``M_4`` uses the full ``q^2``. The values then equal the grid means of the
spectrally differentiated fields. Surfaces without Nyquist content (those of
:func:`roughcontact.self_affine`) give the same ``M_2`` either way.

**Windows.** Non-periodic data (a measured scan) see a jump between opposite edges; a
window tapers it (:func:`hann_1d`, :func:`radial_hann`, :func:`separable_hann`), and
:func:`window_efficiency` says how many independent modes a windowed mode is worth.

**Bins.** :func:`bin_modes` averages ``|q|`` and a per-mode value over the modes in each
bin (equal width: :func:`linear_edges`; equal ratio: :func:`log_edges`).

References
----------
B. N. J. Persson et al., J. Phys.: Condens. Matter 17, R1 (2005).
T. D. B. Jacobs, T. Junge and L. Pastewka, Surf. Topogr.: Metrol. Prop. 5, 013001 (2017).
L. Pastewka and M. O. Robbins, PNAS 111, 3298 (2014), Eqs. 1, 8, 9.
"""

from __future__ import annotations

import math

import numpy as np

from ._backend import array_device, array_namespace, is_cupy_array, is_numpy_array, rfft2

__all__ = [
    "bin_modes",
    "hann_1d",
    "linear_edges",
    "log_edges",
    "mode_cell",
    "mode_power",
    "moments",
    "periodic_moments",
    "radial_hann",
    "separable_hann",
    "wavevectors",
    "window_efficiency",
]


# --------------------------------------------------------------------------- modes


def wavevectors(n: int, spacing: float, *, real: bool = False) -> np.ndarray:
    """Angular wavenumbers ``2 pi k / (n spacing)`` of an n-point FFT [1/length].

    ``real``: the non-negative half of a real FFT (``rfftfreq``), else the full FFT
    layout (``fftfreq``: 0, positive, then negative).
    """
    freq = np.fft.rfftfreq if real else np.fft.fftfreq
    return 2 * np.pi * freq(n, d=spacing)


def mode_cell(shape, sizes) -> float:
    """q-space size of one mode: ``(2 pi/Lx)(2 pi/Ly)`` [1/length^2] for a map, ``2 pi/Lx``
    [1/length] for profiles (``len(shape) == 1``), ``L = n * spacing``."""
    if len(shape) == 2:
        return (2 * np.pi / (shape[0] * sizes[0])) * (2 * np.pi / (shape[1] * sizes[1]))
    return 2 * np.pi / (shape[0] * sizes[0])


def mode_power(h, sizes, *, profiles: bool = False):
    """Each Fourier mode's ``|q|`` [1/length] and share ``p`` of ``<h^2>`` [length^2].

    A 2D map (``profiles`` False) gives the 2D modes in the full FFT layout (arrays of
    ``h.shape``, ``q = 0`` at ``[0, 0]``). A profile, or the profiles along x of a map
    (``profiles``), gives the 1D modes along x (``|q_x|``), ``p`` averaged over a map's
    lines. ``sum(p)`` over the modes is ``<h^2>`` (Parseval); ``C = p / mode_cell``.
    """
    h = np.asarray(h)
    nx = h.shape[0]
    if h.ndim == 2 and not profiles:
        ny = h.shape[1]
        p = np.abs(np.fft.fft2(h)) ** 2 / float(nx * ny) ** 2
        qx, qy = wavevectors(nx, sizes[0]), wavevectors(ny, sizes[1])
        return np.hypot(qx[:, None], qy[None, :]), p
    p = np.abs(np.fft.fft(h, axis=0)) ** 2 / float(nx) ** 2
    if p.ndim == 2:
        p = p.mean(axis=1)
    return np.abs(wavevectors(nx, sizes[0])), p


def moments(q, p, orders=(0, 2, 4)) -> dict:
    """``{k: M_k}`` with ``M_k = sum |q|^k p`` over the modes given [length^(2-k)]."""
    return {k: float(np.sum(q**k * p)) for k in orders}


def _like(values, xp, like):
    """Host ``values`` as an array of ``like``'s namespace, on its device."""
    if like is None or is_numpy_array(like):
        return values
    if is_cupy_array(like):
        with like.device:  # CuPy allocates on the current GPU
            return xp.asarray(values)
    return xp.asarray(values, device=array_device(like))


def _rfft_wavevectors(xp, nx: int, ny: int, pixel_size: float, like):
    """Wavevectors of the rfft2 layout (shape (nx, 1) and (1, ny//2+1)) and Parseval weights.

    Returns ``qx, qy`` (full), ``qx1, qy1`` (first-derivative wavevectors, Nyquist set
    to zero) and ``weights`` counting each rfft mode for itself and its mirror image.
    """
    # built on the host and moved once: array_api_compat's fftfreq/rfftfreq take no
    # device but "cpu" (a CuPy array's device raised "Unsupported device"), and these
    # are O(n) values
    qx = wavevectors(nx, pixel_size)
    qy = wavevectors(ny, pixel_size, real=True)
    qx1, qy1 = qx.copy(), qy.copy()
    if nx % 2 == 0:
        qx1[nx // 2] = 0.0
    if ny % 2 == 0:
        qy1[ny // 2] = 0.0
    # rfft keeps ky >= 0; modes 0 < ky < ny/2 stand for themselves and their mirror.
    wy = np.full(qy.shape, 2.0)
    wy[0] = 1.0
    if ny % 2 == 0:
        wy[ny // 2] = 1.0
    qx, qy, qx1, qy1, wy = (_like(v, xp, like) for v in (qx, qy, qx1, qy1, wy))
    return (
        xp.reshape(qx, (nx, 1)),
        xp.reshape(qy, (1, -1)),
        xp.reshape(qx1, (nx, 1)),
        xp.reshape(qy1, (1, -1)),
        xp.reshape(wy, (1, -1)),
    )


def periodic_moments(h, pixel_size: float) -> tuple[float, float, float]:
    """``(M_0, M_2, M_4) = (<(h-<h>)^2>, <|grad h|^2>, <(lap h)^2>)`` of one period.

    ``h``: a 2D NumPy or array-API array (e.g. CuPy; the FFT runs on its device), heights
    [length] on a grid of ``pixel_size`` [length]. Sums over the rfft modes with the
    Nyquist convention of the module docstring. Returns [length^2, 1, 1/length^2].
    """
    xp = array_namespace(h)
    nx, ny = h.shape
    n = nx * ny
    H = rfft2(h)
    qx, qy, qx1, qy1, w = _rfft_wavevectors(xp, nx, ny, pixel_size, h)
    p = w * xp.real(H * xp.conj(H)) / float(n) ** 2
    m0 = float(xp.sum(p)) - float(p[0, 0])
    m2 = float(xp.sum((qx1**2 + qy1**2) * p))
    m4 = float(xp.sum((qx**2 + qy**2) ** 2 * p))
    return max(m0, 0.0), m2, m4


# --------------------------------------------------------------------------- windows


def hann_1d(n: int) -> np.ndarray:
    """SciPy's periodic Hann window of n points, scaled to a mean square of 1."""
    from scipy.signal import get_window

    w = get_window("hann", n)
    return w * math.sqrt(n / float(np.sum(w * w)))


def radial_hann(shape, sizes) -> np.ndarray:
    """The rotationally symmetric Hann window of a map, ``w(r) = [1 + cos(pi r/r_max)]/2``
    (``r_max = min(Lx, Ly)/2``, 0 beyond), scaled to a mean square of 1."""
    nx, ny = shape
    x = sizes[0] * (np.arange(nx) - nx // 2)
    y = sizes[1] * (np.arange(ny) - ny // 2)
    r = np.hypot(x[:, None], y[None, :])
    r_max = min(nx * sizes[0], ny * sizes[1]) / 2
    w = np.where(r <= r_max, 0.5 + 0.5 * np.cos(np.pi * r / r_max), 0.0)
    return w * math.sqrt(w.size / float(np.sum(w * w)))


def separable_hann(shape) -> np.ndarray:
    """NumPy's symmetric Hann window along each axis of a map, multiplied (not rescaled:
    divide the windowed data by ``sqrt(mean(w^2))`` to keep ``<h^2>``)."""
    return np.outer(np.hanning(shape[0]), np.hanning(shape[1]))


def window_efficiency(w) -> float:
    """Independent modes per mode, ``<w^2>^2/<w^4>``, of a window scaled to ``<w^2> = 1``."""
    return 1.0 / float(np.mean(w**4))


# --------------------------------------------------------------------------- bins


def linear_edges(q_max: float, nbins: int) -> np.ndarray:
    """``nbins`` equal-width bins of ``|q|`` from 0 to ``q_max``."""
    return np.linspace(0.0, q_max, int(nbins) + 1)


def log_edges(q_min: float, q_max: float, points_per_decade: int) -> np.ndarray:
    """Log-spaced bins from ``q_min`` to ``q_max``, ``points_per_decade`` per decade."""
    nb = max(1, math.ceil(math.log10(q_max / q_min) * points_per_decade)) if q_max > q_min else 1
    return np.geomspace(q_min, q_max, nb + 1)


def bin_modes(q, values, edges):
    """Average ``|q|`` and ``values`` over the modes in each bin of ``edges``.

    Modes on or past the last edge count in the last bin. Returns the mean ``|q|``, the
    mean value and the number of modes of each non-empty bin.
    """
    nb = len(edges) - 1
    idx = np.clip(np.searchsorted(edges, q, side="right") - 1, 0, nb - 1)
    counts = np.bincount(idx, minlength=nb)
    keep = counts > 0
    qb = np.bincount(idx, weights=q, minlength=nb)[keep] / counts[keep]
    vb = np.bincount(idx, weights=values, minlength=nb)[keep] / counts[keep]
    return qb, vb, counts[keep]
