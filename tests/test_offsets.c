static const char help[] = "A load path through SNESSSStarSetContactOffsets() (docs/derivation.md (10.4)-(10.5)): the whole body of check 1\n\
of tests/loadpath_check.py -- a random SPD K, 8 nodes against obstacles (tilted frames, gaps, three of them facing an\n\
obstacle that moves) and 3 points of a contact pair (master weights), Coulomb, Tresca and frictionless nodes, pressed,\n\
sheared, released, sheared back and released -- solved step by step from the previous step's solution, each step's\n\
offsets computed here from that solution. Prints the largest difference from numpy's answer and the reductions made.\n\
  -f <file>   the problem and numpy's answers (tests/loadpath_check.py --write file)\n";

#include <ssstar.h>
#include <ssstarreduction.h>

/* The contact nodes of this rank: the nodes 0..p-1 it owns; node blocks split as evenly as the ranks allow */
static void NodeRange(PetscInt nodes, PetscMPIInt rank, PetscMPIInt size, PetscInt *lo, PetscInt *hi)
{
  const PetscInt per = nodes / size, extra = nodes % size;

  *lo = rank * per + PetscMin(rank, extra);
  *hi = *lo + per + (rank < extra ? 1 : 0);
}

static PetscErrorCode LoadVec(PetscViewer viewer, PetscInt nlocal, Vec *v)
{
  PetscFunctionBeginUser;
  PetscCall(VecCreate(PETSC_COMM_WORLD, v));
  PetscCall(VecSetSizes(*v, nlocal, PETSC_DETERMINE));
  PetscCall(VecSetFromOptions(*v));
  PetscCall(VecLoad(*v, viewer));
  PetscFunctionReturn(0);
}

static PetscErrorCode LoadMat(PetscViewer viewer, PetscInt mlocal, PetscInt nlocal, Mat *A)
{
  PetscFunctionBeginUser;
  PetscCall(MatCreate(PETSC_COMM_WORLD, A));
  PetscCall(MatSetSizes(*A, mlocal, nlocal, PETSC_DETERMINE, PETSC_DETERMINE));
  PetscCall(MatSetType(*A, MATAIJ));
  PetscCall(MatLoad(*A, viewer));
  PetscFunctionReturn(0);
}

/* w = B u + g e3 - R d: the points' relative displacements after a step (R d: the obstacle's motion in the frames) */
static PetscErrorCode RelativeDisplacement(Mat B, Vec u, Vec gaps, Vec Rd, Vec w)
{
  const PetscScalar *ga;
  PetscScalar       *wa;
  PetscInt           np;

  PetscFunctionBeginUser;
  PetscCall(MatMult(B, u, w));
  PetscCall(VecAXPY(w, -1.0, Rd));
  PetscCall(VecGetLocalSize(gaps, &np));
  PetscCall(VecGetArrayRead(gaps, &ga));
  PetscCall(VecGetArray(w, &wa));
  for (PetscInt i = 0; i < np; i++) wa[3 * i + 2] += ga[i];
  PetscCall(VecRestoreArray(w, &wa));
  PetscCall(VecRestoreArrayRead(gaps, &ga));
  PetscFunctionReturn(0);
}

/* (10.4): o = g e3 - R d^k - (w_t^(k-1), 0) */
static PetscErrorCode StepOffsets(Vec gaps, Vec Rd, Vec wprev, Vec o)
{
  const PetscScalar *ga, *wa;
  PetscScalar       *oa;
  PetscInt           np;

  PetscFunctionBeginUser;
  PetscCall(VecCopy(Rd, o));
  PetscCall(VecScale(o, -1.0));
  PetscCall(VecGetLocalSize(gaps, &np));
  PetscCall(VecGetArrayRead(gaps, &ga));
  PetscCall(VecGetArrayRead(wprev, &wa));
  PetscCall(VecGetArray(o, &oa));
  for (PetscInt i = 0; i < np; i++) {
    oa[3 * i] -= wa[3 * i];
    oa[3 * i + 1] -= wa[3 * i + 1];
    oa[3 * i + 2] += ga[i];
  }
  PetscCall(VecRestoreArray(o, &oa));
  PetscCall(VecRestoreArrayRead(wprev, &wa));
  PetscCall(VecRestoreArrayRead(gaps, &ga));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  char                file[PETSC_MAX_PATH_LEN] = "";
  PetscViewer         viewer;
  PetscInt            header[3], n, p, nsteps, lo, hi, np, *laws, *dofs, lawIndex[3];
  PetscMPIInt         rank, size;
  Mat                 K, B;
  Vec                 gaps, codes, friction, bound, b, Rd, ref, u, w, o;
  IS                  is;
  SNES                snes;
  PetscReal           worst = 0;
  const char         *lawNames[3] = {"none", "tresca", "coulomb"};
  PetscEventPerfInfo  info;
  SNESConvergedReason reason;
  const PetscScalar  *ca;

  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(SSStarInitializePackage());
  PetscCall(PetscLogDefaultBegin()); /* the reductions made are counted by their log event */
  PetscCall(PetscOptionsGetString(NULL, NULL, "-f", file, sizeof(file), NULL));
  PetscCheck(file[0], PETSC_COMM_WORLD, PETSC_ERR_ARG_WRONG, "give -f file (tests/loadpath_check.py --write file)");
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  PetscCall(PetscViewerBinaryOpen(PETSC_COMM_WORLD, file, FILE_MODE_READ, &viewer));
  PetscCall(PetscViewerBinaryRead(viewer, header, 3, NULL, PETSC_INT));
  n      = header[0];
  p      = header[1];
  nsteps = header[2];
  NodeRange(n / 3, rank, size, &lo, &hi);
  np = PetscMax(0, PetscMin(hi, p) - lo); /* the points are the nodes 0..p-1 */
  PetscCall(LoadMat(viewer, 3 * (hi - lo), 3 * (hi - lo), &K));
  PetscCall(MatSetOption(K, MAT_SPD, PETSC_TRUE));
  PetscCall(LoadMat(viewer, 3 * np, 3 * (hi - lo), &B));
  PetscCall(LoadVec(viewer, np, &gaps));
  PetscCall(LoadVec(viewer, np, &codes));
  PetscCall(LoadVec(viewer, np, &friction));
  PetscCall(LoadVec(viewer, np, &bound));

  PetscCall(MatCreateVecs(K, &u, &b));
  PetscCall(SNESCreate(PETSC_COMM_WORLD, &snes));
  PetscCall(SNESSetType(snes, SNESSSSTAR));
  PetscCall(SNESSSStarSetLinearProblem(snes, K, b));
  PetscCall(PetscMalloc2(3 * np + 1, &dofs, np + 1, &laws));
  for (PetscInt k = 0; k < 3 * np; k++) dofs[k] = 3 * lo + k;
  PetscCall(ISCreateGeneral(PETSC_COMM_WORLD, 3 * np, dofs, PETSC_COPY_VALUES, &is));
  PetscCall(SNESSSStarSetContactOperator(snes, is, B, gaps));
  for (PetscInt l = 0; l < 3; l++) PetscCall(SSStarLawGetIndex(lawNames[l], &lawIndex[l]));
  PetscCall(VecGetArrayRead(codes, &ca));
  for (PetscInt i = 0; i < np; i++) laws[i] = lawIndex[(PetscInt)PetscRealPart(ca[i])];
  PetscCall(VecRestoreArrayRead(codes, &ca));
  PetscCall(SNESSSStarSetNodeFrictionLaws(snes, np, laws));
  PetscCall(SNESSSStarSetNodeLawParameter(snes, "friction", friction));
  PetscCall(SNESSSStarSetNodeLawParameter(snes, "slip_bound", bound));
  PetscCall(SNESSetFromOptions(snes));

  PetscCall(MatCreateVecs(B, NULL, &w));
  PetscCall(VecDuplicate(w, &o));
  PetscCall(VecZeroEntries(w)); /* w^0 = 0: the reference configuration */
  PetscCall(VecZeroEntries(u));
  PetscCall(SNESSSStarSetContactOffsets(snes, o));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%" PetscInt_FMT " dofs, %" PetscInt_FMT " contact points, %" PetscInt_FMT " steps; iterations", n, p, nsteps));
  for (PetscInt k = 0; k < nsteps; k++) {
    PetscReal diff, scale;
    PetscInt  its;

    PetscCall(LoadVec(viewer, 3 * (hi - lo), &ref)); /* b^k into b: the SNES's load */
    PetscCall(VecCopy(ref, b));
    PetscCall(VecDestroy(&ref));
    PetscCall(LoadVec(viewer, 3 * np, &Rd));
    PetscCall(LoadVec(viewer, 3 * (hi - lo), &ref));
    PetscCall(StepOffsets(gaps, Rd, w, o)); /* the values of o change; the SNES reads them at the solve */
    PetscCall(SNESSolve(snes, NULL, u)); /* from u^(k-1) */
    PetscCall(SNESGetConvergedReason(snes, &reason));
    PetscCall(SNESGetIterationNumber(snes, &its));
    PetscCheck(reason > 0, PETSC_COMM_WORLD, PETSC_ERR_NOT_CONVERGED, "step %" PetscInt_FMT ": %s", k, SNESConvergedReasons[reason]);
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, " %" PetscInt_FMT, its));
    PetscCall(RelativeDisplacement(B, u, gaps, Rd, w));
    PetscCall(VecNorm(ref, NORM_INFINITY, &scale));
    PetscCall(VecAXPY(ref, -1.0, u));
    PetscCall(VecNorm(ref, NORM_INFINITY, &diff));
    worst = PetscMax(worst, diff / PetscMax(scale, PETSC_SMALL));
    PetscCall(VecDestroy(&ref));
    PetscCall(VecDestroy(&Rd));
  }
  /* the event SSStarSchur counts the set-ups of the reduction and the reduction of each solve's load */
  PetscCall(PetscLogEventGetPerfInfo(PETSC_DETERMINE, SSSTAR_Schur, &info));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "\nmax |u - u_numpy|/|u_numpy| = %.3e, set-ups of the reduction: %" PetscInt_FMT "\n", (double)worst, (PetscInt)info.count - nsteps));

  PetscCall(PetscFree2(dofs, laws));
  PetscCall(ISDestroy(&is));
  PetscCall(SNESDestroy(&snes));
  PetscCall(PetscViewerDestroy(&viewer));
  PetscCall(MatDestroy(&K));
  PetscCall(MatDestroy(&B));
  PetscCall(VecDestroy(&gaps));
  PetscCall(VecDestroy(&codes));
  PetscCall(VecDestroy(&friction));
  PetscCall(VecDestroy(&bound));
  PetscCall(VecDestroy(&b));
  PetscCall(VecDestroy(&u));
  PetscCall(VecDestroy(&w));
  PetscCall(VecDestroy(&o));
  PetscCall(PetscFinalize());
  return 0;
}
