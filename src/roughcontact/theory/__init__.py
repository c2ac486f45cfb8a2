"""Closed-form and semi-analytic reference solutions (used as test oracles).

* :mod:`.hertz` -- sphere on a half-space (Johnson 1985, ch. 4).
* :mod:`.westergaard` -- 1D sinusoid on a half-space (Westergaard 1939; Johnson 1985,
  section 13.2).
* :mod:`.jkr` -- adhesive sphere: JKR (Johnson, Kendall & Roberts 1971) and DMT
  (Derjaguin, Muller & Toporov 1975).
* :mod:`.maugis_dugdale` -- the JKR-DMT transition with a Dugdale cohesive zone
  (Maugis 1992; Johnson & Greenwood 1997).
* :mod:`.adhesive_sinusoid` -- Johnson's adhesive 1D sinusoid (Johnson 1995).

Rough-surface theories: Pastewka & Robbins (2014) Eqs. 4-10 and the stickiness criterion
(:mod:`.pastewka_robbins`); Persson (2001) and Bush-Gibson-Thomas (1975) area-load laws
(:mod:`.persson`); Greenwood-Williamson with Hertz, DMT and JKR (Fuller-Tabor 1975)
summits from Nayak/McCool summit statistics (:mod:`.greenwood_williamson`).

Every public name of these modules (their ``__all__``) is also a name of this package.
"""

from . import (
    adhesive_sinusoid,
    greenwood_williamson,
    hertz,
    jkr,
    maugis_dugdale,
    pastewka_robbins,
    persson,
    westergaard,
)

_MODULES = (
    adhesive_sinusoid,
    hertz,
    jkr,
    maugis_dugdale,
    westergaard,
    greenwood_williamson,
    pastewka_robbins,
    persson,
)
# each module lists its public names once; the package re-exports them (``jkr`` and
# ``maugis_dugdale`` then name the functions, as they always did, not the modules)
__all__ = [name for module in _MODULES for name in module.__all__]
globals().update({name: getattr(module, name) for module in _MODULES for name in module.__all__})
