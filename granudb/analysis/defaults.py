"""The fits' defaults that every output states: the level of their intervals and the
bootstrap's resample count.

One place for each (the fits, their bands and the reported runs' intervals use them, and
the command line's and the report's words about a fit read them). Nothing is imported
here, so the command line's presentation can read them without loading numpy.
"""

#: The level of every fit's interval (bootstrap, small-n, asymptotic, Bayesian credible).
CONFIDENCE_LEVEL = 0.95
#: Resamples of the Walton and gap-viscosity bootstraps for groups up to the resample
#: rule's size (``granudb.analysis.walton_bootstrap``).
DEFAULT_RESAMPLES = 1000
