"""The biceps engine: model, skeleton, configuration, mesh, rasterizer and export.

Nothing here imports a terminal library (textual, rich): the headless ``snapshot`` path
and the tests use this package alone.

Conventions, stated once for every module:

- Units are centimetres and degrees at the edges (configs, CLI, UI); radians inside.
- World space is right-handed, ``y`` up. The arm bends in the ``x``-``y`` plane: the elbow
  is at the origin, the upper arm points up (``+y``), flexion swings the forearm towards
  ``+x`` (the front of the arm). The default camera looks from ``+z`` towards ``-z``.
- Points are rows: an ``(n, 3)`` array is ``n`` points, and a 4x4 matrix ``M`` acts on
  column vectors, so points transform as ``points @ M[:3, :3].T + M[:3, 3]``.
- A mesh is structure-of-arrays numpy: ``vertices (n, 3) float64``, ``normals (n, 3)
  float64`` (unit length), ``triangles (m, 3) int32`` wound counter-clockwise when seen
  from outside.
- The framebuffer is ``(h, w, 3) uint8`` and the depth buffer ``(h, w) float32``; both are
  allocated once per size and reused from frame to frame.
"""
