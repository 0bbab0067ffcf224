"""The fits of measured collisions: Walton's β and μ_f, restitution against Stokes number,
the gap viscosity, their intervals (bootstrap, small-n, asymptotic, Bayesian) and bands,
the reference datasets' checks, and the synthetic known truth their coverage is measured on.

The runs come as frames from ``granudb.scenario``; nothing here reads a file or prints.
"""
