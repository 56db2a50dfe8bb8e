"""The team radio: latency, loss, silence of fallen robots, joining and leaving, seeds."""

from __future__ import annotations

import numpy as np
import pytest

from soccer_env.presets.sensors import RadioSpec
from soccer_env.sensors.radio import Message, TeamRadio


def _msg(sender, stamp=0.0):
    return Message(sender, stamp, (0.0, 0.0, 0.0), (0.0, 0.0, 0.5, 2.0))


def _radio(spec="zigbee", seed=0, names=("a", "b", "c")):
    radio = TeamRadio(spec, np.random.default_rng(seed))
    for n in names:
        radio.join(n)
    return radio


def test_messages_arrive_after_the_latency_and_not_to_the_sender():
    radio = _radio(RadioSpec(latency=0.05, jitter=0.0, loss=0.0))
    assert radio.broadcast(_msg("a"), now=1.0) == 2
    assert radio.receive("b", 1.04) == []
    assert [m.sender for m in radio.receive("b", 1.05)] == ["a"]
    assert radio.receive("b", 2.0) == []  # delivered once
    assert [m.sender for m in radio.receive("c", 2.0)] == ["a"]
    assert radio.receive("a", 2.0) == []


def test_loss_rate_and_jitter():
    radio = _radio(RadioSpec(latency=0.03, jitter=0.02, loss=0.1), names=("a", "b"))
    arrivals = []
    for k in range(4000):
        radio.broadcast(_msg("a", k), now=float(k))
        got = radio.receive("b", k + 0.051)
        arrivals += got
        assert radio.receive("b", k + 0.0299) == []
    assert len(arrivals) / 4000 == pytest.approx(0.9, abs=0.015)
    assert radio.lost + radio.delivered == 4000


def test_fallen_robots_are_silent_and_leavers_drop_out():
    radio = _radio(RadioSpec(0.0, 0.0, 0.0))
    radio.set_silent("a")
    assert radio.broadcast(_msg("a"), 0.0) == 0
    radio.set_silent("a", False)
    assert radio.broadcast(_msg("a"), 0.0) == 2
    radio.leave("c")
    assert radio.receive("c", 1.0) == []  # in-flight messages to it dropped
    assert radio.broadcast(_msg("c"), 1.0) == 0  # and it cannot send
    radio.join("d")
    assert radio.broadcast(_msg("b"), 2.0) == 2  # a and the newcomer
    assert [m.sender for m in radio.receive("d", 2.0)] == ["b"]
    with pytest.raises(ValueError, match="has not joined"):
        radio.set_silent("zz")


def test_same_seed_same_deliveries():
    def trace(seed):
        radio = _radio(seed=seed)
        out = []
        for k in range(200):
            radio.broadcast(_msg("abc"[k % 3], k * 0.04), k * 0.04)
            out.append(tuple(m.stamp for m in radio.receive("b", k * 0.04)))
        return out

    assert trace(3) == trace(3)
    assert trace(3) != trace(4)


def test_bad_input():
    with pytest.raises(ValueError, match="loss"):
        RadioSpec(loss=1.5)
    with pytest.raises(ValueError, match="latency"):
        RadioSpec(latency=-0.1)
    with pytest.raises(ValueError, match="unknown radio preset"):
        TeamRadio("wifi", np.random.default_rng(0))
    with pytest.raises(TypeError, match="Generator"):
        TeamRadio("ideal", 1)
    radio = _radio()
    with pytest.raises(ValueError, match="finite"):
        radio.broadcast(_msg("a"), float("nan"))
