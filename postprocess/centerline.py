"""Centerline of a boom from a results file's coordinates: ANCF beams
(cubic Hermite, node-major (x, y, dx/ds, dy/ds)) and rigid bodies
((x_c, y_c, theta), axis through the centre). Used to evaluate positions at
any material coordinate, e.g. for boom 3's moving frame (paper Fig. 9)."""
import numpy as np


def position(q, first, ncoords, length, s):
    """Position r(s) of a body whose coordinates are q[first:first+ncoords]."""
    if ncoords == 3:  # rigid body
        xc, yc, th = q[first:first + 3]
        a = s - 0.5 * length
        return np.array([xc + a * np.cos(th), yc + a * np.sin(th)])
    n_el = ncoords // 4 - 1
    l = length / n_el
    el = min(int(np.floor(s / l)), n_el - 1)
    xi = (s - el * l) / l
    e = q[first + 4 * el: first + 4 * el + 8]
    sh = [1 - 3 * xi**2 + 2 * xi**3, l * (xi - 2 * xi**2 + xi**3), 3 * xi**2 - 2 * xi**3, l * (-xi**2 + xi**3)]
    return sum(sh[k] * e[2 * k: 2 * k + 2] for k in range(4))


def moving_frame_deflection(q, first, ncoords, length, s_axis, s_point):
    """Deflection of material point s_point normal to the axis from r(0) to r(s_axis) (paper Fig. 9)."""
    o = position(q, first, ncoords, length, 0.0)
    x = position(q, first, ncoords, length, s_axis) - o
    x /= np.linalg.norm(x)
    n = np.array([-x[1], x[0]])
    return float(np.dot(position(q, first, ncoords, length, s_point) - o, n))


def positions(q, first, ncoords, length, s):
    """Positions r(s) for an array of material coordinates s: shape (len(s), 2).

    The same interpolation as position() (cubic Hermite on the element that
    holds s, the last element for s = length; straight axis for rigid
    bodies), evaluated for many points at once."""
    s = np.atleast_1d(np.asarray(s, dtype=float))
    if ncoords == 3:  # rigid body
        xc, yc, th = q[first:first + 3]
        a = s - 0.5 * length
        return np.column_stack([xc + a * np.cos(th), yc + a * np.sin(th)])
    n_el = ncoords // 4 - 1
    l = length / n_el
    el = np.minimum(np.floor(s / l).astype(int), n_el - 1)
    xi = (s - el * l) / l
    nodes = np.asarray(q[first:first + ncoords]).reshape(n_el + 1, 4)
    r0, d0, r1, d1 = nodes[el, :2], nodes[el, 2:], nodes[el + 1, :2], nodes[el + 1, 2:]
    sh = [1 - 3 * xi**2 + 2 * xi**3, l * (xi - 2 * xi**2 + xi**3), 3 * xi**2 - 2 * xi**3, l * (-xi**2 + xi**3)]
    return sh[0][:, None] * r0 + sh[1][:, None] * d0 + sh[2][:, None] * r1 + sh[3][:, None] * d1


def polyline(q, first, ncoords, length, per_element=8):
    """Points along a body's centerline for drawing: a beam sampled
    `per_element` times per element with its shape functions, so that point
    k * per_element is exactly node k; a rigid body as its two ends."""
    if ncoords == 3:
        return positions(q, first, ncoords, length, [0.0, length])
    n_el = ncoords // 4 - 1
    return positions(q, first, ncoords, length, np.linspace(0.0, length, n_el * per_element + 1))
