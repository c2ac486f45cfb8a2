"""Jump-in / jump-out detection on an adhesive sphere, and none on stable branches."""

import numpy as np
import pytest

import roughcontact as rc


@pytest.fixture(scope="module")
def sphere_path():
    n, radius = 96, 80.0
    h, sub = rc.sphere((n, n), radius), rc.Substrate((n, n))
    law = rc.SmoothLJ93(work_of_adhesion=0.05, stiffness=0.5)  # Δr = 1.1 a0
    return rc.approach_retract(h, sub, law, offsets=np.arange(2.6, -0.45, -0.1), tol=1e-8)


def test_one_jump_in_and_one_jump_out_with_hysteresis(sphere_path):
    ds = sphere_path
    assert ds.attrs["all_converged"]
    jumps = np.flatnonzero(ds["jump"].values)
    assert len(jumps) == 2
    jump_in, jump_out = jumps
    branch = ds["branch"].values
    assert branch[jump_in] == "approach" and branch[jump_out] == "retract"
    # the load drops abruptly into tension on the jump-in and back to ~0 on the jump-out
    load = ds["load"].values
    assert load[jump_in] < 50 * load[jump_in - 1] < 0
    assert abs(load[jump_out]) < 1e-3 * abs(load[jump_out - 1])
    # hysteresis: the retraction detaches at a larger offset than the approach attached
    assert ds["offset"].values[jump_out] > ds["offset"].values[jump_in]


def test_hard_wall_paths_have_no_jumps():
    h = rc.self_affine((64, 64), hurst=0.8, rms_slope=0.1, short_cutoff=4, seed=2)
    sub = rc.Substrate((64, 64))
    ds = rc.approach_retract(h, sub, offsets=h.max() - np.linspace(0, 0.6, 6))
    assert ds.attrs["all_converged"]
    assert not ds["jump"].values.any()


def test_hard_wall_offset_below_the_mean_height_is_rejected():
    h = rc.self_affine((32, 32), hurst=0.8, rms_slope=0.1, short_cutoff=4, seed=2)
    with pytest.raises(rc.ParameterError, match="offset must be >= mean"):
        rc.solve(h, rc.Substrate((32, 32)), offset=h.mean() - 0.1)
