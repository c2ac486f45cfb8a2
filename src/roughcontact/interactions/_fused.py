"""The smoothed 9-3 wall's pressure and curvature as one CuPy kernel each (a GPU).

On CuPy the array-API evaluation of :class:`~.lj93smooth.SmoothLJ93` is some 25 kernels
over the whole grid (the quartic, the clip, the 9-3 core selected by a mask), each a
launch and a pass through memory; the solvers evaluate the law two to four times per
iteration. These kernels do it in one pass, with the same operations in the same order
(compiled without fused multiply-adds, ``--fmad=false``, so that each operation rounds
as NumPy's does): the same values as the NumPy evaluation (tested on a GPU).

Built on first use; if CuPy cannot build them (no compiler for the device, an old CuPy)
:func:`kernel` gives None and the law falls back to the array-API evaluation.
"""

from __future__ import annotations

import functools

__all__ = ["kernel"]

_CORE = """
    if (g < a0) {
        T gc = max(g, g_min);
        T inv = (T)1 / gc;
        T s3 = sigma * inv;
        s3 = s3 * s3 * s3;
        T s9 = s3 * s3 * s3;
        T second = eps * (c180 * s9 - c12 * s3) * (inv * inv);
        CORE
    }
"""

_SOURCES = {
    # -V'(g): the quartic's (1 - m) m m (-12 w / dr), on the core -(V_LJ' + V_LJ'' (g - gc))
    "pressure": (
        """
    T m = (cutoff - g) * inv_range;
    m = min(max(m, (T)0), (T)1);
    T out = (T)1 - m;
    out = out * m;
    out = out * m;
    out = out * scale;
"""
        + _CORE.replace(
            "CORE",
            "T first = eps * (c18 * s9 + c3 * s3) * inv;\n"
            "        out = -(first + second * (g - gc));",
        )
        + "    p = out;\n"
    ),
    # V''(g): the quartic's (3 m - 2) m 12 w / dr^2, on the core V_LJ''(max(g, g_min))
    "curvature": (
        """
    T m = (cutoff - g) * inv_range;
    m = min(max(m, (T)0), (T)1);
    T out = c3 * m - c2;
    out = out * m;
    out = out * scale;
"""
        + _CORE.replace("CORE", "out = second;")
        + "    p = out;\n"
    ),
}

_PARAMS = (
    "T g, T cutoff, T inv_range, T scale, T a0, T g_min, T sigma, T eps, "
    "T c18, T c180, T c12, T c3, T c2"
)


@functools.cache
def kernel(which: str):
    """The CuPy kernel for ``"pressure"`` or ``"curvature"``, or None if it cannot be built."""
    try:
        import cupy

        source = _SOURCES[which]
        name = f"roughcontact_lj93smooth_{which}"
        try:
            k = cupy.ElementwiseKernel(_PARAMS, "T p", source, name, options=("--fmad=false",))
        except TypeError:  # a CuPy without options=: contraction then stays NVRTC's default
            k = cupy.ElementwiseKernel(_PARAMS, "T p", source, name)
        probe = cupy.asarray([0.5, 1.5], dtype=cupy.float64)
        k(probe, 2.0, 1.0, -1.0, 1.0, 0.05, 1.0, 1.0, -1.2, 12.0, 12.0, 3.0, 2.0)  # compiles
        return k
    except Exception:  # noqa: BLE001 - any failure: the array-API evaluation instead
        return None
