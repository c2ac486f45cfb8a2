"""The one way to the compiled (JAX) solvers from other array libraries, and back.

The solvers have two backends: the NumPy loops for the CPU and the compiled loops (one
``jax.jit`` program per solve) for accelerators. Every public solver entry point
(:func:`roughcontact.solve`, the solvers, :func:`roughcontact.approach_retract`) is
wrapped by :func:`routed`, which decides once, before the solve, where it computes:

* NumPy heights (or lists) with ``device`` None or ``"cpu"``: the NumPy loops, nothing
  converted. JAX heights with ``device`` None: the compiled loops, as they are.
* Heights of another library that speaks DLPack (CuPy, torch, array_api_strict, ...):
  to the compiled program through :func:`jax.numpy.from_dlpack` (zero-copy where JAX can
  alias the buffer: on a GPU), and the result's fields back through the caller's
  namespace's ``from_dlpack`` (CuPy in, CuPy fields out), on the caller's device
  (zero-copy on a GPU; host buffers come back as writable copies).
* ``device="cuda"`` / ``"cuda:N"``: the compiled program on JAX's CUDA device N
  (``jax.devices("gpu")[N]``); the fields come back as CuPy arrays when CuPy is
  importable (as before the compiled loops), else as JAX arrays on that GPU.
* What cannot go to the compiled program computes with the NumPy loops on the host, its
  fields returned in the caller's namespace (``xp.asarray``): JAX not installed, a
  namespace whose DLPack export JAX refuses (dask, ...), a free boundary or a
  ``callback`` (the compiled loops have neither; a RuntimeWarning says so when the
  solve was asked of a GPU). ``device="cpu"`` always means NumPy.

A path converts its heights once, at its start; each state's solve then runs on JAX
arrays with no conversion, and ``progress`` receives each state's result with its
fields in the caller's namespace. jax is imported only when such a route is taken
(``import roughcontact`` imports neither jax nor scipy).
"""

from __future__ import annotations

import contextlib
import dataclasses
import functools
import importlib.util
import sys
import warnings

import numpy as np
from array_api_compat import is_jax_array

from ._backend import (
    array_device,
    array_namespace,
    check_dtype,
    is_array,
    is_numpy_array,
    jax_precision,
    to_numpy,
)
from .errors import ParameterError

__all__ = ["check_device", "device_index", "jax_gpu", "place", "routed", "to_device"]

#: What to install for ``device="cuda"``.
JAX_CUDA = 'pip install "jax[cuda12]"'

#: DLPack's device type of host memory.
_DLPACK_CPU = 1

#: The fields of a :class:`~roughcontact.solvers.result.ContactResult`.
_FIELDS = ("pressure", "gap", "deflection")


def device_index(device) -> int | None:
    """The GPU index of ``"cuda"`` (0) / ``"cuda:N"`` (N), None for None and ``"cpu"``, or
    a one-line :class:`ParameterError` for anything else."""
    if device is None or device == "cpu":
        return None
    if isinstance(device, str) and device == "cuda":
        return 0
    if isinstance(device, str) and device.startswith("cuda:") and device[5:].isdigit():
        return int(device[5:])
    raise ParameterError(f"device must be 'cpu', 'cuda' or 'cuda:N', got {device!r}")


def _has_jax_cuda() -> bool:
    """Whether JAX and a CUDA plugin for it are installed (looked up, not imported: no GPU
    memory is taken)."""
    names = ("jax", "jax_plugins.xla_cuda13", "jax_plugins.xla_cuda12", "jax_cuda13_plugin",
             "jax_cuda12_plugin")  # fmt: skip
    try:
        found = [importlib.util.find_spec(name) is not None for name in names]
    except (ImportError, ValueError):  # a namespace package without the plugin
        found = [False]
    return found[0] and any(found[1:])


def _jax_installed() -> bool:
    return importlib.util.find_spec("jax") is not None


def _jax_loaded() -> bool:
    return "jax" in sys.modules


def check_device(device: str | None) -> str | None:
    """Validate a device request before any work: None, "cpu", "cuda" or "cuda:N".

    For a CUDA device this checks that JAX with a CUDA backend is installed (the compiled
    loops run there; ``pip install "jax[cuda12]"``) without starting that backend (which
    would take GPU memory in a process that only hands out work, as ``study run``'s), so a
    study or a path fails at once with a one-line error rather than in its first solve;
    the GPU index is checked by the first solve (:func:`jax_gpu`).
    """
    if device_index(device) is None or _has_jax_cuda():
        return device
    if _jax_loaded():  # a CUDA backend found another way: ask JAX (it is loaded)
        jax_gpu(device)
        return device
    raise ParameterError(
        f"device={device!r} runs the compiled (JAX) loops on an NVIDIA GPU, and JAX with "
        f"CUDA is not installed: {JAX_CUDA}, or use device='cpu'"
    )


def jax_gpu(device: str):
    """JAX's CUDA device for ``"cuda"`` / ``"cuda:N"``, or a one-line ParameterError."""
    index = device_index(device)
    try:
        import jax
    except ImportError:
        raise ParameterError(
            f"device={device!r} runs the compiled (JAX) loops on an NVIDIA GPU, and JAX is "
            f"not installed: {JAX_CUDA}, or use device='cpu'"
        ) from None
    try:
        gpus = jax.devices("gpu")
    except RuntimeError:  # no CUDA backend in this JAX (or no driver, no GPU)
        gpus = []
    if not gpus:
        raise ParameterError(
            f"device={device!r}: JAX has no CUDA backend here (no NVIDIA GPU, or JAX without "
            f"CUDA: {JAX_CUDA}); use device='cpu'"
        )
    if not 0 <= index < len(gpus):
        raise ParameterError(
            f"device={device!r}: CUDA device index must be in [0, {len(gpus) - 1}]"
        )
    return gpus[index]


def _x64():
    """The context in which JAX keeps float64 (:func:`.jax_precision`'s, set up front)."""
    jax = sys.modules["jax"]
    return contextlib.nullcontext() if jax.config.jax_enable_x64 else jax.enable_x64(True)


def _to_jax(x, target=None):
    """``x`` (any array, or array-like) as a JAX array, on JAX device ``target`` if given.

    DLPack first (zero-copy where JAX can alias the buffer); host arrays and array-likes
    through NumPy. Raises what JAX raises when neither works.
    """
    import jax
    import jax.numpy as jnp

    if is_jax_array(x):
        out = x
    elif not is_array(x) or is_numpy_array(x):
        host = np.asarray(x)
        out = jnp.asarray(host) if target is None else jax.device_put(host, target)
    else:
        try:
            out = jnp.from_dlpack(x)
        except Exception:  # noqa: BLE001 - an export refused (a read-only host buffer)
            out = jnp.asarray(to_numpy(x))
    if target is not None and out.devices() != {target}:
        out = jax.device_put(out, target)
    return out


class _Route:
    """Where a solve computes and how its result's fields come back.

    ``inward(x)``: an array (heights, a warm start) as the loop takes it; ``outward(a)``:
    a field as the caller gets it; ``context``: what the solve runs in (JAX's float64).
    """

    def __init__(self, inward, outward, context=contextlib.nullcontext, device=None):
        self.inward, self.outward, self.context, self.device = inward, outward, context, device

    def initial(self, initial):
        """A warm start (a result or an array) moved as the heights were."""
        if initial is None:
            return None
        if hasattr(initial, "pressure") and dataclasses.is_dataclass(initial):
            return dataclasses.replace(initial, **{k: self.inward(getattr(initial, k))
                                                   for k in _FIELDS})  # fmt: skip
        return self.inward(initial)

    def result(self, res):
        """A solve's result with its fields in the caller's namespace (else unchanged)."""
        if not (hasattr(res, "pressure") and dataclasses.is_dataclass(res)):
            return res
        return dataclasses.replace(res, **{k: self.outward(getattr(res, k)) for k in _FIELDS})


def _back_to(like):
    """The conversion of a field (JAX or NumPy) into the namespace and device of ``like``."""
    xp, dev = array_namespace(like), array_device(like)

    def outward(a):
        if not is_numpy_array(a) and a.__dlpack_device__()[0] != _DLPACK_CPU:
            try:  # zero-copy on the same device (a GPU)
                out = xp.from_dlpack(a)
                if array_device(out) == dev:
                    return out
            except Exception:  # noqa: BLE001 - a refused export: through the host
                pass
        # on the host a copy (JAX's buffers would come read-only), on the caller's device
        return xp.asarray(np.array(to_numpy(a)), device=dev)

    return outward


def _gpu_fields():
    """The conversion of a compiled result's fields for ``device="cuda"``: CuPy arrays
    when CuPy is importable (zero-copy), else the JAX arrays themselves."""
    try:
        import cupy
    except ImportError:
        return lambda a: a
    return lambda a: a if is_numpy_array(a) else cupy.from_dlpack(a)


def _on_host(x):
    """``x`` as a NumPy array for the NumPy loops, or a one-line ParameterError."""
    if not is_array(x):
        return x
    try:
        out = to_numpy(x)
    except Exception as err:  # noqa: BLE001 - e.g. a GPU tensor JAX could not take
        out, why = None, f"{type(err).__name__}: {err}"
    else:
        why = "no numeric buffer"
    if out is None or out.dtype == object:
        raise ParameterError(
            f"arrays of type {type(x).__module__}.{type(x).__name__} can go neither to the "
            "compiled program (no DLPack export JAX takes; on a GPU JAX needs CUDA: "
            f"{JAX_CUDA}) nor to NumPy ({why}); pass NumPy or JAX arrays"
        )
    return out


def _numpy_route(outward):
    return _Route(_on_host, outward)


def plan(heights, device, compiled: bool) -> _Route | None:
    """The route of a solve on ``heights`` asked for ``device``, or None for none (NumPy
    heights on the CPU, JAX heights with no device: their own loops). ``compiled``:
    whether the compiled loops support the solve's options (periodic, no callback)."""
    index = device_index(device)
    numpy_in = not is_array(heights) or is_numpy_array(heights)
    if device == "cpu" or (device is None and numpy_in):
        return None if numpy_in else _numpy_route(lambda a: a)
    if device is None and is_jax_array(heights):
        return None
    if index is not None:  # device="cuda[:N]": the compiled program on JAX's GPU N
        gpu = jax_gpu(device)
        fields = _gpu_fields()
        if not compiled:  # the NumPy loops, the fields then on that GPU
            _on_the_host(f"device={device!r}", NO_OPTION)
            return _numpy_route(lambda a: fields(_to_jax(a, gpu)))
        return _Route(lambda x: _to_jax(x, gpu), fields, _x64, gpu)
    back = _back_to(heights)
    if compiled and _jax_installed():
        import jax.numpy as jnp

        try:
            with _x64():
                probe = jnp.from_dlpack(heights)
        except Exception:  # noqa: BLE001 - DLPack refused: the NumPy loops
            probe = None
        if probe is not None:
            target = next(iter(probe.devices()))
            return _Route(lambda x: probe if x is heights else _to_jax(x, target), back, _x64,
                          target)  # fmt: skip
    if _dlpack_device(heights) not in (None, _DLPACK_CPU):
        why = None if compiled else NO_OPTION
        _on_the_host(f"heights on a GPU ({type(heights).__module__})", why)
    return _numpy_route(back)


def _dlpack_device(x):
    try:
        return x.__dlpack_device__()[0]
    except Exception:  # noqa: BLE001 - no DLPack at all
        return None


#: Why a solve asked of a GPU may still run on the host (:func:`_on_the_host`).
NO_OPTION = "the compiled loops have no free boundary and no callback"


def _on_the_host(what, why=None):
    """Say that a solve asked of a GPU runs the NumPy loops on the host, and why: ``why``, or
    (None) JAX could not take the heights (not installed, or without that GPU's backend)."""
    why = why or f"JAX could not take them (JAX with CUDA: {JAX_CUDA})"
    warnings.warn(
        f"{what}: {why}, so this solve runs the NumPy loops on the host (its fields are "
        "returned on the GPU)",
        RuntimeWarning,
        stacklevel=4,
    )


def place(heights, device=None):
    """``heights`` where a solve asked for ``device`` computes: as they are for None,
    NumPy for ``"cpu"``, a JAX array on JAX's GPU N for ``"cuda[:N]"`` (float64 kept).
    For a caller that solves many states on the same heights (one move, not one per
    solve; the results' fields then stay there)."""
    if device_index(device) is None:
        return to_numpy(heights) if device == "cpu" and is_array(heights) else heights
    gpu = jax_gpu(device)
    with _x64():
        return _to_jax(heights, gpu)


def routed(solver):
    """Wrap a solver ``solver(heights, substrate, ..., device=..., **kwargs)`` with its
    route (module docstring): the heights (and a warm start ``initial``) moved once, the
    result's fields and those ``progress`` sees returned in the caller's namespace."""

    @functools.wraps(solver)
    def wrapper(heights, *args, device=None, **kwargs):
        substrate = args[0] if args else kwargs.get("substrate")
        compiled = kwargs.get("callback") is None and getattr(substrate, "periodic", True)
        route = plan(heights, device, compiled)
        if route is None:
            if device is None and is_jax_array(heights):
                with jax_precision(heights, kwargs.get("dtype")):
                    return solver(heights, *args, device=device, **kwargs)
            return solver(heights, *args, device=device, **kwargs)
        with route.context():
            h = route.inward(heights)
            if route.device is not None and kwargs.get("dtype") is None:
                kwargs["dtype"] = "float64"  # the default of every array but JAX's own
            if kwargs.get("initial") is not None:
                kwargs["initial"] = route.initial(kwargs["initial"])
            if callable(progress := kwargs.get("progress")):
                kwargs["progress"] = lambda step, n, res: progress(step, n, route.result(res))
            if route.device is not None:
                with jax_precision(h, kwargs.get("dtype")):
                    res = solver(h, *args, device=None, **kwargs)
            else:
                res = solver(h, *args, device=None, **kwargs)
        return route.result(res)

    return wrapper


def _cupy(device: str):
    """(cupy, GPU index) for ``"cuda"`` / ``"cuda:N"``, or None when CuPy is not importable
    or sees no such GPU."""
    index = device_index(device)
    try:
        import cupy

        count = cupy.cuda.runtime.getDeviceCount()
    except Exception:  # noqa: BLE001 - not installed, no driver, no device
        return None
    return (cupy, index) if 0 <= index < count else None


def to_device(x, device: str | None = None, dtype=None):
    """``x`` as an array on ``device`` in floating precision ``dtype``.

    Parameters
    ----------
    x : array of any backend, or array-like
    device : {None, "cpu", "cuda", "cuda:N"}
        ``None`` keeps the array where it is (its own namespace); ``"cpu"`` gives NumPy;
        ``"cuda"`` gives CuPy on the current (``"cuda:N"``: the N-th) GPU, or, without
        CuPy, a JAX array on JAX's CUDA device N (the solvers compute on either with
        the compiled loops).
    dtype : {None, "float64", "float32"}
        ``None`` keeps a floating array's precision and makes anything else float64.

    Returns
    -------
    array
        Copied only when the device or the precision changes.
    """
    dtype = check_dtype(dtype)
    device_index(device)
    if device == "cpu" or (device is None and not is_array(x)):
        x = to_numpy(x) if is_array(x) else np.asarray(x)
    elif device is not None:
        found = _cupy(device)
        if found is not None:
            cupy, index = found
            with cupy.cuda.Device(index):
                x = cupy.asarray(x)
        else:
            x = place(x, device)  # JAX's GPU (or a one-line error saying what to install)
    xp = array_namespace(x)
    if dtype is None:
        dtype = x.dtype if xp.isdtype(x.dtype, "real floating") else "float64"
    want = getattr(xp, dtype) if isinstance(dtype, str) else dtype
    if x.dtype == want:
        return x
    if is_jax_array(x):  # float64 without JAX's global switch (see jax_precision)
        with jax_precision(x):
            return xp.astype(x, want)
    return xp.astype(x, want)
