"""The arguments of the physics relations, described once: name → "description [unit]".

Every public relation in ``granudb.physics`` gets its numpydoc ``Parameters`` section from
this table through the ``parameters`` decorator, so an argument that means the same thing
(``radius``, ``viscosity``, ``reduced_modulus_pa`` …) is described, with its unit, in one
place, and ``help()``, the doctests and the documentation site show the whole section. An
argument with a special meaning in one relation keeps its own sentence, given to the
decorator (``@parameters(stokes="… [-]")``). The pattern is scipy's ``scipy._lib.doccer``
and pandas' ``pandas.util._decorators.doc``: docstrings completed from shared text when the
function is defined.

Units in square brackets, ``[-]`` when dimensionless; SI throughout (docs/physics.md).
"""

from __future__ import annotations

import inspect
from collections.abc import Callable
from typing import TypeVar, overload

F = TypeVar("F", bound=Callable[..., object])

#: name → "description [unit]" of every argument of the public physics relations.
ARGUMENTS: dict[str, str] = {
    "added_mass": "added-mass coefficient C_M; 1/2 for a sphere [-]",
    "approach": "approach of the centres δ [m]",
    "approach_speed": "normal approach speed v₀ [m/s]",
    "beta": "rotational restitution β [-]",
    "c": "c = η̂ p_max [-]",
    "chi": "Maw's modified radius of gyration χ [-]",
    "code": "integer state codes [-]",
    "coefficient": "β_L of the exponential law [-]",
    "contact_radius": "Hertz contact radius a [m]",
    "contact_stiffness": "lateral contact stiffness κ [N/m]",
    "contact_time_s": "contact duration t_c [s]",
    "critical_stokes": "critical Stokes number St_c, no rebound below it [-]",
    "density": "density ρ of the sphere [kg/m³]",
    "diameter": "diameter d [m]",
    "dry_friction": "dry friction coefficient μ_dry [-]",
    "dry_restitution": "dry normal restitution e_dry [-]",
    "effective_mass": "effective mass m* [kg]",
    "effective_radius": "effective radius R* [m]",
    "elastic_length": "Davis's elastic length x₁ [m]; NaN where there is no liquid",
    "energy_returned": "energy returned in unloading W′ [J]",
    "energy_stored": "elastic energy stored at the peak W [J]",
    "eta_hat": "Chu–Cameron pressure coefficient η̂ [1/Pa]",
    "factor": "Walton factor B; 7/2 for a sphere on a wall or two equal spheres [-]",
    "film_thickness": "film thickness h [m]",
    "fluid_density": "fluid density ρ_f [kg/m³]",
    "fraction": "h_m / x₁, 1/3 in the paper (Davis et al. give 1/4 to 1/3) [-]",
    "friction": "sliding friction coefficient μ_f [-]",
    "gyration": "K², the squared radius of gyration over R²; 2/5 for a solid sphere [-]",
    "has_pressure_coefficient": "whether the fluid has a pressure–viscosity coefficient [bool]",
    "immersed": "whether the collision is in a liquid [bool]",
    "integral": "A(η̂ p_max) of (5.9) [-]",
    "limiting_shear_slope": "slope γ of the limiting shear stress τ_L = τ_L0 + γ p [-]",
    "load": "impact load W [N]",
    "mass": "mass m (the effective mass for two bodies) [kg]",
    "mass_1": "mass of body 1 [kg]",
    "mass_2": "mass of body 2 [kg]; ∞ for a wall or a fixed sphere",
    "mass_fraction": "glycerol mass fraction C_m [-]",
    "max_pressure_pa": "maximum Hertz pressure p_max [Pa]",
    "normal_force": "normal force R_n [N]",
    "normal_speed": "normal approach speed v_N,in [m/s]",
    "omega": "angular velocity ω [rad/s]",
    "particle_density": "particle density ρ_p [kg/m³]",
    "particle_gyration": "K² = I/(mR²) of the particle [-]",
    "particle_mass": "mass of the particle m₁ [kg]",
    "particle_omega": "spin of the particle about n × t [rad/s]",
    "particle_radius": "radius of the particle [m]",
    "particle_v_n": "the particle's velocity along n [m/s] (n from particle to target)",
    "particle_v_t": "velocity of the particle's centre along t [m/s]",
    "particle_yield_stress": "particle's yield stress Y [Pa]; NaN where not known",
    "period": "torsional oscillation period τ [s]",
    "poisson_1": "Poisson ratio ν₁ of body 1 [-]",
    "poisson_2": "Poisson ratio ν₂ of body 2 [-]",
    "poisson_ratio": "Poisson ratio ν [-]",
    "pressure": "pressure p [Pa]",
    "pressure_coefficient": "Barus pressure–viscosity coefficient C [1/Pa]",
    "psi_in": "effective incidence Ψ_in [-]",
    "psi_out": "effective rebound Ψ_out [-]",
    "radius": "radius R (the effective radius for two bodies) [m]",
    "radius_1": "radius of body 1 [m]",
    "radius_2": "radius of body 2 [m]; ∞ for a flat wall",
    "ratio": "(1−ν)/(2−ν) of the material, or the pair's stiffness ratio 2G*/E* [-]",
    "reduced_modulus_pa": "reduced modulus E* [Pa]",
    "reduced_shear_modulus_pa": "reduced shear modulus G* [Pa]",
    "restitution": "normal restitution e [-]",
    "rolling_coefficient": "rolling friction coefficient μ_r [-]",
    "rolling_length": "rolling friction length λ_r [m]",
    "roughness": "composite RMS roughness σ [m]",
    "roughness_1": "RMS roughness of surface 1 [m]",
    "roughness_2": "RMS roughness of surface 2 [m]",
    "shear_1": "shear modulus G₁ of body 1 [Pa]",
    "shear_2": "shear modulus G₂ of body 2 [Pa]",
    "speed": "impact speed V (the normal component for an oblique impact) [m/s]",
    "states": "the names of the states, by code [-]",
    "stokes": "Stokes number St [-]",
    "string_stiffness": "string torsional stiffness K_s [N·m]",
    "tangential_speed": "tangential speed of the contact point U [m/s]",
    "target_gyration": "K² = I/(mR²) of the target [-]",
    "target_mass": "mass of the target m₂ [kg]; ∞ for a wall or a fixed sphere",
    "target_omega": "spin of the target about n × t [rad/s]",
    "target_radius": "radius of the target [m] (a wall's term is 0: pass 0 for it)",
    "target_v_n": "the target's velocity along n [m/s] (0 for a wall or fixed sphere)",
    "target_v_t": "velocity of the target's centre along t [m/s]",
    "temperature_c": "temperature T [°C]",
    "v_n_in": "normal speed before impact v_N,in [m/s]",
    "v_N_in": "relative normal approach speed v_N,in (> 0) [m/s]",
    "v_n_out": "normal speed after impact (positive, away from the target) [m/s]",
    "v_t": "tangential velocity of the centre v_t [m/s]",
    "v_T": "tangential velocity of the contact point v_T [m/s]",
    "v_T_in": "tangential velocity of the contact point before impact v_T,in [m/s]",
    "v_T_out": "tangential velocity of the contact point after impact v_T,out [m/s]",
    "viscosity": "viscosity μ (μ₀ at ambient pressure) [Pa·s]",
    "wall_yield_stress": "target's yield stress Y [Pa]; NaN where not known",
    "wave_speed_m_s": "bulk elastic wave speed c [m/s]",
    "yield_speed": "normal impact speed at the onset of yield V_y [m/s]",
    "yield_stress": "yield stress Y of the softer body, in tension [Pa]",
    "youngs_1": "Young's modulus E₁ of body 1 [Pa]",
    "youngs_2": "Young's modulus E₂ of body 2 [Pa]",
    "youngs_modulus": "Young's modulus E [Pa]",
}

#: numpydoc section headings that follow ``Parameters``.
_LATER_SECTIONS = ("Returns", "Yields", "Raises", "See Also", "Notes", "References", "Examples")


def parameters_section(names: list[str], special: dict[str, str]) -> str:
    """The numpydoc ``Parameters`` section for ``names``, from ``special`` or ``ARGUMENTS``.

    Examples
    --------
    >>> print(parameters_section(["radius", "stokes"], {"stokes": "Stokes number St [-]"}))
    Parameters
    ----------
    radius : radius R (the effective radius for two bodies) [m]
    stokes : Stokes number St [-]
    """
    unknown = [name for name in names if name not in special and name not in ARGUMENTS]
    if unknown:
        raise KeyError(f"no description for argument(s) {', '.join(unknown)}: add to ARGUMENTS")
    entries = [f"{name} : {special.get(name) or ARGUMENTS[name]}" for name in names]
    return "\n".join(["Parameters", "----------", *entries])


@overload
def parameters(function: F, /) -> F: ...


@overload
def parameters(function: None = None, /, **special: str) -> Callable[[F], F]: ...


def parameters(function: F | None = None, /, **special: str) -> F | Callable[[F], F]:
    """Decorator: insert the ``Parameters`` section of the function's arguments into its
    docstring, before its first later section (``Returns``, ``Examples`` …).

    ``special`` gives an argument its own sentence in this function, in place of the
    table's.

    Examples
    --------
    >>> @parameters(stokes="Stokes number St at which the fit was made [-]")
    ... def ratio(stokes, radius):
    ...     \"\"\"A ratio.
    ...
    ...     Examples
    ...     --------
    ...     \"\"\"
    >>> print(ratio.__doc__)
    A ratio.
    <BLANKLINE>
    Parameters
    ----------
    stokes : Stokes number St at which the fit was made [-]
    radius : radius R (the effective radius for two bodies) [m]
    <BLANKLINE>
    Examples
    --------
    """

    def decorate(function: F) -> F:
        names = list(inspect.signature(function).parameters)
        section = parameters_section(names, special)
        lines = inspect.cleandoc(function.__doc__ or "").splitlines()
        if "Parameters" in lines:
            raise ValueError(f"{function.__name__}: its Parameters section is generated here")
        at = next(
            (
                index
                for index, line in enumerate(lines[:-1])
                if line in _LATER_SECTIONS and set(lines[index + 1]) == {"-"}
            ),
            len(lines),
        )
        before = "\n".join(lines[:at]).rstrip()
        after = "\n".join(lines[at:])
        function.__doc__ = f"{before}\n\n{section}\n" + (f"\n{after}" if after else "")
        return function

    return decorate if function is None else decorate(function)
