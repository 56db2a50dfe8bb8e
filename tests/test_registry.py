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
