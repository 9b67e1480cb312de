"""The geometry module (src/geometry, include/ssstargeometry.h) that rigid mesh obstacles and contact pairs share."""
import os

from harness import *  # noqa: F401,F403 (run, expect, test, paths)


@test("the closest point of a triangle (over the face, beyond each edge and vertex, degenerate triangles, 2000 random "
      "triangles against brute force), a triangle's normal, area and box, and the pseudo-normals of a tetrahedron with "
      "each defect of a surface named give the hand-computed values (1e-14); the search tree gives the closest triangle "
      "(ties: the lowest number) and the triangles meeting a region as a loop over all of them, bit for bit, on random "
      "soups, identical and zero-area triangles, exact ties on a curved grid's vertices, one triangle and none")
def geometry_hand_computed():
    out = run([os.path.join(ROOT, "tests", "test_geometry")])
    expect(out.rstrip().endswith("OK"), "tests/test_geometry did not end with OK", out)


@test("the search over triangles spread over the ranks (tests/test_search) answers as a loop over all triangles on 1, "
      "2, 3 and 4 ranks, however the triangles are spread (compact parts, every size-th, all on rank 0): the closest "
      "triangle with its distance, closest point, barycentric coordinates and feature bit for bit (ties: the least key "
      "among the closest, or within a tolerance), its data, and the triangles meeting boxes and oriented regions (infinite "
      "too) in key order; a search without triangles finds none")
def search_against_brute_force():
    for ranks in (1, 2, 3, 4):
        out = run(mpiexec(ranks, os.path.join(ROOT, "tests", "test_search")))
        expect(out.rstrip().endswith("OK"), "tests/test_search on %d ranks did not end with OK" % ranks, out)
