"""Option registries: name -> value and description, errors that list the options."""

import pytest

from estimators.registry import Registry


def test_registration_order_lookup_and_descriptions():
    reg = Registry("colour", [("red", 1, "the colour of stop"), ("green", 2, "go")])
    reg.register("blue", 3, "  cold,\n calm ")
    assert list(reg) == ["red", "green", "blue"] and len(reg) == 3
    assert reg["green"] == 2 and "blue" in reg and "pink" not in reg
    assert reg.description("blue") == "cold, calm"
    assert reg.descriptions() == {"red": "the colour of stop", "green": "go", "blue": "cold, calm"}
    assert reg.check("red") == "red"


def test_unknown_names_list_the_options():
    reg = Registry("ball filter", [("kf", dict, "plain"), ("ekf", list, "extended")])
    with pytest.raises(ValueError, match=r"ball_filter must be one of \['kf', 'ekf'\], got 'x'"):
        reg.check("x", "ball_filter")
    with pytest.raises(ValueError, match="ball filter must be one of"):
        reg.create("x")
    with pytest.raises(ValueError, match="ball filter must be one of"):
        reg.description(3)
    assert reg.create("ekf", (1, 2)) == [1, 2]


def test_duplicates_and_bad_entries_are_refused():
    reg = Registry("preset", [("a", 1, "first")])
    with pytest.raises(ValueError, match="already registered"):
        reg.register("a", 2, "again")
    reg.register("a", 2, "replaced", replace=True)
    assert reg["a"] == 2 and list(reg) == ["a"]
    for bad in ("", " a", "a,b", 3):
        with pytest.raises(ValueError, match="names must be"):
            reg.register(bad, 0, "x")
    with pytest.raises(ValueError, match="description"):
        reg.register("b", 0, " ")


# --------------------------------------------------------------------------------------------
# The estimators' option families
# --------------------------------------------------------------------------------------------


def test_the_estimators_registries_hold_what_their_names_stand_for():
    import numpy as np

    from estimators import (
        FBPF,
        FUSION_WEIGHTINGS,
        MEAN_SHIFT_KERNELS,
        MFBPF,
        PARTICLE_FILTERS,
        BootstrapPF,
    )

    assert dict(PARTICLE_FILTERS) == {"bootstrap": BootstrapPF, "fbpf": FBPF, "mfbpf": MFBPF}
    assert dict(FUSION_WEIGHTINGS) == {"equal": 0, "inverse": 1, "inverse_square": 2}
    assert list(MEAN_SHIFT_KERNELS) == ["flat", "epanechnikov"]
    ys, xs = np.mgrid[0:3, 0:5].astype(np.float64)
    np.testing.assert_array_equal(MEAN_SHIFT_KERNELS["flat"](xs, ys), np.ones((3, 5)))
    k = MEAN_SHIFT_KERNELS["epanechnikov"](xs, ys)
    assert k[1, 2] == 1.0 and k[0, 0] == 0.0 and 0.0 < k[1, 1] < 1.0
    for reg in (PARTICLE_FILTERS, FUSION_WEIGHTINGS, MEAN_SHIFT_KERNELS):
        for name, text in reg.descriptions().items():
            assert "\n" not in text and len(text) > 20, (reg.family, name)


def test_unknown_estimator_options_are_refused_with_the_options_listed():
    import numpy as np

    from estimators import ParticleBallTracker, fuse_sightings, fusion_weights, mean_shift

    with pytest.raises(ValueError, match=r"^filter must be one of \['bootstrap', 'fbpf', "
                                         r"'mfbpf'\], got 'kalman'$"):
        ParticleBallTracker(np.random.default_rng(0), filter="kalman")
    weightings = (r"^weighting must be one of \['equal', 'inverse', 'inverse_square', "
                  r"'inverse_variance'\], got 'cubic'$")
    with pytest.raises(ValueError, match=weightings):
        fusion_weights([1.0, 2.0], "cubic")
    with pytest.raises(ValueError, match=weightings):
        fuse_sightings([[0.0, 0.0], [1.0, 0.0]], [0.3, 1.0], [1.0, 1.0], weighting="cubic")
    with pytest.raises(ValueError, match=r"^kernel must be one of \['flat', 'epanechnikov'\], "
                                         r"got 'gauss'$"):
        mean_shift(np.zeros((8, 8)), (0, 0, 2, 2), kernel="gauss")


def test_unregister_removes_an_option():
    reg = Registry("kernel", [("flat", 1, "flat"), ("cone", 2, "cone")])
    assert reg.unregister("flat") == 1
    assert list(reg) == ["cone"] and reg.descriptions() == {"cone": "cone"}
    with pytest.raises(ValueError, match="kernel must be one of"):
        reg.unregister("flat")
