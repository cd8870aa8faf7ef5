"""Lame's shrink fit, the closed form of tests/estimate: a shaft of radius b
in a hub of bore a < b and outer radius c, both E = 200000, nu = 0.3, u_z = 0
(plane strain along the axis).  The field is that of the linearized contact
problem the program solves: the gap closes along the slave's normal,
u_hub(a) - u_shaft(b) = b - a, and the hub carries the slave's force,
p_hub a = p b.  Both bodies Lame cylinders: u_r = A r (shaft), A r + B / r (hub)."""
E, nu = 200000.0, 0.3
lam, mu = E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))


def lame(b, a, c):
    """A1 (shaft), A2, B2 (hub): shaft of radius b in a hub of bore a, outer radius c."""
    def coeffs(p):
        a1 = -p / (2 * (lam + mu))
        ph = p * b / a
        b2 = ph / (2 * mu * (1 / a ** 2 - 1 / c ** 2))
        return a1, mu * b2 / ((lam + mu) * c ** 2), b2
    a1, a2, b2 = coeffs(1.0)
    p = (b - a) / ((a2 * a + b2 / a) - a1 * b)
    return coeffs(p)


def axial(coef):
    """u_r = A r + B / r in PLANE axisymmetric (x = r, y = z), u_z = 0."""
    a1, a2, b2 = coef

    def exact(x, y, body):
        A, B = (a1, 0.0) if body == 1 else (a2, b2)
        return (A * x + B / x, 0.0, A - B / (x * x), 0.0, 0.0, 0.0)
    return exact


def radial(coef):
    """The same field in the plane: u = u_r(r) (x, y) / r."""
    a1, a2, b2 = coef

    def exact(x, y, body):
        A, B = (a1, 0.0) if body == 1 else (a2, b2)
        r2 = x * x + y * y
        return (A * x + B * x / r2, A * y + B * y / r2, A + B * (r2 - 2 * x * x) / r2 ** 2,
                -2 * B * x * y / r2 ** 2, -2 * B * x * y / r2 ** 2, A + B * (r2 - 2 * y * y) / r2 ** 2)
    return exact


