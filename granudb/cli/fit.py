"""``granudb fit walton|restitution|gap-viscosity``: the paper's fits on stored runs.

Each command takes the collision filters of ``collisions list`` and prints one row per
group (dataset × particle × wall × fluid); JSON and CSV show
every key the fit returns (``granudb.analysis.fits`` documents them). A table shows each
group as a record: every value with its interval or the reason it has none.
"""

from __future__ import annotations

from typing import Any

import typer

from granudb import api
from granudb.cli.options import (
    DbOption,
    Format,
    FormatOption,
    collision_filters,
    keyword_option,
    option_group,
    text,
    wraps,
)
from granudb.cli.output import emit, emit_records

app = typer.Typer(
    help="Fit measured collisions: Walton β and μ_f, e(St), gap viscosity.", no_args_is_help=True
)


#: A Bayesian fit's table title says where its priors and diagnostics are.
BAYES_TITLE = " — posterior medians (priors, sampler, diagnostics: --format json or csv)"


def _show(frame: Any, kind: str, fmt: Format, title: str) -> None:
    every = list(frame.columns)
    if "prior" in every:
        title += BAYES_TITLE
    if fmt is Format.table:  # for people: each group's values with interval or reason
        views = [api.fit_people_view(kind, r) for r in frame.to_dict("records")]
        emit_records(views, title=title)
        return
    emit(frame.to_dict("records"), every, fmt, title=title)


def _fit_command(kind: str, help_text: str, title: str, *options: Any) -> None:
    """``granudb fit <kind>``: ``granudb.fit_<kind>`` with the collision filters and the
    fit's own ``options`` (keyword options, see ``option_group``), shown by ``_show``."""
    function = f"fit_{kind}"

    @collision_filters
    @option_group("given", list(options))
    @wraps(function)
    def command(
        db: DbOption = None,
        fmt: FormatOption = Format.table,
        filters: dict | None = None,
        given: dict | None = None,
    ) -> None:
        _show(getattr(api, function)(db=db, **given or {}, **filters or {}), kind, fmt, title)

    app.command(kind.replace("_", "-"), help=help_text)(command)


#: The Bayesian option of the Walton and restitution fits.
BAYES_OPTIONS = (
    keyword_option(
        "method",
        text(
            "bootstrap (the default): bootstrap intervals; bayes: posterior medians and 95 % "
            "credible intervals (emcee), with priors, sampler settings and convergence."
        ),
    ),
    keyword_option(
        "draws", text("With --method bayes: write the posterior draws to this new CSV.")
    ),
)

_fit_command(
    "walton",
    "β (sticking runs) and μ_f (sliding runs) per dataset × pair × fluid, with ē.",
    "Walton fits",
    *BAYES_OPTIONS,
)
_fit_command(
    "restitution",
    "e against the normal Stokes number for immersed runs: e_dry and k (or St_c).",
    "Restitution against Stokes number",
    keyword_option("model", text("exponential (the default) or threshold.")),
    *BAYES_OPTIONS,
)
_fit_command(
    "gap_viscosity",
    "Gap viscosity μ₀ fitting (5.8) to sliding runs, and the gap temperature.",
    "Gap viscosity (figure 14, table 2)",
)
