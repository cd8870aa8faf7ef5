"""Closed forms of homogeneous deformations of the neo-Hookean law
W = mu/2 (J^-2/3 I1 - 3) + K/2 (J - 1)^2 (doc/theory.md, "Hyperelastic
bodies in finite strain"), for the checks of tests/finite: with
F = diag(lx, ly, lz), J = lx ly lz, the Cauchy stress is
    sigma = mu J^-5/3 (F F' - I1/3 I) + K (J - 1) I,   I1 = lx^2 + ly^2 + lz^2."""


def sigma(lx, ly, lz, K, mu=1.0):
    """The principal Cauchy stresses (sxx, syy, szz) of F = diag(lx, ly, lz)."""
    J = lx * ly * lz
    i1 = lx * lx + ly * ly + lz * lz
    s = lambda l: mu * J ** (-5.0 / 3.0) * (l * l - i1 / 3.0) + K * (J - 1.0)
    return s(lx), s(ly), s(lz)


def solve_free(f, lo=0.5, hi=2.0):
    """The root of f(l) = 0 by bisection (f increasing)."""
    for _ in range(200):
        m = 0.5 * (lo + hi)
        if f(m) > 0:
            hi = m
        else:
            lo = m
    return 0.5 * (lo + hi)


def block_exact(K, s):
    """A block squeezed by s between frictionless plates, free sides, plane
    strain (lz = 1): (lx, ly, the plate force per unit length and thickness)."""
    ly = 1.0 - s
    lx = solve_free(lambda l: sigma(l, ly, 1.0, K)[0])
    return lx, ly, -sigma(lx, ly, 1.0, K)[1] * lx
