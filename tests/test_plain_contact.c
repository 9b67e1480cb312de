static const char help[] = "A plain PETSc program that assembles its own contact problem (P sparse AIJ, f) and knows nothing of ssstar.\n\
Run with -dll_append <dir>/libssstar.so -snes_type ssstar: it checks the Coulomb law at the solution itself.\n\
  -p <40>                         contact nodes\n\
  -snes_ssstar_friction <0.3>     friction coefficient (read here too, for the check)\n\
  -dense                          hand P to the solver as a dense matrix\n\
  -singular                       node 0 gets no stiffness and is pulled off the plane: the Newton matrix is singular\n\
  -poison <load|stiffness|guess>  a NaN in f, an Inf in P or a NaN in the initial guess at node 3 (the solver must refuse it)\n\
  -kappa <0>                      a nonlinear residual P u + kappa u^3 - f (Jacobian P + 3 kappa diag(u^2)), not declared affine\n";

/* Requirement: the SNES type "ssstar" is usable, through -dll_append only, from a program that does not link
   libssstar, on 1 and 2 ranks and with a sparse (AIJ) P; its solution satisfies the Coulomb law at every node
   (u_n >= 0, r_n >= 0, u_n r_n = 0, |r_t| <= phi r_n, r_t = -phi r_n u_t/|u_t| when sliding) to 1e-8 relative. */
#include <petscsnes.h>

typedef struct {
  Mat       P, J; /* J: the Jacobian's matrix (P itself when kappa = 0) */
  Vec       f;
  PetscReal kappa;
} Problem;

static PetscErrorCode FormFunction(SNES snes, Vec u, Vec c, void *ctx)
{
  Problem *pb = (Problem *)ctx;

  PetscFunctionBeginUser;
  PetscCall(MatMult(pb->P, u, c));
  PetscCall(VecAXPY(c, -1.0, pb->f));
  if (pb->kappa != 0) {
    Vec u3;

    PetscCall(VecDuplicate(u, &u3));
    PetscCall(VecPointwiseMult(u3, u, u));
    PetscCall(VecPointwiseMult(u3, u3, u));
    PetscCall(VecAXPY(c, pb->kappa, u3));
    PetscCall(VecDestroy(&u3));
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode FormJacobian(SNES snes, Vec u, Mat J, Mat Jp, void *ctx)
{
  Problem *pb = (Problem *)ctx;
  Vec      d;

  PetscFunctionBeginUser;
  if (pb->kappa == 0) PetscFunctionReturn(0); /* J = P, constant */
  PetscCall(MatCopy(pb->P, J, SAME_NONZERO_PATTERN));
  PetscCall(VecDuplicate(u, &d));
  PetscCall(VecPointwiseMult(d, u, u));
  PetscCall(VecScale(d, 3 * pb->kappa));
  PetscCall(MatDiagonalSet(J, d, ADD_VALUES));
  PetscCall(VecDestroy(&d));
  PetscFunctionReturn(0);
}

/* A chain of p nodes: springs between neighbours in every direction, a stiffer one to the ground. */
static PetscErrorCode CreateProblem(MPI_Comm comm, PetscInt p, PetscBool singular, Problem *pb)
{
  PetscMPIInt size, rank;
  PetscInt    nloc, start, end;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  nloc = 3 * (p / size + (rank < p % size));
  PetscCall(MatCreateAIJ(comm, nloc, nloc, 3 * p, 3 * p, 9, NULL, 6, NULL, &pb->P));
  PetscCall(MatGetOwnershipRange(pb->P, &start, &end));
  for (PetscInt row = start; row < end; row++) {
    const PetscInt i = row / 3, k = row % 3;

    if (singular && i < 2) continue; /* node 0 free of stiffness (node 1 loses its coupling to it) */
    PetscCall(MatSetValue(pb->P, row, row, 2.0 + (k == 2 ? 3.0 : 1.0), INSERT_VALUES));
    if (i > 0) PetscCall(MatSetValue(pb->P, row, row - 3, -1.0, INSERT_VALUES));
    if (i < p - 1) PetscCall(MatSetValue(pb->P, row, row + 3, -1.0, INSERT_VALUES));
    if (k < 2) PetscCall(MatSetValue(pb->P, row, 3 * i + 1 - k, 0.25, INSERT_VALUES)); /* couples the two tangential directions */
  }
  if (singular && start < 6) {
    for (PetscInt row = 3; row < PetscMin(6, end); row++) {
      PetscCall(MatSetValue(pb->P, row, row, 5.0, INSERT_VALUES));
      PetscCall(MatSetValue(pb->P, row, row + 3, -1.0, INSERT_VALUES));
    }
  }
  PetscCall(MatAssemblyBegin(pb->P, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(pb->P, MAT_FINAL_ASSEMBLY));
  PetscCall(MatCreateVecs(pb->P, &pb->f, NULL));
  for (PetscInt row = start; row < end; row++) {
    const PetscInt  i = row / 3, k = row % 3;
    const PetscReal val[3] = {PetscSinReal(0.7 * i), 0.5 * PetscCosReal(1.3 * i), i % 5 == 0 ? 1.0 : -2.0};

    PetscCall(VecSetValue(pb->f, row, val[k], INSERT_VALUES));
  }
  PetscCall(VecAssemblyBegin(pb->f));
  PetscCall(VecAssemblyEnd(pb->f));
  PetscFunctionReturn(0);
}

/* Worst violation of the Coulomb law over the nodes, relative to max|u| and max|f|. */
static PetscErrorCode CoulombViolation(Problem *pb, Vec u, PetscReal phi, PetscReal *violation, PetscInt count[3])
{
  Vec                r;
  const PetscScalar *ua, *ra;
  PetscInt           n;
  PetscReal          umax, fmax, worst = 0;

  PetscFunctionBeginUser;
  PetscCall(VecDuplicate(u, &r));
  PetscCall(FormFunction(NULL, u, r, pb));
  PetscCall(VecNorm(u, NORM_INFINITY, &umax));
  PetscCall(VecNorm(pb->f, NORM_INFINITY, &fmax));
  PetscCall(VecGetLocalSize(u, &n));
  PetscCall(VecGetArrayRead(u, &ua));
  PetscCall(VecGetArrayRead(r, &ra));
  count[0] = count[1] = count[2] = 0;
  for (PetscInt i = 0; i < n / 3; i++) {
    const PetscReal *x = &ua[3 * i], *f = &ra[3 * i];
    const PetscReal  ut = PetscSqrtReal(x[0] * x[0] + x[1] * x[1]), rt = PetscSqrtReal(f[0] * f[0] + f[1] * f[1]);
    PetscReal        v  = PetscMax(-x[2] / umax, -f[2] / fmax);

    v = PetscMax(v, PetscAbsReal(x[2] * f[2]) / (umax * fmax));
    v = PetscMax(v, (rt - phi * f[2]) / fmax);
    if (ut > 1e-8 * umax) {
      v = PetscMax(v, PetscAbsReal(f[0] + phi * f[2] * x[0] / ut) / fmax);
      v = PetscMax(v, PetscAbsReal(f[1] + phi * f[2] * x[1] / ut) / fmax);
    }
    worst = PetscMax(worst, v);
    count[x[2] > 1e-8 * umax ? 0 : (ut > 1e-8 * umax ? 1 : 2)]++;
  }
  PetscCall(VecRestoreArrayRead(r, &ra));
  PetscCall(VecRestoreArrayRead(u, &ua));
  PetscCall(VecDestroy(&r));
  PetscCall(MPIU_Allreduce(&worst, violation, 1, MPIU_REAL, MPIU_MAX, PetscObjectComm((PetscObject)u)));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, count, 3, MPIU_INT, MPI_SUM, PetscObjectComm((PetscObject)u)));
  PetscFunctionReturn(0);
}

/* Puts a NaN or Inf at node 3 into what -poison names */
static PetscErrorCode Poison(Problem *pb, Vec u)
{
  char      what[16] = "";
  PetscBool set, load, stiffness, guess;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsGetString(NULL, NULL, "-poison", what, sizeof(what), &set));
  if (!set) PetscFunctionReturn(0);
  PetscCall(PetscStrcmp(what, "load", &load));
  PetscCall(PetscStrcmp(what, "stiffness", &stiffness));
  PetscCall(PetscStrcmp(what, "guess", &guess));
  PetscCheck(load || stiffness || guess, PETSC_COMM_WORLD, PETSC_ERR_ARG_WRONG, "-poison %s: not load, stiffness or guess", what);
  if (load) {
    PetscCall(VecSetValue(pb->f, 11, NAN, INSERT_VALUES));
    PetscCall(VecAssemblyBegin(pb->f));
    PetscCall(VecAssemblyEnd(pb->f));
  }
  if (stiffness) {
    PetscCall(MatSetValue(pb->P, 11, 11, INFINITY, INSERT_VALUES));
    PetscCall(MatAssemblyBegin(pb->P, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(pb->P, MAT_FINAL_ASSEMBLY));
  }
  if (guess) {
    PetscCall(VecSetValue(u, 11, NAN, INSERT_VALUES));
    PetscCall(VecAssemblyBegin(u));
    PetscCall(VecAssemblyEnd(u));
  }
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  Problem             pb;
  SNES                snes;
  Vec                 u;
  PetscInt            p = 40, its, count[3];
  PetscBool           singular = PETSC_FALSE, dense = PETSC_FALSE;
  PetscReal           phi = 0.3, violation;
  SNESConvergedReason reason;

  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-p", &p, NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-snes_ssstar_friction", &phi, NULL));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-singular", &singular, NULL));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-dense", &dense, NULL));
  pb.kappa = 0;
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-kappa", &pb.kappa, NULL));
  PetscCall(CreateProblem(PETSC_COMM_WORLD, p, singular, &pb));
  if (dense) PetscCall(MatConvert(pb.P, MATDENSE, MAT_INPLACE_MATRIX, &pb.P));
  if (pb.kappa != 0) PetscCall(MatDuplicate(pb.P, MAT_COPY_VALUES, &pb.J));
  else {
    PetscCall(PetscObjectReference((PetscObject)pb.P));
    pb.J = pb.P;
  }
  PetscCall(SNESCreate(PETSC_COMM_WORLD, &snes));
  PetscCall(SNESSetFunction(snes, NULL, FormFunction, &pb));
  PetscCall(SNESSetJacobian(snes, pb.J, pb.J, FormJacobian, &pb));
  PetscCall(SNESSetFromOptions(snes));
  PetscCall(MatCreateVecs(pb.P, &u, NULL));
  PetscCall(VecZeroEntries(u));
  PetscCall(Poison(&pb, u));
  PetscCall(SNESSolve(snes, NULL, u));
  PetscCall(SNESGetConvergedReason(snes, &reason));
  PetscCall(SNESGetIterationNumber(snes, &its));
  PetscCall(CoulombViolation(&pb, u, phi, &violation, count));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%s after %" PetscInt_FMT " iterations; separated/sliding/sticking %" PetscInt_FMT "/%" PetscInt_FMT "/%" PetscInt_FMT "; Coulomb law violation %.1e\n", SNESConvergedReasons[reason], its, count[0], count[1], count[2], (double)violation));
  PetscCall(SNESDestroy(&snes));
  PetscCall(VecDestroy(&u));
  PetscCall(VecDestroy(&pb.f));
  PetscCall(MatDestroy(&pb.P));
  PetscCall(MatDestroy(&pb.J));
  PetscCall(PetscFinalize());
  return (reason > 0 && violation <= 1e-8) ? 0 : 1;
}
