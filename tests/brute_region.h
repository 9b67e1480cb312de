/* The brute-force answer the search tree's region queries are tested against (tests/test_geometry.c, test_search.c) */
#ifndef BRUTE_REGION_H
#define BRUTE_REGION_H
#include <ssstargeometry.h>

/* Whether the triangle's vertices, measured from the region's origin along each axis, overlap its bounds */
static PetscBool BruteMeets(const PetscReal x[9], const SSStarRegion *r)
{
  for (PetscInt a = 0; a < 3; a++) {
    PetscReal lo = PETSC_MAX_REAL, hi = PETSC_MIN_REAL;

    for (PetscInt k = 0; k < 3; k++) {
      PetscReal v = 0;

      for (PetscInt c = 0; c < 3; c++) v += (x[3 * k + c] - r->origin[c]) * r->axes[3 * a + c];
      lo = PetscMin(lo, v);
      hi = PetscMax(hi, v);
    }
    if (lo > r->hi[a] || hi < r->lo[a]) return PETSC_FALSE;
  }
  return PETSC_TRUE;
}

#endif
