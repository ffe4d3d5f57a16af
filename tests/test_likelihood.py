"""The observation likelihood p_i = exp(-alpha * residual_i) (smtmvt.likelihood)."""

import numpy as np

from smtmvt.likelihood import likelihoods


def test_integer_residuals_and_integer_valid_flags():
    """Residuals of any real dtype give float64 likelihoods (not truncated to integers);
    ``valid`` may be 0/1 integers."""
    p = likelihoods([0, 1, 2, 3], 0.5, valid=[1, 1, 0, 1])
    assert p.dtype == np.float64
    np.testing.assert_allclose(p, [1.0, np.exp(-0.5), 0.0, np.exp(-1.5)], rtol=1e-15)
    np.testing.assert_allclose(likelihoods(np.array([2.0, np.inf], np.float32), 1.0), [np.exp(-2.0), 0.0], rtol=1e-15)
