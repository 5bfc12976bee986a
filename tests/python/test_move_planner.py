"""The planner's shortcuts (python/stewart/moves.py) against the plain computations they replace:
the lower envelope of lines against the minimum of all of them, the static bounds per unordered
pair against every (lower, upper) pair, and the phase-plane passes over the envelope's bounds
against the same passes over every bound; the entrywise Rodrigues formula and 3x3 solve against
scipy and numpy."""
import numpy as np
import pytest
from scipy.spatial.transform import Rotation

import stewart
from stewart import moves

RNG = np.random.default_rng(36)


def lines(n, m):
    """Random lines with some missing (offset +inf), some repeated, some parallel."""
    slope = RNG.normal(size=(n, m))
    offset = RNG.normal(size=(n, m)) + 2.0
    offset[RNG.uniform(size=(n, m)) < 0.2] = np.inf
    slope[:, 1], offset[:, 1] = slope[:, 0], offset[:, 0]          # a repeated line
    slope[:, 2] = slope[:, 3]                                      # parallel lines
    return slope, offset


def test_the_envelope_keeps_every_line_that_is_ever_the_smallest():
    n, m = 400, 13
    slope, offset = lines(n, m)
    top = RNG.uniform(0, 5, n)
    top[:20], top[20:40] = 0.0, np.inf
    offset[40] = np.inf                                            # a row without lines
    keep = moves._envelope(slope, offset, top)
    assert np.array_equal(keep.any(axis=1), np.isfinite(offset).any(axis=1))
    h = np.linspace(0, 1, 2001)[None, :] * np.where(np.isfinite(top), top, 50.0)[:, None]
    with np.errstate(invalid="ignore"):
        value = slope[:, :, None] * h[:, None, :] + offset[:, :, None]
    full = value.min(axis=1)
    kept = np.where(keep[:, :, None], value, np.inf).min(axis=1)
    finite = np.isfinite(full)
    assert np.array_equal(np.isfinite(kept), finite)
    assert np.all(np.abs(kept[finite] - full[finite]) <= 1e-12 * (1 + np.abs(full[finite])))
    # It prunes: most lines are never the smallest.
    assert keep.sum() < 0.5 * np.isfinite(offset).sum()


def constraints(n=300, seed=5):
    rng = np.random.default_rng(seed)
    start = (rng.normal(size=(n, 6)), rng.normal(size=(n, 6)))
    end = (rng.normal(size=(n, 6)), rng.normal(size=(n, 6)))
    ds = np.full(n, 1.0 / n)
    accel = np.array([0.5, 0.4, np.inf, 0.5, 0.6, 0.5])            # one leg without a limit
    speed = np.minimum(rng.uniform(0.5, 3.0, n + 1), moves._X_CAP)
    upper, lower = moves._segment_constraints(start, end, ds, accel, speed)
    return upper, lower, speed, ds


def test_the_static_bounds_per_pair_are_those_of_every_pair():
    upper, lower, _, _ = constraints()
    (cu, bu, du), (cl, bl, dl) = upper, lower
    coef = dl[:, :, None] * bu[:, None, :] - du[:, None, :] * bl[:, :, None]
    rhs = dl[:, :, None] * cu[:, None, :] - du[:, None, :] * cl[:, :, None]
    every = np.divide(rhs, coef, out=np.full_like(rhs, np.inf), where=coef > 0).min(axis=(1, 2))
    assert np.array_equal(moves._static_bound(upper, lower), every)


def plain_passes(upper, lower, speed, ds):
    """The backward and forward passes over every bound, one node at a time."""
    (cu, bu, du), (cl, bl, dl) = upper, lower
    n = cu.shape[0]
    static = np.minimum(moves._static_bound(upper, lower), speed[:-1])
    hi = np.zeros(n + 1)
    for i in range(n - 1, -1, -1):
        k = dl[i] - 2 * ds[i] * bl[i]
        use = k > 0
        limit = np.min((dl[i][use] * hi[i + 1] - 2 * ds[i] * cl[i][use]) / k[use], initial=np.inf)
        hi[i] = max(0.0, min(static[i], limit))
    x = np.zeros(n + 1)
    for i in range(n):
        use = du[i] > 0
        room = np.min((cu[i][use] - bu[i][use] * x[i]) / du[i][use], initial=moves._X_CAP)
        u = min(room, (hi[i + 1] - x[i]) / (2 * ds[i]))
        x[i + 1] = max(0.0, x[i] + 2 * ds[i] * u)
    x[n] = 0.0
    return hi, x


@pytest.mark.parametrize("seed", [5, 6, 7])
def test_the_passes_over_the_envelope_are_the_passes_over_every_bound(seed):
    upper, lower, speed, ds = constraints(seed=seed)
    hi = moves._controllable(upper, lower, speed, ds)
    x, _ = moves._forward(upper, hi, ds)
    hi_plain, x_plain = plain_passes(upper, lower, speed, ds)
    assert np.allclose(hi, hi_plain, rtol=1e-12, atol=0) and hi.max() > 0
    assert np.allclose(x, x_plain, rtol=1e-12, atol=1e-300) and x.max() > 0


def test_rodrigues_and_the_3x3_solve():
    w = RNG.normal(size=(200, 3))
    w[0], w[1] = 0.0, 1e-10
    assert np.max(np.abs(moves._exp(w) - Rotation.from_rotvec(w).as_matrix())) < 1e-14
    E = stewart.angles._rate_matrix(RNG.uniform(-1.2, 1.2, (200, 3)), 0)
    b = RNG.normal(size=(200, 3))
    np.testing.assert_allclose(moves._solve3(E, b), np.linalg.solve(E, b[..., None])[..., 0],
                               rtol=0, atol=1e-12)
