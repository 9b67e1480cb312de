static const char help[] = "The seed's test problem: an elastic prism pressed onto a rigid plane with Coulomb friction,\n\
solved by the semismooth* Newton method (SNES type ssstar) on the contact dofs.\n\
  -level <6>                 mesh level L of meshes/prism.geo: (4L+1)x(2L+1)x(2L+1) nodes\n\
  -mesh <file.msh>           any gmsh mesh with physical groups dirichlet, top, right, contact (instead of -level)\n\
  -geo <file.geo>            the geometry meshed for -level (default: meshes/prism.geo of the source tree)\n\
  -E <2.1e5> -nu <0.3>       Young's modulus and Poisson ratio\n\
  -friction <0.3>            Coulomb friction coefficient (same as -snes_ssstar_friction)\n\
  -traction_top <0,0,-500>   traction on the group top\n\
  -traction_right <-200,30,200> traction on the group right\n\
  -reduction <mumps>         Schur complement: mumps (MUMPS's own, on rank 0) or explicit (MATSCHURCOMPLEMENT)\n\
  -o <file.h5>               write the solution (HDF5 + XDMF)\n\
  -summary_header <true>     print the header line of the summary table\n";

#include <ssstar.h>
#include <ssstarcontact.h>

#ifndef SSSTAR_MESH_DIR
  #define SSSTAR_MESH_DIR "meshes"
#endif

static PetscErrorCode GetVector3(const char name[], PetscReal v[3])
{
  PetscInt  n = 3;
  PetscBool set;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsGetRealArray(NULL, NULL, name, v, &n, &set));
  PetscCheck(!set || n == 3, PETSC_COMM_WORLD, PETSC_ERR_ARG_WRONG, "Option %s needs three comma-separated values x,y,z (got %" PetscInt_FMT ")", name, n);
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  SSStarScene         scene = {2.1e5, 0.3, {0, 0, -500}, {-200, 30, 200}};
  PetscInt            level = 6, nnodes, counts[SSSTAR_NUM_STATES], its, ncontact;
  PetscReal           friction = 0.3, t_assembly, t_schur, t_solve, t0;
  char                mesh[PETSC_MAX_PATH_LEN] = "", geo[PETSC_MAX_PATH_LEN] = SSSTAR_MESH_DIR "/prism.geo", out[PETSC_MAX_PATH_LEN] = "";
  PetscBool           hasMesh, hasOut, header = PETSC_TRUE;
  SSStarReductionType rtype = SSSTAR_REDUCTION_MUMPS;
  DM                  dm;
  Vec                 tags, F, u, uC, rC;
  Mat                 K;
  SSStarContactNodes  cn;
  SSStarReduction     red;
  Mat                 P;
  Vec                 f;
  SNES                snes;
  SNESConvergedReason reason;
  PetscMPIInt         size;

  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(SSStarInitializePackage());
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "Prism contact problem", "ssstar");
  PetscCall(PetscOptionsInt("-level", "Mesh level of meshes/prism.geo", NULL, level, &level, NULL));
  PetscCall(PetscOptionsString("-mesh", "gmsh mesh file (instead of -level)", NULL, mesh, mesh, sizeof(mesh), &hasMesh));
  PetscCall(PetscOptionsString("-geo", "Geometry meshed for -level", NULL, geo, geo, sizeof(geo), NULL));
  PetscCall(PetscOptionsReal("-E", "Young's modulus", NULL, scene.E, &scene.E, NULL));
  PetscCall(PetscOptionsReal("-nu", "Poisson ratio", NULL, scene.nu, &scene.nu, NULL));
  PetscCall(PetscOptionsReal("-friction", "Coulomb friction coefficient", NULL, friction, &friction, NULL));
  PetscCall(PetscOptionsEnum("-reduction", "Schur complement", NULL, SSStarReductionTypes, (PetscEnum)rtype, (PetscEnum *)&rtype, NULL));
  PetscCall(PetscOptionsString("-o", "Output file (HDF5; an XDMF file is written beside it)", NULL, out, out, sizeof(out), &hasOut));
  PetscCall(PetscOptionsBool("-summary_header", "Print the header of the summary table", NULL, header, &header, NULL));
  PetscOptionsEnd();
  PetscCall(GetVector3("-traction_top", scene.traction_top));
  PetscCall(GetVector3("-traction_right", scene.traction_right));
  if (hasOut) PetscCall(SSStarCheckOutputFile(PETSC_COMM_WORLD, out)); /* before the work, not after */

  /* mesh, FEM */
  PetscCall(PetscTime(&t0));
  if (!hasMesh) {
    size_t len;

    /* meshes/prism.geo at level 6 -> meshes/prism_L6.msh */
    PetscCall(PetscStrlen(geo, &len));
    PetscCheck(len > 4 && !strcmp(geo + len - 4, ".geo"), PETSC_COMM_WORLD, PETSC_ERR_ARG_WRONG, "-geo %s: expected a .geo file", geo);
    PetscCall(PetscSNPrintf(mesh, sizeof(mesh), "%.*s_L%" PetscInt_FMT ".msh", (int)(len - 4), geo, level));
    PetscCall(SSStarMeshGeneratePrism(PETSC_COMM_WORLD, geo, level, mesh));
  }
  PetscCall(SSStarMeshLoad(PETSC_COMM_WORLD, mesh, &dm, &tags));
  PetscCall(SSStarAssembleElasticity(dm, &scene, &K, &F));
  PetscCall(SSStarContactNodesCreate(dm, tags, &cn));
  PetscCall(PetscTimeSubtract(&t0));
  t_assembly = -t0;

  /* reduction to the contact dofs */
  PetscCall(PetscTime(&t0));
  PetscCall(SSStarReductionCreate(K, F, cn.isC, cn.isI, rtype, &red));
  PetscCall(SSStarReductionGetProblem(red, &P, &f));
  PetscCall(PetscTimeSubtract(&t0));
  t_schur = -t0;

  /* the contact problem */
  PetscCall(SNESCreate(PETSC_COMM_WORLD, &snes));
  PetscCall(SNESSetType(snes, SNESSSSTAR));
  PetscCall(SNESSSStarSetFriction(snes, friction));
  PetscCall(SNESSSStarSetContactProblem(snes, P, f));
  PetscCall(SNESSetFromOptions(snes));
  PetscCall(VecDuplicate(f, &uC));
  PetscCall(VecZeroEntries(uC));
  PetscCall(PetscTime(&t0));
  PetscCall(SNESSolve(snes, NULL, uC));
  PetscCall(PetscTimeSubtract(&t0));
  t_solve = -t0;
  PetscCall(SNESGetIterationNumber(snes, &its));
  PetscCall(SNESGetConvergedReason(snes, &reason));
  PetscCall(SNESGetFunction(snes, &rC, NULL, NULL)); /* r = P u - f at the solution */

  /* summary in the shape of Table 2 */
  {
    Vec coordinates;
    PetscCall(DMGetCoordinates(dm, &coordinates));
    PetscCall(VecGetSize(coordinates, &nnodes));
    nnodes /= 3;
  }
  PetscCall(ISGetSize(cn.isC, &ncontact));
  ncontact /= 3;
  if (header) PetscCall(PetscPrintf(PETSC_COMM_WORLD, "level ranks  nodes assembly[s] schur[s] contact solve[s] iters  L/M1/M2/M3+/M3-/M4  separated/sliding/sticking reason\n"));
  {
    const SSStarState *states;
    PetscBool          isssstar;

    PetscCall(PetscObjectTypeCompare((PetscObject)snes, SNESSSSTAR, &isssstar));
    if (isssstar) PetscCall(SNESSSStarGetStates(snes, &states, counts));
    else PetscCall(PetscArrayzero(counts, SSSTAR_NUM_STATES));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%5" PetscInt_FMT " %5d %6" PetscInt_FMT " %11.3f %8.3f %7" PetscInt_FMT " %8.3f %5" PetscInt_FMT "  %" PetscInt_FMT "/%" PetscInt_FMT "/%" PetscInt_FMT "/%" PetscInt_FMT "/%" PetscInt_FMT "/%" PetscInt_FMT "  %" PetscInt_FMT "/%" PetscInt_FMT "/%" PetscInt_FMT " %s\n",
                          hasMesh ? -1 : level, size, nnodes, (double)t_assembly, (double)t_schur, ncontact, (double)t_solve, its, counts[0], counts[1], counts[2], counts[3], counts[4], counts[5], counts[0], counts[1] + counts[2], counts[3] + counts[4] + counts[5],
                          SNESConvergedReasons[reason]));

    if (hasOut) {
      PetscInt *st;

      PetscCall(DMCreateGlobalVector(dm, &u));
      PetscCall(SSStarReductionRecover(red, uC, u));
      PetscCall(PetscMalloc1(cn.n, &st));
      for (PetscInt i = 0; i < cn.n; i++) st[i] = isssstar ? (PetscInt)states[i] : -1;
      PetscCall(SSStarWriteSolution(out, dm, u, &cn, uC, rC, st));
      PetscCall(PetscFree(st));
      PetscCall(VecDestroy(&u));
    }
  }

  PetscCall(SNESDestroy(&snes));
  PetscCall(VecDestroy(&uC));
  PetscCall(SSStarReductionDestroy(&red));
  PetscCall(SSStarContactNodesDestroy(&cn));
  PetscCall(MatDestroy(&K));
  PetscCall(VecDestroy(&F));
  PetscCall(VecDestroy(&tags));
  PetscCall(DMDestroy(&dm));
  PetscCall(PetscFinalize());
  return 0;
}
