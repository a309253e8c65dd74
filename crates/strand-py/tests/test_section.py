"""`strand.section` over arrays: each point the scalar law of `strand section`, bit for bit;
the energy and the hysteretic state checked against the laws of mechanics."""

import json

import numpy as np
import pytest

import strand
from strand import section_point

LAWS = ["continuous", "paper", "hysteretic", "constant"]


@pytest.fixture
def scene(static_scene):
    return strand.Scene(static_scene)


@pytest.mark.parametrize("law", LAWS)
def test_vectorised_law_is_the_scalar_law_point_by_point(scene, law):
    rng = np.random.default_rng(7)
    k = rng.uniform(-0.3, 0.3, 200)  # first slip ~0.036 1/m, full slip ~0.061 1/m at 1e-3
    e = rng.uniform(-5e-4, 2e-3, 200)
    x = rng.uniform(0.0, scene.length, 200)
    r = strand.section(scene, k, e, x, law=law)
    for i in range(0, 200, 7):
        p = section_point(scene, e[i], k[i], x[i], law=law)
        assert r["moment"][i] == p["moment"]
        assert r["tangent"][i] == p["tangent_stiffness"]
        assert r["axial_force"][i] == p["axial_force"]


def test_matches_the_command_output(scene, static_scene, scene_file, cli):
    f = scene_file(static_scene)
    for e, k, at in [(1e-3, -3.0, 0.0), (2e-3, 0.04, 0.31), (0.0, 0.01, 1.2), (5e-4, -0.05, 2.5)]:
        r = cli("section", f, "--strain", e, "--curvature", k, "--at", at, "--json")
        expected = json.loads(r.stdout)
        got = strand.section(scene, k, e, at)
        assert got["moment"] == expected["moment"]
        assert got["tangent"] == expected["tangent_stiffness"]
        assert got["axial_force"] == expected["axial_force"]
        assert got["derived"] == {k: v for k, v in expected.items() if k in got["derived"]}
        point = section_point(scene, e, k, at)
        assert point == expected


def test_broadcasting_and_shapes(scene):
    k = np.linspace(-0.2, 0.2, 12).reshape(3, 4)
    r = strand.section(scene, k, 1e-3, x=np.array([0.0, 0.1, 0.2, 0.3]))
    assert r["moment"].shape == (3, 4) and r["state"].shape == (3, 4, 0)
    flat = strand.section(scene, k.ravel(), 1e-3, x=np.tile([0.0, 0.1, 0.2, 0.3], 3))
    assert np.array_equal(flat["moment"], r["moment"].ravel())
    h = strand.section(scene, k, 1e-3, law="hysteretic")
    # a slip per wire, then the stored bending direction and the committed strain
    assert h["state"].shape == (3, 4, 8 + 3)
    with pytest.raises(ValueError, match="state: shape"):
        strand.section(scene, k, 1e-3, state=np.zeros((2, 2)), law="hysteretic")
    with pytest.raises(ValueError, match="must lie on the strand"):
        strand.section(scene, 0.1, 1e-3, x=10.0)
    with pytest.raises(ValueError, match="must be finite"):
        strand.section(scene, [0.1, np.nan], 1e-3)
    with pytest.raises(ValueError, match="unknown section law"):
        strand.section(scene, 0.1, law="elastic")


def test_moment_is_the_derivative_of_the_stored_energy(scene):
    """The continuous law is elastic in planar bending: M = dW/dkappa. Central differences
    with h = 1e-7 1/m: truncation h^2 |M''| / 6 ~ 1e-14 N m and rounding ~ eps W / h ~ 1e-12
    N m against moments of 1e-3 N m; points within 2h of a wire's switch (a kink) are left
    out by requiring the same slipping count on both sides."""
    k = np.linspace(-0.25, 0.25, 401)
    h = 1e-7
    x = 0.013
    r = strand.section(scene, k, 1e-3, x)
    up = strand.section(scene, k + h, 1e-3, x)
    down = strand.section(scene, k - h, 1e-3, x)
    smooth = (up["slipping"] == down["slipping"]) & (k != 0.0)
    assert smooth.sum() > 350
    fd = (up["energy"] - down["energy"]) / (2 * h)
    assert np.allclose(fd[smooth], r["moment"][smooth], rtol=1e-6, atol=1e-10)


def test_hysteretic_state_carries_a_loading_path(scene):
    """Load to beyond full slip, unload and reload along a closed loop, passing the state
    from step to step. (1) On reversal every wire sticks again: the tangent is K_max, the
    all-stick stiffness of the derived quantities. (2) The work of the moment over the loop,
    a trapezoid sum of M dkappa, equals the change of stored energy plus the slip work
    (energy balance), to the trapezoid error O(dkappa^2); and it is positive (friction)."""
    n = scene._core.state_len("hysteretic")
    path = np.concatenate([np.linspace(0, 0.2, 801), np.linspace(0.2, -0.2, 1601)[1:], np.linspace(-0.2, 0.2, 1601)[1:]])
    state = np.zeros(n)
    moments, energies, slip = [], [], 0.0
    tangents = []
    for kappa in path:
        r = strand.section(scene, kappa, 1e-3, 0.0, state=state, law="hysteretic")
        state = r["state"]
        moments.append(float(r["moment"]))
        energies.append(float(r["energy"]))
        tangents.append(float(r["tangent"]))
        slip += float(r["slip_work"])
    m = np.array(moments)
    work = np.sum(0.5 * (m[1:] + m[:-1]) * np.diff(path))
    balance = energies[-1] - energies[0] + slip
    assert work > 0 and slip > 0
    assert work == pytest.approx(balance, rel=1e-3)
    k_max = scene.summary()["K_max"]
    reversal = 801  # first step down from 0.2
    assert tangents[reversal] == pytest.approx(k_max, rel=1e-12)
    assert tangents[reversal - 1] < 0.5 * k_max  # fully slipped before the reversal
