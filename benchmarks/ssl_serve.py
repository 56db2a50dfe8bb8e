"""A match served over the SSL protocols on loopback (127.0.0.1): the stepped rate with both
teams' software in the loop, and in real time the cameras' rate and latency measured from the
packets' own time stamps.

Usage: ``python benchmarks/ssl_serve.py [--vision ssl-2012] [--size 2] [--steps 3000]
[--seconds 5]``.

1. **Stepped.** :class:`soccer_env.protocol.server.SSLServer` with ``--size`` robots a side,
   60 commands a second; before each step each team's socket sends a ``RobotControl`` for all
   its robots (a slow turn on the spot) and reads the server's ``RobotControlResponse``; a
   :class:`~soccer_env.protocol.reader.VisionReader` reads every vision packet. Steps per
   second of wall time over ``--steps`` steps, everything in one process on one core.
2. **Real time.** The same server run in real time for ``--seconds``; per camera, the frame
   rate from the ``t_capture`` of the frames read (median interval) and, per frame, the delay
   ``t_sent - t_capture`` (the preset's latency and jitter), and how late each packet arrived
   beside its ``t_sent`` by the reader's clock; the CPU time of the process (server and
   reader) over the wall time.
"""

from __future__ import annotations

import argparse
import socket
import threading
import time

import numpy as np
from ssl_protocol.sim import ssl_simulation_robot_control_pb2 as control_pb2

from soccer_env.presets.sensors import vision as vision_preset
from soccer_env.protocol.reader import VisionReader
from soccer_env.protocol.server import SSLServer

LOOPBACK = ("127.0.0.1", 0)


def _control(size: int) -> bytes:
    control = control_pb2.RobotControl()
    for i in range(size):
        move = control.robot_commands.add(id=i).move_command.local_velocity
        move.forward, move.left, move.angular = 0.0, 0.0, 0.5
    return control.SerializeToString()


def _server(size: int, preset: str, reader: VisionReader) -> SSLServer:
    return SSLServer({"blue": size, "yellow": size, "control_dt": 1 / 60,
                      "match_duration": 3600.0}, preset, reader.address, ("127.0.0.1", 9),
                     (LOOPBACK, LOOPBACK), LOOPBACK)


def stepped(size: int, preset: str, steps: int) -> dict[str, float]:
    """Steps per second with both teams' commands and the vision read in the loop."""
    reader = VisionReader((size, size), LOOPBACK)
    server = _server(size, preset, reader)
    teams = [socket.socket(socket.AF_INET, socket.SOCK_DGRAM) for _ in range(2)]
    data = _control(size)
    try:
        for t in teams:
            t.bind(LOOPBACK)
            t.settimeout(1.0)
        server.reset(seed=0)
        t0 = time.perf_counter()
        for _ in range(steps):
            for t, address in zip(teams, server.control_addresses):
                t.sendto(data, address)
            server.step()
            for t in teams:
                t.recv(65_536)
            reader.poll()
        seconds = time.perf_counter() - t0
    finally:
        for s in (server, reader, *teams):
            s.close()
    return {"steps": steps, "seconds": seconds, "steps_per_second": steps / seconds,
            "frames": reader.frames, "dropped": sum(reader.dropped.values())}


def realtime(size: int, preset: str, seconds: float) -> dict[str, object]:
    """Per camera frame rate, delivery delay and arrival lateness in real time."""
    reader = VisionReader((size, size), LOOPBACK)
    server = _server(size, preset, reader)
    arrivals: list[tuple[float, object]] = []
    stop = threading.Event()

    def read() -> None:
        while not stop.is_set():
            for f in reader.poll(timeout=0.05):
                arrivals.append((time.time(), f))

    thread = threading.Thread(target=read)
    thread.start()
    try:
        server.reset(seed=0)  # episode time 0 is now
        cpu, wall = time.process_time(), time.perf_counter()
        server.run(duration=seconds, realtime=True)
        cpu, wall = time.process_time() - cpu, time.perf_counter() - wall
        time.sleep(0.3)
    finally:
        stop.set()
        thread.join()
        server.close()
        reader.close()
    cams = sorted({f.camera for _, f in arrivals})
    rates = {c: 1.0 / float(np.median(np.diff(sorted(f.t_capture for _, f in arrivals
                                                       if f.camera == c)))) for c in cams}
    delay = np.array([f.t_delivered - f.t_capture for _, f in arrivals])
    late = np.array([wall - f.t_delivered for wall, f in arrivals])  # the reader's clock is 0
    return {"cameras": len(cams), "rate_per_camera": rates, "frames": len(arrivals),
            "delay_ms": (1e3 * delay.min(), 1e3 * float(np.median(delay)), 1e3 * delay.max()),
            "late_ms": (1e3 * float(np.median(late)), 1e3 * float(np.percentile(late, 99))),
            "cpu_fraction": cpu / wall}


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--vision", default="ssl-2012")
    p.add_argument("--size", type=int, default=2)
    p.add_argument("--steps", type=int, default=3000)
    p.add_argument("--seconds", type=float, default=5.0)
    args = p.parse_args(argv)
    spec = vision_preset(args.vision)
    s = stepped(args.size, args.vision, args.steps)
    print(f"stepped, {args.size} vs {args.size}, vision {args.vision}: {s['steps']} steps in "
          f"{s['seconds']:.2f} s, {s['steps_per_second']:.0f} steps/s ({s['frames']} frames "
          f"read, {s['dropped']} dropped)")
    r = realtime(args.size, args.vision, args.seconds)
    rates = ", ".join(f"{v:.1f}" for v in r["rate_per_camera"].values())
    d, late = r["delay_ms"], r["late_ms"]
    print(f"real time, {args.seconds:g} s: {r['cameras']} cameras at {rates} frames/s (preset "
          f"{spec.frame_rate:g}); t_sent - t_capture {d[0]:.1f} / {d[1]:.1f} / {d[2]:.1f} ms "
          f"(min / median / max; preset {1e3 * spec.latency:.0f} ms + up to "
          f"{1e3 * spec.latency_jitter:.0f} ms); arrival after t_sent: median {late[0]:.2f} ms, "
          f"99th percentile {late[1]:.2f} ms; server and reader used "
          f"{100 * r['cpu_fraction']:.0f} % of one core")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
