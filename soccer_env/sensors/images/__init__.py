"""Rendered camera images drawn from the world state with OpenCV (the ``pixels`` extra): the
overhead camera of SSL / MiroSot vision (Li et al.'s 2010 setting) and a humanoid's head camera
(Xu et al. 2012 and Yu et al. 2010).

Images are ``(H, W, 3)`` ``uint8`` arrays in **RGB** order (as every other image of the
package, e.g. :class:`~soccer_env.render.Renderer`); convert with ``cv2.cvtColor(img,
cv2.COLOR_RGB2BGR)`` before ``cv2.imwrite``. Units are SI and radians, except where pixels are
stated.

Pixel coordinates. ``(u, v)`` are continuous pixel coordinates with ``u`` to the right and
``v`` downwards; the pixel at array index ``[j, i]`` (row ``j``, column ``i``) covers
``i <= u < i + 1``, ``j <= v < j + 1``, so its centre is ``(i + 0.5, j + 0.5)`` and the image
centre is ``(W / 2, H / 2)``: the convention of :class:`estimators.HeadCamera`.

* :mod:`~soccer_env.sensors.images.patterns`: the coloured markers on the robots' tops;
* :mod:`~soccer_env.sensors.images.overhead`: overhead frames;
* :mod:`~soccer_env.sensors.images.head`: head-camera frames;
* :mod:`~soccer_env.sensors.images.common`: the drawing units, lighting and noise
  (:class:`~soccer_env.sensors.images.common.Photometry`) and per-robot lists shared by both;
* :mod:`~soccer_env.sensors.images.cameras`: cameras that deliver these images with a
  sensor's timing.

The colour and motion operations that image trackers apply to these frames (colour look-up
table, hue back-projection, frame difference) are estimators: :mod:`estimators.image.colour`.

Cost on a 2-core machine with OpenCV 5 (``soccer-env bench --frames`` measures it): a
640 x 480 overhead frame with 12 robots about 0.5 ms clean, 2 ms with lighting and noise
(1.5 ms of which are the two full-image passes), 2.6 ms when all 12 robots and the ball are
also motion-blurred; a 320 x 240 head frame about 0.6 ms clean and 1.1 ms with lighting and
noise, 720 x 625 about 0.8 and 3 ms.
"""

try:
    import cv2  # noqa: F401
except ImportError as err:  # pragma: no cover - depends on the installation
    raise ImportError("soccer_env.sensors.images needs OpenCV; install it with: "
                      "pip install 'soccer-env[pixels]'") from err
