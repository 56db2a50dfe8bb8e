"""A world's cameras served as SSL-Vision over real loopback sockets (127.0.0.1 only) and read
back: every frame arrives with its required fields, at the preset's rate per camera, with the
preset's latency between capture and sending, the geometry about once a second; bad
datagrams among them are counted by reason and the reading goes on."""

from __future__ import annotations

import logging

import numpy as np
import pytest

pytest.importorskip("ssl_protocol")

from worlds import make_world, park  # noqa: E402

from soccer_env.presets.sensors import vision  # noqa: E402
from soccer_env.protocol.publisher import VisionPublisher  # noqa: E402
from soccer_env.protocol.reader import VisionReader  # noqa: E402
from soccer_env.protocol.udp import check_address  # noqa: E402
from soccer_env.sim.world import idle_commands  # noqa: E402

LOOPBACK = ("127.0.0.1", 0)


def _serve(preset: str, seconds: float, bad: list[bytes] = ()):
    world = park(make_world(n_blue=2, n_yellow=2, field="ssl-div-b", control_dt=1 / 60))
    reader = VisionReader((2, 2), LOOPBACK, clock=100.0)
    pub = VisionPublisher(world, preset, address=reader.address)
    pub.reset(np.random.default_rng(0), clock=100.0)
    frames = []
    try:
        for k in range(round(seconds * 60)):
            world.step(idle_commands(world.n_robots))
            pub.step()
            pub.publish(world.time)
            if k == 30:
                for data in bad:
                    pub.sock.sendto(data, reader.address)
            frames.extend(reader.poll(timeout=0.05 if pub.sent > reader.received else 0.0))
        frames.extend(reader.poll(timeout=0.2))
    finally:
        pub.close()
        reader.close()
    return pub, reader, frames


@pytest.mark.parametrize("preset", ["ssl-2012", "realistic"])
def test_served_frames_keep_the_presets_rate_and_latency(preset):
    spec = vision(preset)
    pub, reader, frames = _serve(preset, 3.0)
    assert reader.received == pub.sent and not reader.dropped  # loopback loses nothing
    assert reader.frames == len(frames) > 0 and reader.geometry is not None
    assert pub.geometry_sent == 1 + int(pub.world.time + 1e-9)  # at 0 s and every second
    for cam in range(len(pub.cameras.cameras)):
        t = np.array(sorted(f.t_capture for f in frames if f.camera == cam))
        rate = 1.0 / np.median(np.diff(t))
        assert rate == pytest.approx(spec.frame_rate, rel=0.02)
    lag = np.array([f.t_delivered - f.t_capture for f in frames])
    assert lag.min() >= spec.latency - 1e-6
    assert lag.max() <= spec.latency + spec.latency_jitter + 1e-6


def test_senders_to_loopback_are_bound_to_loopback():
    from soccer_env.protocol.udp import sender

    sock = sender(("127.0.0.1", 10006))
    try:
        assert sock.getsockname()[0] == "127.0.0.1"
    finally:
        sock.close()


def test_bad_datagrams_are_counted_by_reason_logged_once_and_reading_goes_on(caplog):
    bad = [b"\xff" * 30, b"\xff" * 30, b"", b"\x00" * 20_000]
    with caplog.at_level(logging.WARNING, logger="soccer_env.protocol"):
        pub, reader, frames = _serve("ssl-2012", 1.0, bad)
    assert reader.dropped == {"malformed": 2, "empty": 1, "oversized": 1}
    assert reader.received == pub.sent + len(bad)
    assert reader.frames == len(frames) == pub.sent - pub.geometry_sent
    assert sum("malformed" in r.message for r in caplog.records) == 1


@pytest.mark.parametrize("address, message", [
    (("localhost", 10006), "IPv4 host"),
    (("127.0.0.1", 70000), "port must be an integer"),
    (("127.0.0.1",), "IPv4 host"),
])
def test_bad_addresses_are_refused(address, message):
    with pytest.raises(ValueError, match=message):
        check_address(address)
    with pytest.raises(ValueError, match="team_sizes"):
        VisionReader((2, 20), LOOPBACK)
