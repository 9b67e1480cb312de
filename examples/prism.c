static const char help[] = "The seed's test problem: an elastic prism pressed onto a rigid plane with Coulomb friction,\n\
solved by the semismooth* Newton method (SNES type ssstar) on the contact dofs.\n\
  -level <6>                 mesh level L of meshes/prism.geo: (4L+1)x(2L+1)x(2L+1) nodes\n\
  -mesh <file.msh>           any gmsh mesh with physical groups dirichlet, top, right, contact (instead of -level)\n\
  -geo <file.geo>            the geometry meshed for -level (default: meshes/prism.geo of the source tree)\n\
  -mesh_scale <1>            multiply the mesh coordinates by this (a change of length unit, e.g. 1e-3 for mm -> m)\n\
  -E <2.1e5> -nu <0.3>       Young's modulus and Poisson ratio\n\
  -friction <0.3>            Coulomb friction coefficient (same as -snes_ssstar_friction)\n\
  -traction_top <0,0,-500>   traction on the group top\n\
  -traction_right <-200,30,200> traction on the group right\n\
  -reduction <direct>        Schur complement: direct (MUMPS + METIS, every rank), mumps (PETSc's MUMPS Schur, on\n\
                             rank 0) or explicit (MATSCHURCOMPLEMENT)\n\
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

/* The elastic body: F(u) = K u - b, Jacobian K */
typedef struct {
  Mat K;
  Vec b;
} Body;

static PetscErrorCode FormFunction(SNES snes, Vec u, Vec r, void *ctx)
{
  Body *body = (Body *)ctx;

  PetscFunctionBeginUser;
  PetscCall(MatMult(body->K, u, r));
  PetscCall(VecAXPY(r, -1.0, body->b));
  PetscFunctionReturn(0);
}

static PetscErrorCode FormJacobian(SNES snes, Vec u, Mat J, Mat Jpre, void *ctx)
{
  PetscFunctionBeginUser;
  PetscFunctionReturn(0); /* K, assembled once */
}

/* Time spent in a log event, max over the ranks */
static PetscErrorCode EventTime(PetscLogEvent event, PetscReal *t)
{
  PetscEventPerfInfo info;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventGetPerfInfo(PETSC_DETERMINE, event, &info));
  PetscCall(MPIU_Allreduce(&info.time, t, 1, MPIU_REAL, MPIU_MAX, PETSC_COMM_WORLD));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  SSStarScene         scene = {2.1e5, 0.3, {0, 0, -500}, {-200, 30, 200}};
  PetscInt            level = 6, nnodes, counts[SSSTAR_NUM_STATES], its, ncontact;
  PetscReal           friction = 0.3, meshScale = 1, t_assembly, t_schur, t_solve, t_recovery, t0;
  char                mesh[PETSC_MAX_PATH_LEN] = "", geo[PETSC_MAX_PATH_LEN] = SSSTAR_MESH_DIR "/prism.geo", out[PETSC_MAX_PATH_LEN] = "";
  PetscBool           hasMesh, hasOut, header = PETSC_TRUE, isssstar;
  SSStarReductionType rtype = SSSTAR_REDUCTION_DIRECT;
  DM                  dm;
  Vec                 tags, u, r;
  Body                body;
  SSStarContactNodes  cn;
  SNES                snes;
  SNESConvergedReason reason;
  PetscMPIInt         size;
  const SSStarState  *states = NULL;

  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(SSStarInitializePackage());
  PetscCall(PetscLogDefaultBegin()); /* the phases of the summary row are read from the log events */
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "Prism contact problem", "ssstar");
  PetscCall(PetscOptionsInt("-level", "Mesh level of meshes/prism.geo", NULL, level, &level, NULL));
  PetscCall(PetscOptionsString("-mesh", "gmsh mesh file (instead of -level)", NULL, mesh, mesh, sizeof(mesh), &hasMesh));
  PetscCall(PetscOptionsString("-geo", "Geometry meshed for -level", NULL, geo, geo, sizeof(geo), NULL));
  PetscCall(PetscOptionsReal("-mesh_scale", "Multiply the mesh coordinates by this", NULL, meshScale, &meshScale, NULL));
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
  PetscCall(SSStarMeshScale(dm, meshScale));
  PetscCall(SSStarAssembleElasticity(dm, &scene, &body.K, &body.b));
  PetscCall(SSStarContactNodesCreate(dm, tags, &cn));
  PetscCall(PetscTimeSubtract(&t0));
  t_assembly = -t0;

  /* the whole body with its contact nodes: SNESSolve reduces K to them, solves, recovers u */
  PetscCall(SNESCreate(PETSC_COMM_WORLD, &snes));
  PetscCall(SNESSetType(snes, SNESSSSTAR));
  PetscCall(SNESSSStarSetFriction(snes, friction));
  PetscCall(SNESSSStarSetReductionType(snes, rtype));
  PetscCall(SNESSetFunction(snes, NULL, FormFunction, &body));
  PetscCall(SNESSetJacobian(snes, body.K, body.K, FormJacobian, &body));
  PetscCall(SNESSSStarSetContactNodes(snes, cn.isC, NULL, NULL));
  PetscCall(SNESSetFromOptions(snes));
  PetscCall(DMCreateGlobalVector(dm, &u));
  PetscCall(PetscObjectSetName((PetscObject)u, "displacement"));
  PetscCall(VecZeroEntries(u));
  PetscCall(PetscTime(&t0));
  PetscCall(SNESSolve(snes, NULL, u));
  PetscCall(PetscTimeSubtract(&t0));
  PetscCall(EventTime(SSSTAR_Schur, &t_schur));
  PetscCall(EventTime(SSSTAR_Recovery, &t_recovery));
  t_solve = -t0 - t_schur - t_recovery;
  PetscCall(SNESGetIterationNumber(snes, &its));
  PetscCall(SNESGetConvergedReason(snes, &reason));
  PetscCall(SNESGetFunction(snes, &r, NULL, NULL)); /* K u - b: the contact forces at the contact dofs */

  /* summary in the shape of Table 2 */
  {
    Vec coordinates;
    PetscCall(DMGetCoordinates(dm, &coordinates));
    PetscCall(VecGetSize(coordinates, &nnodes));
    nnodes /= 3;
  }
  PetscCall(ISGetSize(cn.isC, &ncontact));
  ncontact /= 3;
  PetscCall(PetscObjectTypeCompare((PetscObject)snes, SNESSSSTAR, &isssstar));
  if (isssstar) PetscCall(SNESSSStarGetStates(snes, &states, counts));
  else PetscCall(PetscArrayzero(counts, SSSTAR_NUM_STATES));
  if (header) PetscCall(PetscPrintf(PETSC_COMM_WORLD, "level ranks  nodes assembly[s] schur[s] contact solve[s] iters  L/M1/M2/M3+/M3-/M4  separated/sliding/sticking reason\n"));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%5" PetscInt_FMT " %5d %6" PetscInt_FMT " %11.3f %8.3f %7" PetscInt_FMT " %8.3f %5" PetscInt_FMT "  %" PetscInt_FMT "/%" PetscInt_FMT "/%" PetscInt_FMT "/%" PetscInt_FMT "/%" PetscInt_FMT "/%" PetscInt_FMT "  %" PetscInt_FMT "/%" PetscInt_FMT "/%" PetscInt_FMT " %s\n",
                        hasMesh ? -1 : level, size, nnodes, (double)t_assembly, (double)t_schur, ncontact, (double)t_solve, its, counts[0], counts[1], counts[2], counts[3], counts[4], counts[5], counts[0], counts[1] + counts[2], counts[3] + counts[4] + counts[5],
                        SNESConvergedReasons[reason]));

  if (hasOut) {
    Vec       uC, rC;
    PetscInt *st;

    PetscCall(VecGetSubVector(u, cn.isC, &uC));
    PetscCall(VecGetSubVector(r, cn.isC, &rC));
    PetscCall(PetscMalloc1(cn.n, &st));
    for (PetscInt i = 0; i < cn.n; i++) st[i] = states ? (PetscInt)states[i] : -1;
    PetscCall(SSStarWriteSolution(out, dm, u, &cn, uC, rC, st));
    PetscCall(PetscFree(st));
    PetscCall(VecRestoreSubVector(r, cn.isC, &rC));
    PetscCall(VecRestoreSubVector(u, cn.isC, &uC));
  }

  PetscCall(SNESDestroy(&snes));
  PetscCall(VecDestroy(&u));
  PetscCall(SSStarContactNodesDestroy(&cn));
  PetscCall(MatDestroy(&body.K));
  PetscCall(VecDestroy(&body.b));
  PetscCall(VecDestroy(&tags));
  PetscCall(DMDestroy(&dm));
  PetscCall(PetscFinalize());
  return 0;
}
