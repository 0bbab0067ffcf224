"""Pure, vectorized physics of particle–wall collisions in liquids.

Every function takes numpy arrays or scalars in SI units and returns arrays (or floats);
nothing here reads a database, prints or imports pandas. Equation numbers refer to
Joseph & Hunt (2004), *Oblique particle–wall collisions in a liquid*, J. Fluid Mech. 510,
71–93 (doi:10.1017/S002211200400919X), unless a docstring says otherwise; "thesis" refers
to the contact-mechanics chapter in ``shared/seeds`` (after Johnson 1985, *Contact
Mechanics*).

Modules by topic: ``contact`` (pair properties, Hertz), ``flow`` (Re, St, predicted wet
restitution), ``lubrication`` (EHD gap, piezoviscosity, lubricated friction), ``impact``
(e, β, Ψ, Walton, Maw), ``pair`` (a particle and a moving target: relative contact-point
velocities, Walton factor, Davis's pair Stokes number), ``limits`` (yield, the bounds of
(5.8), the uncertain gap band), ``apparatus`` (the pendulum of the Appendix),
``viscosity`` (fluid models) and ``derive`` (everything at once, for a table of
collisions).
"""
