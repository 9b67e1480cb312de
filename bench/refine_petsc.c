static const char help[] = "PETSc's own route to a refined mesh, for comparison with ssstar's -dm_refine (meshrefine.c): a gmsh file read\n\
by DMPlexCreateFromFile (rank 0, interpolated: edges and faces), distributed, then refined k times by DMRefine (the\n\
regular 1:8 refinement of tetrahedra, labels refined), each phase timed with the memory of the largest rank.\n\
  -mesh <file.msh>   the mesh (e.g. meshes/prism_L8.msh)\n\
  -refine <1>        refinements\n\
Prints: phase <name> time <s> cells <n> vertices <n> rss <GB per rank, the largest>\n";

#include <petscdmplex.h>
#include <ssstarscene.h>

static PetscErrorCode Phase(const char name[], DM dm, PetscLogDouble *t)
{
  PetscLogDouble now, rss;
  PetscInt       c[2], v[2], cg[2];

  PetscFunctionBeginUser;
  PetscCall(PetscTime(&now));
  PetscCall(SSStarMemoryGetUsage(PETSC_COMM_WORLD, &rss, NULL));
  PetscCall(DMPlexGetHeightStratum(dm, 0, &c[0], &c[1]));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &v[0], &v[1]));
  cg[0] = c[1] - c[0];
  cg[1] = v[1] - v[0];
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, cg, 2, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "phase %-12s time %.3f cells %" PetscInt_FMT " vertices %" PetscInt_FMT " (with ghosts) rss %.3f\n", name, now - *t, cg[0], cg[1], rss / 1e9));
  *t = now;
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  char           mesh[PETSC_MAX_PATH_LEN] = "meshes/prism_L8.msh";
  PetscInt       refine                   = 1;
  DM             dm, other;
  PetscLogDouble t;

  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "PETSc's refinement", "bench");
  PetscCall(PetscOptionsString("-mesh", "gmsh mesh", NULL, mesh, mesh, sizeof(mesh), NULL));
  PetscCall(PetscOptionsInt("-refine", "refinements", NULL, refine, &refine, NULL));
  PetscOptionsEnd();
  PetscCall(PetscTime(&t));
  PetscCall(DMPlexCreateFromFile(PETSC_COMM_WORLD, mesh, "mesh", PETSC_TRUE, &dm));
  PetscCall(Phase("read", dm, &t));
  PetscCall(DMPlexDistribute(dm, 0, NULL, &other));
  if (other) {
    PetscCall(DMDestroy(&dm));
    dm = other;
  }
  PetscCall(Phase("distribute", dm, &t));
  for (PetscInt k = 0; k < refine; k++) {
    PetscCall(DMRefine(dm, PETSC_COMM_WORLD, &other));
    PetscCall(DMDestroy(&dm));
    dm = other;
    PetscCall(Phase("refine", dm, &t));
  }
  PetscCall(DMDestroy(&dm));
  PetscCall(PetscFinalize());
  return 0;
}
