"""The record returned by every solve."""

from __future__ import annotations

import dataclasses
import enum
from dataclasses import dataclass, field

from .._backend import is_numpy_array, to_numpy
from ..analysis.contact_geometry import AREA_CORRECTION_PER_EDGE

__all__ = ["STATE_SCALARS", "ContactResult", "SolveStatus"]


class SolveStatus(enum.StrEnum):
    """Why a solver stopped: the machine-readable twin of ``ContactResult.message``.

    A ``str`` subclass (``enum.StrEnum``), so it is JSON-ready (``status.value``); branch
    on it, never on the message text. ``converged`` is ``status is SolveStatus.CONVERGED``.
    """

    #: The convergence test passed (also: no contact, nothing to solve).
    CONVERGED = "converged"
    #: ``max_iter`` iterations without meeting ``tol``.
    ITERATION_LIMIT = "iteration_limit"
    #: Stuck at the rounding floor of the physical pressure scale (float32; float64 with a
    #: ``tol`` below what it resolves): the state is an equilibrium to that floor.
    STALLED = "stalled"
    #: A non-finite pressure, state or step (check the inputs and the interaction).
    NON_FINITE = "non_finite"
    #: The callback returned True.
    CALLBACK = "stopped_by_callback"
    #: The line search found no finite minimum, or no descent along the projected direction.
    LINE_SEARCH_FAILED = "line_search_failed"
    #: Load control: no stable state carries the load: it jumps across it between two
    #: offsets (an instability of the load-offset curve; follow it with offset control).
    NO_STABLE_STATE = "no_stable_state"
    #: Load control: the load stays the same however far the surfaces separate (a tensile
    #: load beyond the pull-off force).
    DETACHED = "detached"
    #: Load control: the load is not reached before the contact is complete (a hard core
    #: at its lowest offset).
    FULL_CONTACT = "full_contact"
    #: Load control: no offset bracketing the load within 60 doublings of the search step.
    NOT_BRACKETED = "not_bracketed"
    #: Pressures beyond any elastic equilibrium (an offset that pushes the surfaces through
    #: each other, far below full contact): the residual stopped at float64's rounding
    #: floor of those pressures, far above a force balance on the physical scale
    #: (``E*·h'rms``, the law's largest attraction); not an equilibrium, no load carried.
    RUNAWAY = "runaway"


#: The numbers describing one solved state: the path datasets' per-step variables and,
#: with message, status, tol and solver, the keys of :meth:`ContactResult.summary`.
STATE_SCALARS = (
    "offset",
    "load",
    "repulsive_load",
    "attractive_load",
    "repulsive_area",
    "attractive_area",
    "perimeter",
    "perimeter_edges",
    "corrected_repulsive_area",
    "mean_gap",
    "iterations",
    "converged",
    "residual",
    "solve_seconds",
)


@dataclass(frozen=True)
class ContactResult:
    """One solved contact state (the README's conventions, lattice units unless given).

    Attributes
    ----------
    offset : float
        Offset ``d`` of the rigid surface (length); gap ``g = d - h + w``.
    load : float
        External load per nominal area, :math:`N/A_0 = \\bar p` (pressure, >0 pushes
        the bodies together).
    repulsive_load, attractive_load : float
        :math:`N_{rep}/A_0` and :math:`N_{att}/A_0` (magnitudes; load = rep - att).
    repulsive_area, attractive_area : float
        :math:`A_{rep}/A_0`, :math:`A_{att}/A_0` (fractions of the nominal area).
    perimeter : float
        Perimeter of the repulsive area per nominal area (1/length): nearest-neighbour
        edge count × π/4 × a0 / A0.
    perimeter_edges : int
        The raw nearest-neighbour edge count.
    mean_gap : float
        Mean of the gap over the nominal area (length).
    pressure, gap, deflection : array
        Fields on the grid (pressure units, length, length), arrays of the heights'
        namespace on their device (CuPy arrays for CuPy heights, JAX arrays for JAX
        heights; for ``device="cuda"`` CuPy if importable, else JAX): a warm start from
        this record on the same device copies nothing. :meth:`to_numpy` gives the
        record with NumPy fields.
    iterations : int
        Iterations the solver took.
    residual : float
        Final value of the solver's convergence measure (see the solver's docs).
    converged : bool
        Whether ``residual <= tol`` was reached within the iteration cap
        (``status is SolveStatus.CONVERGED``).
    status : SolveStatus
        Why the solver stopped, as an enum (str-valued): branch on this.
    message : str
        Why the solver stopped, for people.
    solve_seconds : float
        Wall time of the solve (no imports, no set-up of the substrate).
    nominal_area, pixel_size : float
        :math:`A_0` (length²) and :math:`a_0` (length).
    """

    offset: float
    load: float
    repulsive_load: float
    attractive_load: float
    repulsive_area: float
    attractive_area: float
    perimeter: float
    perimeter_edges: int
    mean_gap: float
    iterations: int
    residual: float
    converged: bool
    status: SolveStatus
    message: str
    solve_seconds: float
    nominal_area: float
    pixel_size: float
    tol: float
    solver: str
    pressure: object = field(repr=False)
    gap: object = field(repr=False)
    deflection: object = field(repr=False)

    def __post_init__(self):
        status = SolveStatus(self.status)
        object.__setattr__(self, "status", status)
        if bool(self.converged) != (status is SolveStatus.CONVERGED):
            raise ValueError(f"converged={self.converged!r} contradicts status {status.value!r}")

    def to_numpy(self) -> ContactResult:
        """This record with its fields copied to host NumPy arrays (itself if they are).

        The edge between the solvers, which keep the fields where the heights are, and
        what needs NumPy: files, plots, scipy-based analysis. Scalars are unchanged.
        """
        names = ("pressure", "gap", "deflection")
        if all(is_numpy_array(getattr(self, k)) for k in names):
            return self
        return dataclasses.replace(self, **{k: to_numpy(getattr(self, k)) for k in names})

    @property
    def total_load(self) -> float:
        """External load N (pressure × length²)."""
        return self.load * self.nominal_area

    @property
    def corrected_repulsive_area(self) -> float:
        r"""Perimeter-corrected repulsive area per nominal area, :math:`A_{rep}/A_0`.

        The estimate of Yastrebov, Anciaux & Molinari, Tribol. Int. 114, 161 (2017)
        (see :func:`roughcontact.analysis.corrected_area`), computed on demand from the
        stored site fraction and boundary-bond count :math:`n_e` (``perimeter_edges``):
        ``repulsive_area - (π - 1 + ln 2)/24 · n_e · a0² / A0``. Less biased than the
        raw site count ``repulsive_area``, which overestimates by a term proportional
        to the perimeter.
        """
        edge_area = AREA_CORRECTION_PER_EDGE * self.pixel_size**2
        return float(self.repulsive_area - edge_area * self.perimeter_edges / self.nominal_area)

    def summary(self) -> dict:
        """Scalars only, JSON-ready (the keys of ``roughcontact contact --json``)."""
        out = {}
        for k in (*STATE_SCALARS, "message", "status", "tol", "solver"):
            v = getattr(self, k)
            out[k] = (
                v.value
                if isinstance(v, SolveStatus)
                else v
                if isinstance(v, (str, bool))
                else (int(v) if k in ("iterations", "perimeter_edges") else float(v))
            )
        return out
