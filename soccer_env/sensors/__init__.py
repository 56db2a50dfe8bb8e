"""Sensors: what the robots' cameras and radio deliver, late and imperfect, from the truth.

* :mod:`~soccer_env.sensors.overhead`: SSL-Vision-like overhead cameras (detection frames);
* :mod:`~soccer_env.sensors.headcam`: humanoids' pan/tilt head cameras (detections in the
  image and on the ground, landmarks);
* :mod:`~soccer_env.sensors.radio`: a team's lossy, delayed radio link;
* :mod:`~soccer_env.sensors.images`: rendered camera images (the ``pixels`` extra).

Sensors read :class:`~soccer_env.state.WorldState` and :class:`~soccer_env.state.HeadState`
snapshots only, never the simulation's objects.
"""
