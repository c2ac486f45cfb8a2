"""Rules of the preconditioned Polonsky-Keer iteration shared by its two loops.

The constants were chosen by measurement (given with each); :class:`StepKind` decides
whether a step is preconditioned. See :mod:`roughcontact.solvers.polonsky_keer`.
"""

from __future__ import annotations

import math

__all__ = [
    "JOINING_KEEPS_DIRECTIONS",
    "POINT_CORRECTIONS",
    "RESUME_PRECONDITIONING",
    "StepKind",
]


#: Up to this many sites changed by a projection, the hard-wall solver adds their point
#: responses (each a pass over the grid) instead of convolving the correction (measured
#: break-even against a float32 convolution: 2-3 sites at 1024²-2048², 4-8 at 128²-512²).
POINT_CORRECTIONS = 2

#: When interpenetrating sites join a preconditioned hard-wall step and they are at most
#: this fraction of the contact set, the conjugate directions are kept (the new sites
#: start with none), as they are when sites leave; more restart them. Restarting on every
#: join made the late iterations steepest descent whenever a site or two joined each time
#: (benchmark surface: 82 → 46 iterations at 2048², 34 → 29 at 512²; 1 % was the best of
#: 0-100 % over 1008 small cases, none of which fails to converge).
JOINING_KEEPS_DIRECTIONS = 0.01

#: After a preconditioned hard-wall step lost the whole contact set (and the solve
#: restarted from the overlap or from uniform pressure), the steps stay plain until the
#: residual is below this fraction of the one before the loss: repeating the losing path
#: is then impossible, and the preconditioner returns for the rest (plain to the end took
#: up to 1800 iterations with most of a 256x512 surface in contact; this rule, 62-378;
#: 0.3 was the best of 0.1, 0.3 and 0.5).
RESUME_PRECONDITIONING = 0.3


class StepKind:
    """Whether the hard wall's steps are preconditioned, shared by its two loops.

    Preconditioned when the problem has a preconditioner, except for a while after a
    preconditioned step lost the whole contact set: the restart then takes plain steps
    (they cannot repeat the losing path) until the residual is below
    :data:`RESUME_PRECONDITIONING` of its value before the loss.
    """

    def __init__(self, precondition: bool):
        self.pre, self.resume_below = precondition, -math.inf

    def lost_contact(self, residual: float) -> None:
        """The loop restarts because the whole contact set was lost."""
        if self.pre:
            self.pre, self.resume_below = False, RESUME_PRECONDITIONING * residual

    def resumes(self, residual: float) -> bool:
        """Whether preconditioned steps return with this one (directions must restart)."""
        if self.pre or residual >= self.resume_below:
            return False
        self.pre = True
        return True
