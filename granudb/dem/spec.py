"""What a DEM export is made of: particle types, per-pair values with provenance, a model.

Plain frozen dataclasses, so the database layer (or a notebook) can build a model from
whatever it has, and every writer in this package reads the same validated object. A
value never travels without the sentence that says where it came from, because a DEM
input whose numbers cannot be traced back to a measurement cannot be trusted or updated.

The pair matrix must be complete: every (particle, particle) and (particle, wall) pair
exactly once. A missing pair would otherwise be filled by the target code's mixing rule
(geometric means in LAMMPS, the minimum friction angle in Yade), silently replacing the
measured value. Wall–wall pairs never touch and may be omitted.
"""

from __future__ import annotations

import math
import re
import unicodedata
from dataclasses import dataclass, field

from granudb.errors import ValidationError
from granudb.physics.contact import (
    contact_time,
    effective_mass,
    effective_radius,
    reduced_modulus,
    reduced_shear_modulus,
    shear_modulus,
    sphere_mass,
)
from granudb.physics.flow import (
    CRITICAL_STOKES_NUMBER,
    LEGENDRE_BETA,
    added_mass_stokes_number,
    predicted_restitution,
)

#: The parameter sets a DEM export writes for sensitivity runs: every value at its central
#: estimate, or at the lower / upper end of its stated interval (``Value.at``).
PARAMETER_SETS = ("central", "low", "high")

#: GUM's coverage factor for an interval from a standard uncertainty: k = 2 gives about
#: 95 % for a normal distribution (JCGM 100:2008 §6.3), the level of the fits' intervals.
COVERAGE_FACTOR = 2.0


@dataclass(frozen=True)
class Value:
    """A number and where it came from, e.g. ``Value(0.97, "Joseph & Hunt 2004 §3")``,
    with its interval where one is stated: ``low``–``high`` and ``interval`` saying what
    it is ("95 % studentized bootstrap interval", "± 2u (k = 2) from the stated u").
    """

    value: float
    provenance: str
    low: float | None = None
    high: float | None = None
    interval: str = ""

    def __post_init__(self) -> None:
        if not math.isfinite(self.value):
            raise ValidationError("value", self.value, "must be a finite number")
        if not self.provenance.strip():
            raise ValidationError(
                "provenance", repr(self.provenance), "must say where it came from"
            )
        if (self.low is None) != (self.high is None):
            raise ValidationError("interval", (self.low, self.high), "needs both ends")
        if self.low is not None and self.high is not None:
            if not (math.isfinite(self.low) and math.isfinite(self.high)):
                raise ValidationError("interval", (self.low, self.high), "must be finite")
            if not self.low <= self.value <= self.high:
                raise ValidationError(
                    "interval",
                    f"{self.low:g}–{self.high:g}",
                    f"must hold the value {self.value:g}",
                )
            if not self.interval.strip():
                raise ValidationError("interval", repr(self.interval), "must say what it is")

    @classmethod
    def uncertain(
        cls,
        value: float,
        provenance: str,
        u: float | None,
        stated: str,
        bounds: tuple[float, float] = (-math.inf, math.inf),
    ) -> Value:
        """``value`` with the interval value ± k·u (``COVERAGE_FACTOR``), cut to the
        quantity's physical ``bounds``; no interval where ``u`` is missing, zero or not
        finite. ``stated`` says whose u it is.

        >>> v = Value.uncertain(0.11, "paper", 0.003, "the paper's ±")
        >>> (round(v.low, 3), round(v.high, 3)), v.interval
        ((0.104, 0.116), "± 2u (k = 2, about 95 %), u = 0.003 the paper's ±")
        """
        if u is None or not math.isfinite(u) or u <= 0.0:
            return cls(value, provenance)
        low = max(value - COVERAGE_FACTOR * u, bounds[0])
        high = min(value + COVERAGE_FACTOR * u, bounds[1])
        said = f"± {COVERAGE_FACTOR:g}u (k = {COVERAGE_FACTOR:g}, about 95 %), u = {u:.2g} {stated}"
        if (low, high) != (value - COVERAGE_FACTOR * u, value + COVERAGE_FACTOR * u):
            said += f", cut to [{bounds[0]:g}, {bounds[1]:g}]"
        return cls(value, provenance, min(low, value), max(high, value), said)

    def stated_interval(self) -> str:
        """The interval as a deck comment says it, or "" where none is stated."""
        if self.low is None or self.high is None:
            return ""
        return f"{self.interval}: {self.low:.3g}–{self.high:.3g}"

    def at(self, which: str) -> Value:
        """This value in the parameter set ``which`` (``PARAMETER_SETS``): the central
        value, or the low / high end of its interval, the provenance saying which; a
        value without an interval keeps its central value and says so.

        >>> Value(0.5, "x", 0.4, 0.7, "95 % interval").at("high").value
        0.7
        >>> Value(0.5, "x").at("low").provenance
        'x; low set: no interval stated, the central value kept'
        """
        if which not in PARAMETER_SETS:
            raise ValidationError(
                "parameter_set",
                which,
                f"must be one of {', '.join(PARAMETER_SETS)}",
                parameter=True,
            )
        if which == "central":
            return self
        if self.low is None or self.high is None:
            return Value(
                self.value, f"{self.provenance}; {which} set: no interval stated, the central "
                "value kept",
            )  # fmt: skip
        end = self.low if which == "low" else self.high
        said = (
            f"{which} set: the {which} end of the {self.stated_interval()} (central "
            f"{self.value:.3g}); {self.provenance}"
        )
        return Value(end, said)


#: What every code takes as a name: an ASCII letter, then letters, digits or underscores
#: (LAMMPS fix and group IDs, MercuryDPM's C++ variables, Yade labels).
IDENTIFIER = re.compile(r"[A-Za-z][A-Za-z0-9_]{0,63}")
#: Words a generated name must not be: C++ keywords (MercuryDPM), Python's (Yade), and
#: LAMMPS's group names with a meaning.
RESERVED = frozenset(
    (
        "all",
        "and",
        "auto",
        "bool",
        "break",
        "case",
        "catch",
        "char",
        "class",
        "const",
        "continue",
        "default",
        "delete",
        "do",
        "double",
        "else",
        "enum",
        "explicit",
        "extern",
        "false",
        "float",
        "for",
        "friend",
        "goto",
        "if",
        "inline",
        "int",
        "long",
        "mutable",
        "namespace",
        "new",
        "not",
        "operator",
        "or",
        "private",
        "protected",
        "public",
        "register",
        "return",
        "short",
        "signed",
        "sizeof",
        "static",
        "struct",
        "switch",
        "template",
        "this",
        "throw",
        "true",
        "try",
        "typedef",
        "typename",
        "union",
        "unsigned",
        "using",
        "virtual",
        "void",
        "volatile",
        "while",
        "as",
        "assert",
        "async",
        "await",
        "def",
        "del",
        "elif",
        "except",
        "finally",
        "from",
        "global",
        "import",
        "in",
        "is",
        "lambda",
        "nonlocal",
        "pass",
        "raise",
        "with",
        "yield",
        "None",
        "True",
        "False",
        "region",
        "type",
    )
)


def identifier(name: str, taken: set[str] | None = None) -> str:
    """A name every code accepts, derived from a material's name: accents dropped, any
    other character an underscore, an ``m_`` prefix where it would not start with a letter
    or would be a reserved word, and a number where it would repeat one in ``taken``
    (which is updated).

    >>> [identifier(n) for n in ("steel", "stainless steel", "PTFE-1", "Glasä", "316L", "new")]
    ['steel', 'stainless_steel', 'PTFE_1', 'Glasa', 'm_316L', 'm_new']
    """
    ascii_text = unicodedata.normalize("NFKD", name).encode("ascii", "ignore").decode()
    text = re.sub(r"_+", "_", re.sub(r"[^A-Za-z0-9_]", "_", ascii_text)).strip("_")[:56]
    if not text or not text[0].isalpha() or text in RESERVED:
        text = f"m_{text}" if text else "m"
    chosen, number = text, 2
    while taken is not None and chosen in taken:
        chosen, number = f"{text}_{number}", number + 1
    if taken is not None:
        taken.add(chosen)
    return chosen


@dataclass(frozen=True)
class ParticleType:
    """One material and size; ``diameter_m=None`` with ``is_wall=True`` is a flat wall."""

    name: str
    youngs_modulus_pa: float
    poisson_ratio: float
    density_kg_m3: float
    diameter_m: float | None
    is_wall: bool = False
    #: The catalogue's name of the material (any text); ``name`` is the identifier every
    #: code's input takes (``identifier``).
    material: str = ""

    def __post_init__(self) -> None:
        if not IDENTIFIER.fullmatch(self.name) or self.name in RESERVED:
            raise ValidationError(
                "type name", repr(self.name), "must be an identifier (use dem.spec.identifier)"
            )
        _positive(f"youngs_modulus {self.name}", self.youngs_modulus_pa, "Pa")
        _positive(f"density {self.name}", self.density_kg_m3, "kg/m^3")
        if not -1.0 < self.poisson_ratio <= 0.5:
            raise ValidationError(
                f"poisson_ratio {self.name}", self.poisson_ratio, "must be in (-1, 0.5]"
            )
        if self.is_wall != (self.diameter_m is None):
            raise ValidationError(
                f"diameter {self.name}", self.diameter_m, "must be None exactly for a flat wall"
            )
        if self.diameter_m is not None:
            _positive(f"diameter {self.name}", self.diameter_m, "m")

    @property
    def radius_m(self) -> float:
        """Radius [m]; infinite for a flat wall (docs/physics.md §1)."""
        return math.inf if self.diameter_m is None else self.diameter_m / 2.0

    @property
    def mass_kg(self) -> float:
        """Mass of one particle [kg]; infinite for a wall (it does not move)."""
        if self.diameter_m is None:
            return math.inf
        return float(sphere_mass(self.density_kg_m3, self.diameter_m))


#: The largest error ``dem verify`` accepts, by quantity: relative for e, μ_f and Ψ_out
#: (against Walton's relation with a measured β), absolute for e against the e(St) law.
TOLERANCES = {"restitution": 0.01, "friction": 0.03, "rebound": 0.10, "restitution_law": 0.03}


@dataclass(frozen=True)
class WetParameters:
    """An e(St) law e = e_max exp(−β_L/St_am) (Legendre et al. 2006, docs/physics.md §10), St_am
    the Stokes number with added mass."""

    fluid_viscosity_pa_s: float
    coefficient: float  # β_L
    max_restitution: float
    provenance: str

    def __post_init__(self) -> None:
        _positive("fluid_viscosity", self.fluid_viscosity_pa_s, "Pa s")
        _positive("coefficient", self.coefficient, "")
        if not 0.0 < self.max_restitution <= 1.0:
            raise ValidationError("max_restitution", self.max_restitution, "must be in (0, 1]")

    def restitution(self, stokes: float) -> float:
        """e at the added-mass Stokes number ``stokes``: e_max exp(−β_L/St_am)."""
        return self.max_restitution * math.exp(-self.coefficient / stokes)

    def stokes_at(self, restitution: float) -> float:
        """The St_am at which the law gives ``restitution``: β_L / ln(e_max/e)."""
        return self.coefficient / math.log(self.max_restitution / restitution)

    def constant_range(self, restitution: float, tolerance: float) -> tuple[float, float]:
        """The St_am range over which the law stays within ``tolerance`` (relative) of the
        constant ``restitution``: β_L(1/St_e − 1/St) = ln(1 ± tolerance), St_e the law's
        St at that e; the upper end is infinite where e_max is itself within it.

        >>> law = WetParameters(0.048, 35.0, 0.97, "example")
        >>> [round(x) for x in law.constant_range(law.restitution(150.0), 0.01)]
        [144, 157]
        """
        inverse = 1.0 / self.stokes_at(restitution)
        low = 1.0 / (inverse - math.log(1.0 - tolerance) / self.coefficient)
        top = inverse - math.log(1.0 + tolerance) / self.coefficient
        return low, (1.0 / top if top > 0.0 else math.inf)


@dataclass(frozen=True)
class PairParameters:
    """Everything a code needs for one pair of types; ``restitution`` is the e to reproduce.

    For an immersed pair ``restitution`` is e at a stated Stokes number (say which in its
    provenance); ``wet`` carries the e(St) law where one is known.
    """

    type_i: str
    type_j: str
    restitution: Value
    friction: Value
    rolling_friction: Value | None = None
    wet: WetParameters | None = None
    #: Walton's β (tangential restitution of a sticking impact), where one is known.
    rotational_restitution: Value | None = None

    def __post_init__(self) -> None:
        label = f"{self.type_i}/{self.type_j}"
        beta = self.rotational_restitution
        if beta is not None and not -1.0 < beta.value < 1.0:
            raise ValidationError(
                f"rotational_restitution {label}", beta.value, "must be in (-1, 1)"
            )
        if not 0.0 < self.restitution.value <= 1.0:
            raise ValidationError(
                f"restitution {label}", self.restitution.value, "must be in (0, 1]"
            )
        if self.friction.value < 0.0:
            raise ValidationError(f"friction {label}", self.friction.value, "must be >= 0")
        if self.rolling_friction is not None and self.rolling_friction.value < 0.0:
            raise ValidationError(
                f"rolling_friction {label}", self.rolling_friction.value, "must be >= 0"
            )

    @property
    def key(self) -> frozenset[str]:
        return frozenset((self.type_i, self.type_j))


@dataclass(frozen=True)
class ContactScales:
    """Hertz–Mindlin quantities of one pair (docs/physics.md §1, §2, §9, §13)."""

    reduced_modulus_pa: float  # E*, 1/E* = Σ(1−ν²)/E
    reduced_shear_modulus_pa: float  # G*, 1/G* = Σ(2−ν)/G
    radius_m: float  # R*, 1/R* = 1/R₁ + 1/R₂
    mass_kg: float  # m*, 1/m* = 1/m₁ + 1/m₂
    contact_time_s: float  # t_c ≈ 2.87 (m*²/(R* E*² V))^{1/5} at the characteristic speed

    @property
    def hertz_stiffness(self) -> float:
        """k_n = (4/3) E* (force = k_n √R* δ^{3/2}), docs/physics.md §13 [Pa]."""
        return 4.0 / 3.0 * self.reduced_modulus_pa

    @property
    def mindlin_stiffness(self) -> float:
        """8 G*, so that k_t = 8 G* a with a = √(R* δ) (Mindlin; docs/physics.md §13) [Pa]."""
        return 8.0 * self.reduced_shear_modulus_pa


@dataclass(frozen=True)
class DemModel:
    """N types (particles and walls), their complete pair matrix, a characteristic speed."""

    types: tuple[ParticleType, ...]
    pairs: tuple[PairParameters, ...]
    characteristic_velocity_m_s: float
    #: Which of ``PARAMETER_SETS`` the pair values are (each ``Value.at`` that set).
    parameter_set: str
    _by_key: dict[frozenset[str], PairParameters] = field(init=False, repr=False, compare=False)

    def __init__(
        self,
        types: list[ParticleType] | tuple[ParticleType, ...],
        pairs: list[PairParameters] | tuple[PairParameters, ...],
        characteristic_velocity_m_s: float,
        parameter_set: str = "central",
    ) -> None:
        object.__setattr__(self, "types", tuple(types))
        object.__setattr__(self, "pairs", tuple(pairs))
        object.__setattr__(self, "characteristic_velocity_m_s", characteristic_velocity_m_s)
        _positive("characteristic_velocity", characteristic_velocity_m_s, "m/s")
        if parameter_set not in PARAMETER_SETS:
            raise ValidationError(
                "parameter_set", parameter_set, f"must be one of {', '.join(PARAMETER_SETS)}"
            )
        object.__setattr__(self, "parameter_set", parameter_set)
        object.__setattr__(self, "_by_key", _pair_index(self.types, self.pairs))

    def type(self, name: str) -> ParticleType:
        for t in self.types:
            if t.name == name:
                return t
        raise ValidationError("type", name, "is not one of the model's types")

    def index(self, name: str) -> int:
        """1-based type number, the order of ``types`` (LIGGGHTS and LAMMPS atom types)."""
        return [t.name for t in self.types].index(name) + 1

    def pair(self, name_i: str, name_j: str) -> PairParameters | None:
        """The pair's parameters; None only for a wall–wall pair (walls never touch)."""
        return self._by_key.get(frozenset((name_i, name_j)))

    @property
    def particles(self) -> tuple[ParticleType, ...]:
        return tuple(t for t in self.types if not t.is_wall)

    @property
    def walls(self) -> tuple[ParticleType, ...]:
        return tuple(t for t in self.types if t.is_wall)

    def contact(self, pair: PairParameters, speed: float | None = None) -> ContactScales:
        """E*, G*, R*, m* and t_c of a pair (docs/physics.md §1, §9; t_c from Johnson §11.4)."""
        a, b = self.type(pair.type_i), self.type(pair.type_j)
        e_star = float(
            reduced_modulus(
                a.youngs_modulus_pa, a.poisson_ratio, b.youngs_modulus_pa, b.poisson_ratio
            )
        )
        g_star = float(
            reduced_shear_modulus(
                shear_modulus(a.youngs_modulus_pa, a.poisson_ratio),
                a.poisson_ratio,
                shear_modulus(b.youngs_modulus_pa, b.poisson_ratio),
                b.poisson_ratio,
            )
        )
        radius = float(effective_radius(a.radius_m, b.radius_m))
        mass = float(effective_mass(a.mass_kg, b.mass_kg))
        v = self.characteristic_velocity_m_s if speed is None else speed
        t_c = float(contact_time(mass, radius, e_star, v))
        return ContactScales(e_star, g_star, radius, mass, t_c)


def predicted_wet_restitution(
    dry: Value,
    particle: ParticleType,
    viscosity_pa_s: float,
    speed_m_s: float,
    fluid_density_kg_m3: float,
    *,
    coefficient: float = LEGENDRE_BETA,
    critical_stokes: float = CRITICAL_STOKES_NUMBER,
) -> tuple[Value, WetParameters]:
    """e_wet = e_dry exp(−β_L/St_am) above St_c, 0 below (Legendre et al. 2006;
    docs/physics.md §10), with the added-mass Stokes number St_am = (ρ_p + ρ_f/2) 2RV/(9μ):
    the one prediction ``granudb pair`` and the reports make (``flow.predicted_restitution``).

    Returns the constant e at the stated Stokes number (what a code without a wet model
    takes) and the law itself (for LIGGGHTS-style e(St) models, St being St_am).
    """
    st = float(
        added_mass_stokes_number(
            particle.density_kg_m3, fluid_density_kg_m3, particle.radius_m, speed_m_s,
            viscosity_pa_s,
        )
    )  # fmt: skip
    law = WetParameters(
        viscosity_pa_s,
        coefficient,
        dry.value,
        f"predicted: e = e_dry exp(-{coefficient:g}/St_am) (Legendre et al. 2006), "
        f"e_dry from {dry.provenance}",
    )
    e = float(predicted_restitution(st, dry.value, critical_stokes, coefficient))
    note = (
        f"predicted: e = e_dry exp(-{coefficient:g}/St_am), St_am = {st:.3g} (with added "
        f"mass) at V = {speed_m_s:g} m/s, mu = {viscosity_pa_s:g} Pa s, rho_f = "
        f"{fluid_density_kg_m3:g} kg/m3 (Legendre et al. 2006); e_dry = {dry.value:g} from "
        f"{dry.provenance}"
    )
    return Value(e, note), law


def _positive(name: str, value: float, unit: str) -> None:
    if not (math.isfinite(value) and value > 0.0):
        raise ValidationError(
            name, value, f"must be a positive number{' of ' + unit if unit else ''}"
        )


def _pair_index(
    types: tuple[ParticleType, ...], pairs: tuple[PairParameters, ...]
) -> dict[frozenset[str], PairParameters]:
    """Check the pair matrix is complete and unique; return it keyed by the unordered pair."""
    if not types:
        raise ValidationError("types", "[]", "must name at least one particle type")
    names = [t.name for t in types]
    if len(set(names)) != len(names):
        raise ValidationError("types", ",".join(names), "must have distinct names")
    if all(t.is_wall for t in types):
        raise ValidationError("types", ",".join(names), "must include a particle type")
    index: dict[frozenset[str], PairParameters] = {}
    for p in pairs:
        for name in (p.type_i, p.type_j):
            if name not in names:
                raise ValidationError(f"pair {p.type_i}/{p.type_j}", name, "is not a declared type")
        if p.key in index:
            raise ValidationError(f"pair {p.type_i}/{p.type_j}", "twice", "must be given once")
        index[p.key] = p
    by_name = {t.name: t for t in types}
    for i, a in enumerate(names):
        for b in names[i:]:
            if by_name[a].is_wall and by_name[b].is_wall:
                continue
            if frozenset((a, b)) not in index:
                raise ValidationError(
                    f"pair {a}/{b}",
                    "missing",
                    "must be given: the pair matrix must be complete so that no code's "
                    "mixing rule replaces a value",
                )
    return index
