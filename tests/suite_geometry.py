"""The geometry module (src/geometry, include/ssstargeometry.h) that rigid mesh obstacles and contact pairs share."""
import os

from harness import *  # noqa: F401,F403 (run, expect, test, paths)


@test("the closest point of a triangle (over the face, beyond each edge and vertex, degenerate triangles, 2000 random "
      "triangles against brute force), a triangle's normal, area and box, and the pseudo-normals of a tetrahedron with "
      "each defect of a surface named give the hand-computed values (1e-14)")
def geometry_hand_computed():
    out = run([os.path.join(ROOT, "tests", "test_geometry")])
    expect(out.rstrip().endswith("OK"), "tests/test_geometry did not end with OK", out)
