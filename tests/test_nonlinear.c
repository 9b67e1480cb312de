static const char help[] = "A plain PETSc program with a nonlinear residual F(u) and contact, that knows nothing of ssstar's library:\n\
run it with -dll_append <dir>/libssstar.so -snes_type ssstar (the contact is declared through the functions the type\n\
composes on the SNES). It checks its answer itself: F in equilibrium at the free dofs and the contact law at the\n\
contact nodes, as written.\n\
  -problem <block>           block: a neo-Hookean block of its own assembly (a structured tetrahedral grid, DMDA),\n\
                             its top face moved down and along x, pressed onto a rigid obstacle with Coulomb friction\n\
                             cubic: the prism's K and b (examples/prism -save_whole FILE) with F(u) = K u + kappa u^3 - b\n\
  -n <4>                     block: cells along x and y (n/2 along z); the block is 1 x 1 x 0.5\n\
  -press <0.2> -shift <0.05> block: the top face moved down and along x by these fractions of the height\n\
  -E <1> -nu <0.3>           block: W = mu/2 (I1 - 3) - mu ln J + lambda/2 (ln J)^2\n\
  -obstacle <plane>          block: plane (z = 0, touching the bottom face) or ball (radius -radius below its centre,\n\
                             touching it at one point): the contact measured at every iterate (SNESSSStarSetContactUpdate)\n\
  -radius <2>                block: the ball's radius\n\
  -geometric_stiffness       block, ball: the Jacobian adds the term of the turning normal, -r_n (I - n n^T)/d\n\
  -load <file.bin>           cubic: the file of examples/prism -save_whole\n\
  -stiffening <0.5>          cubic: kappa = s max|b| / max|K^-1 b|^3\n\
  -affine                    declare F affine (SNESSSStarSetAffine): wrong here, and the solver must say so\n\
  -snes_ssstar_friction <0.3> the friction coefficient (read here too, for the check)\n\
Exit status: 0 converged and its checks hold, 1 converged but a check fails, 2 not converged.\n";

/* Requirement: -snes_type ssstar solves a user's nonlinear residual with contact in a program that links nothing of
   ssstar (PETSc only; the type through -dll_append): a hyperelastic block of its own assembly and the prism's K with
   a cubic stiffening; its converged answers satisfy F = 0 at the free dofs and the contact law at the contact nodes as
   written, with the geometry of a curved obstacle measured at the solution (docs/derivation.md section 17). */
#include <petscsnes.h>
#include <petscdmda.h>

#define CHECK_TOL 1e-7 /* ten times the solver's law tolerance, as tests/check_solution.py */

typedef enum {
  PROBLEM_BLOCK,
  PROBLEM_CUBIC
} ProblemType;
static const char *const ProblemTypes[] = {"block", "cubic", "ProblemType", "PROBLEM_", NULL};

typedef struct {
  ProblemType type;
  PetscReal   phi;
  /* the contact nodes of this rank: their dofs (3 each, global), normals and gaps at the last measure */
  PetscInt    ncontact;
  IS          dofs;
  Vec         normals, gaps;
  PetscReal  *X;          /* their reference coordinates (block) */
  PetscBool   ball, geometric;
  PetscReal   radius, centre[3];
  /* block */
  DM          da;
  PetscInt    n[3];       /* nodes along x, y, z */
  PetscReal   h, mu, lambda, press[3], dirichletScale;
  PetscInt    rstart;     /* the first row of this rank */
  Vec         local;
  /* cubic */
  Mat         K;
  Vec         b;
  PetscReal   kappa, bmax;
} Problem;

/* The functions the type ssstar composes on the SNES (a program that links libssstar calls SNESSSStar*() itself) */
static PetscErrorCode Composed(SNES snes, const char name[], void (**fn)(void))
{
  PetscFunctionBeginUser;
  PetscCall(PetscObjectQueryFunction_Private((PetscObject)snes, name, fn));
  PetscCheck(*fn, PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_WRONG, "%s is not composed on the SNES: run with -snes_type ssstar -dll_append <dir>/libssstar.so", name);
  PetscFunctionReturn(0);
}

static PetscErrorCode DeclareContact(SNES snes, Problem *pb)
{
  PetscErrorCode (*set)(SNES, IS, Vec, Vec);

  PetscFunctionBeginUser;
  PetscCall(Composed(snes, "SNESSSStarSetContactNodes_C", (void (**)(void))&set));
  PetscCall((*set)(snes, pb->dofs, pb->normals, pb->gaps));
  PetscFunctionReturn(0);
}

/* ---------------------------------------------------------------- the neo-Hookean block */

/* The 6 tetrahedra of a cube (Freudenthal: the paths from corner 0 to corner 7), corners numbered i + 2 j + 4 k */
static const PetscInt Tets[6][4] = {{0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7}, {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7}};

/* First Piola-Kirchhoff stress and the tangent A_iJkL = dP_iJ/dF_kL of W = mu/2 (I1 - 3) - mu ln J + lambda/2 ln^2 J */
static PetscBool NeoHooke(PetscReal mu, PetscReal lambda, const PetscReal F[9], PetscReal P[9], PetscReal A[81])
{
  PetscReal J, Fi[9], lnJ;

  J = F[0] * (F[4] * F[8] - F[5] * F[7]) - F[1] * (F[3] * F[8] - F[5] * F[6]) + F[2] * (F[3] * F[7] - F[4] * F[6]);
  if (!(J > 0)) return PETSC_FALSE;
  Fi[0] = (F[4] * F[8] - F[5] * F[7]) / J; /* Fi = F^-1, row-major */
  Fi[1] = (F[2] * F[7] - F[1] * F[8]) / J;
  Fi[2] = (F[1] * F[5] - F[2] * F[4]) / J;
  Fi[3] = (F[5] * F[6] - F[3] * F[8]) / J;
  Fi[4] = (F[0] * F[8] - F[2] * F[6]) / J;
  Fi[5] = (F[2] * F[3] - F[0] * F[5]) / J;
  Fi[6] = (F[3] * F[7] - F[4] * F[6]) / J;
  Fi[7] = (F[1] * F[6] - F[0] * F[7]) / J;
  Fi[8] = (F[0] * F[4] - F[1] * F[3]) / J;
  lnJ   = PetscLogReal(J);
  for (PetscInt i = 0; i < 3; i++)
    for (PetscInt q = 0; q < 3; q++) P[3 * i + q] = mu * F[3 * i + q] + (lambda * lnJ - mu) * Fi[3 * q + i];
  if (A)
    for (PetscInt i = 0; i < 3; i++)
      for (PetscInt q = 0; q < 3; q++)
        for (PetscInt k = 0; k < 3; k++)
          for (PetscInt L = 0; L < 3; L++) A[27 * i + 9 * q + 3 * k + L] = mu * (i == k) * (q == L) + lambda * Fi[3 * q + i] * Fi[3 * L + k] + (mu - lambda * lnJ) * Fi[3 * q + k] * Fi[3 * L + i];
  return PETSC_TRUE;
}

/* The gradients of the 4 barycentric functions of a tetrahedron (4 x 3) and its volume */
static void TetGradients(const PetscReal X[4][3], PetscReal G[4][3], PetscReal *vol)
{
  PetscReal D[9], det, Di[9];

  for (PetscInt r = 0; r < 3; r++)
    for (PetscInt c = 0; c < 3; c++) D[3 * r + c] = X[c + 1][r] - X[0][r]; /* columns x_a - x_0 */
  det   = D[0] * (D[4] * D[8] - D[5] * D[7]) - D[1] * (D[3] * D[8] - D[5] * D[6]) + D[2] * (D[3] * D[7] - D[4] * D[6]);
  Di[0] = (D[4] * D[8] - D[5] * D[7]) / det;
  Di[1] = (D[2] * D[7] - D[1] * D[8]) / det;
  Di[2] = (D[1] * D[5] - D[2] * D[4]) / det;
  Di[3] = (D[5] * D[6] - D[3] * D[8]) / det;
  Di[4] = (D[0] * D[8] - D[2] * D[6]) / det;
  Di[5] = (D[2] * D[3] - D[0] * D[5]) / det;
  Di[6] = (D[3] * D[7] - D[4] * D[6]) / det;
  Di[7] = (D[1] * D[6] - D[0] * D[7]) / det;
  Di[8] = (D[0] * D[4] - D[1] * D[3]) / det;
  for (PetscInt c = 0; c < 3; c++) { /* grad xi_a = row a-1 of D^-1 */
    G[0][c] = 0;
    for (PetscInt a = 1; a < 4; a++) {
      G[a][c] = Di[3 * (a - 1) + c];
      G[0][c] -= G[a][c];
    }
  }
  *vol = PetscAbsReal(det) / 6;
}

/* Every owned cell (its lower corner owned) of the grid: the element residual (and matrix) of each of its tetrahedra,
   added into fl (a local vector) and J; false where an element is inverted */
static PetscErrorCode AssembleBlock(Problem *pb, Vec ul, Vec fl, Mat J, PetscBool *defined)
{
  PetscInt           xs, ys, zs, xm, ym, zm;
  const PetscScalar *ua;
  PetscScalar       *fa = NULL;
  PetscInt           gxs, gys, gzs, gxm, gym;

  PetscFunctionBeginUser;
  *defined = PETSC_TRUE;
  PetscCall(DMDAGetCorners(pb->da, &xs, &ys, &zs, &xm, &ym, &zm));
  PetscCall(DMDAGetGhostCorners(pb->da, &gxs, &gys, &gzs, &gxm, &gym, NULL));
  PetscCall(VecGetArrayRead(ul, &ua));
  if (fl) PetscCall(VecGetArray(fl, &fa));
  for (PetscInt k = zs; k < PetscMin(zs + zm, pb->n[2] - 1); k++)
    for (PetscInt j = ys; j < PetscMin(ys + ym, pb->n[1] - 1); j++)
      for (PetscInt i = xs; i < PetscMin(xs + xm, pb->n[0] - 1); i++)
        for (PetscInt t = 0; t < 6; t++) {
          PetscInt    loc[4];
          MatStencil  st[12];
          PetscReal   X[4][3], G[4][3], vol, F[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, P[9], A[81], fe[12], Ke[144];
          PetscScalar Kes[144];

          for (PetscInt a = 0; a < 4; a++) {
            const PetscInt c = Tets[t][a], ii = i + (c & 1), jj = j + ((c >> 1) & 1), kk = k + ((c >> 2) & 1);

            loc[a] = ((kk - gzs) * gym + (jj - gys)) * gxm + (ii - gxs);
            X[a][0] = ii * pb->h, X[a][1] = jj * pb->h, X[a][2] = kk * pb->h;
            for (PetscInt d = 0; d < 3; d++) st[3 * a + d] = (MatStencil){.k = kk, .j = jj, .i = ii, .c = d};
          }
          TetGradients(X, G, &vol);
          for (PetscInt a = 0; a < 4; a++)
            for (PetscInt r = 0; r < 3; r++)
              for (PetscInt c = 0; c < 3; c++) F[3 * r + c] += PetscRealPart(ua[3 * loc[a] + r]) * G[a][c];
          if (!NeoHooke(pb->mu, pb->lambda, F, P, J ? A : NULL)) {
            *defined = PETSC_FALSE;
            continue;
          }
          for (PetscInt a = 0; a < 4; a++)
            for (PetscInt r = 0; r < 3; r++) fe[3 * a + r] = vol * (P[3 * r] * G[a][0] + P[3 * r + 1] * G[a][1] + P[3 * r + 2] * G[a][2]);
          if (fa)
            for (PetscInt a = 0; a < 4; a++)
              for (PetscInt r = 0; r < 3; r++) fa[3 * loc[a] + r] += fe[3 * a + r];
          if (!J) continue;
          for (PetscInt a = 0; a < 4; a++)
            for (PetscInt r = 0; r < 3; r++)
              for (PetscInt b = 0; b < 4; b++)
                for (PetscInt s = 0; s < 3; s++) {
                  PetscReal v = 0;

                  for (PetscInt q = 0; q < 3; q++)
                    for (PetscInt L = 0; L < 3; L++) v += A[27 * r + 9 * q + 3 * s + L] * G[a][q] * G[b][L];
                  Ke[12 * (3 * a + r) + 3 * b + s] = vol * v;
                }
          for (PetscInt e = 0; e < 144; e++) Kes[e] = Ke[e];
          PetscCall(MatSetValuesStencil(J, 12, st, 12, st, Kes, ADD_VALUES));
        }
  if (fl) PetscCall(VecRestoreArray(fl, &fa));
  PetscCall(VecRestoreArrayRead(ul, &ua));
  PetscFunctionReturn(0);
}

/* The Dirichlet rows of this rank (the top face, k = nz - 1): their global indices */
static PetscErrorCode DirichletRows(Problem *pb, PetscInt *n, PetscInt **rows)
{
  PetscInt xs, ys, zs, xm, ym, zm, m = 0;

  PetscFunctionBeginUser;
  PetscCall(DMDAGetCorners(pb->da, &xs, &ys, &zs, &xm, &ym, &zm));
  PetscCall(PetscMalloc1(3 * xm * ym + 1, rows));
  if (zs + zm == pb->n[2])
    for (PetscInt j = 0; j < ym; j++)
      for (PetscInt i = 0; i < xm; i++)
        for (PetscInt d = 0; d < 3; d++) (*rows)[m++] = pb->rstart + 3 * (((zm - 1) * ym + j) * xm + i) + d;
  *n = m;
  PetscFunctionReturn(0);
}

static PetscErrorCode BlockFunction(SNES snes, Vec u, Vec f, void *ctx)
{
  Problem           *pb = (Problem *)ctx;
  PetscInt           nrows, *rows;
  PetscBool          defined;
  const PetscScalar *ua;
  PetscScalar       *fa;
  PetscInt           rstart;

  PetscFunctionBeginUser;
  PetscCall(DMGlobalToLocal(pb->da, u, INSERT_VALUES, pb->local));
  PetscCall(VecZeroEntries(f));
  {
    Vec fl;

    PetscCall(DMGetLocalVector(pb->da, &fl));
    PetscCall(VecZeroEntries(fl));
    PetscCall(AssembleBlock(pb, pb->local, fl, NULL, &defined));
    PetscCall(DMLocalToGlobal(pb->da, fl, ADD_VALUES, f));
    PetscCall(DMRestoreLocalVector(pb->da, &fl));
  }
  if (!defined) PetscCall(SNESSetFunctionDomainError(snes)); /* an inverted element: F is not defined here */
  PetscCall(DirichletRows(pb, &nrows, &rows));
  PetscCall(VecGetOwnershipRange(f, &rstart, NULL));
  PetscCall(VecGetArrayRead(u, &ua));
  PetscCall(VecGetArray(f, &fa));
  for (PetscInt r = 0; r < nrows; r++) fa[rows[r] - rstart] = pb->dirichletScale * (ua[rows[r] - rstart] - pb->press[rows[r] % 3]);
  PetscCall(VecRestoreArray(f, &fa));
  PetscCall(VecRestoreArrayRead(u, &ua));
  PetscCall(PetscFree(rows));
  PetscFunctionReturn(0);
}

static PetscErrorCode BlockFunction(SNES, Vec, Vec, void *);

/*
   -geometric_stiffness: the term the contact measured at the iterate leaves out (docs/derivation.md section 17), added
   by the program itself: the force r_n n(u) on a node against the ball turns with the normal, d n/d u = (I - n n^T)/d
   (d the distance from the centre), so the Jacobian of F(u) - r_n n(u) at a node in contact gets -r_n (I - n n^T)/d,
   with r_n = n.F(u) at the iterate
*/
static PetscErrorCode AddGeometricStiffness(SNES snes, Problem *pb, Vec u, Mat J)
{
  Vec                f;
  const PetscScalar *ua, *fa;
  const PetscInt    *idx;
  PetscInt           rstart;

  PetscFunctionBeginUser;
  PetscCall(VecDuplicate(u, &f));
  PetscCall(BlockFunction(snes, u, f, pb));
  PetscCall(VecGetOwnershipRange(u, &rstart, NULL));
  PetscCall(ISGetIndices(pb->dofs, &idx));
  PetscCall(VecGetArrayRead(u, &ua));
  PetscCall(VecGetArrayRead(f, &fa));
  for (PetscInt i = 0; i < pb->ncontact; i++) {
    PetscReal   d[3], len, n[3], rn = 0;
    PetscScalar block[9];

    for (PetscInt k = 0; k < 3; k++) d[k] = pb->X[3 * i + k] + PetscRealPart(ua[idx[3 * i + k] - rstart]) - pb->centre[k];
    len = PetscSqrtReal(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (PetscInt k = 0; k < 3; k++) {
      n[k] = d[k] / len;
      rn += n[k] * PetscRealPart(fa[idx[3 * i + k] - rstart]);
    }
    if (rn <= 0) continue; /* not pressed */
    for (PetscInt r = 0; r < 3; r++)
      for (PetscInt c = 0; c < 3; c++) block[3 * r + c] = -rn * ((r == c) - n[r] * n[c]) / len;
    PetscCall(MatSetValues(J, 3, &idx[3 * i], 3, &idx[3 * i], block, ADD_VALUES));
  }
  PetscCall(VecRestoreArrayRead(f, &fa));
  PetscCall(VecRestoreArrayRead(u, &ua));
  PetscCall(ISRestoreIndices(pb->dofs, &idx));
  PetscCall(VecDestroy(&f));
  PetscCall(MatAssemblyBegin(J, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(J, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

static PetscErrorCode BlockJacobian(SNES snes, Vec u, Mat J, Mat Jp, void *ctx)
{
  Problem  *pb = (Problem *)ctx;
  PetscInt  nrows, *rows;
  PetscBool defined;

  PetscFunctionBeginUser;
  PetscCall(DMGlobalToLocal(pb->da, u, INSERT_VALUES, pb->local));
  PetscCall(MatZeroEntries(J));
  PetscCall(AssembleBlock(pb, pb->local, NULL, J, &defined));
  PetscCall(MatAssemblyBegin(J, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(J, MAT_FINAL_ASSEMBLY));
  /* the iterates keep the top's prescribed values (the initial guess has them, every step keeps them): its rows and
     columns are the identity times the scale, J stays symmetric */
  PetscCall(DirichletRows(pb, &nrows, &rows));
  PetscCall(MatZeroRowsColumns(J, nrows, rows, pb->dirichletScale, NULL, NULL));
  PetscCall(PetscFree(rows));
  if (pb->geometric) PetscCall(AddGeometricStiffness(snes, pb, u, J));
  PetscFunctionReturn(0);
}

/* The contact measured at x = the iterate: a ball's normal at the closest point and the gap, linearized there */
static PetscErrorCode MeasureBall(Problem *pb, Vec x)
{
  const PetscScalar *xa;
  PetscScalar       *na, *ga;
  const PetscInt    *idx;
  PetscInt           rstart;

  PetscFunctionBeginUser;
  PetscCall(VecGetOwnershipRange(x, &rstart, NULL));
  PetscCall(ISGetIndices(pb->dofs, &idx));
  PetscCall(VecGetArrayRead(x, &xa));
  PetscCall(VecGetArray(pb->normals, &na));
  PetscCall(VecGetArray(pb->gaps, &ga));
  for (PetscInt i = 0; i < pb->ncontact; i++) {
    PetscReal u[3], d[3], len, nu = 0;

    for (PetscInt k = 0; k < 3; k++) {
      u[k] = PetscRealPart(xa[idx[3 * i + k] - rstart]);
      d[k] = pb->X[3 * i + k] + u[k] - pb->centre[k];
    }
    len = PetscSqrtReal(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (PetscInt k = 0; k < 3; k++) {
      na[3 * i + k] = d[k] / len;
      nu += d[k] / len * u[k];
    }
    ga[i] = len - pb->radius - nu; /* w_n = n.u + g: the exact gap at x, to first order around it */
  }
  PetscCall(VecRestoreArray(pb->gaps, &ga));
  PetscCall(VecRestoreArray(pb->normals, &na));
  PetscCall(VecRestoreArrayRead(x, &xa));
  PetscCall(ISRestoreIndices(pb->dofs, &idx));
  PetscFunctionReturn(0);
}

static PetscErrorCode ContactUpdate(SNES snes, Vec x, void *ctx)
{
  Problem *pb = (Problem *)ctx;

  PetscFunctionBeginUser;
  PetscCall(MeasureBall(pb, x));
  PetscCall(DeclareContact(snes, pb));
  PetscFunctionReturn(0);
}

static PetscErrorCode CreateBlock(MPI_Comm comm, Problem *pb, SNES snes, Mat *J, Vec *u)
{
  PetscInt   n = 4, xs, ys, zs, xm, ym, zm, m = 0, *dofs, rstart;
  PetscReal  E = 1, nu = 0.3, press = 0.2, shift = 0.05, H;
  char       obstacle[16] = "plane";
  PetscScalar *ua;
  Vec        coords;
  MatNullSpace nsp;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-n", &n, NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-E", &E, NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-nu", &nu, NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-press", &press, NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-shift", &shift, NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-radius", &pb->radius, NULL));
  PetscCall(PetscOptionsGetString(NULL, NULL, "-obstacle", obstacle, sizeof(obstacle), NULL));
  PetscCall(PetscStrcmp(obstacle, "ball", &pb->ball));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-geometric_stiffness", &pb->geometric, NULL));
  PetscCheck(n >= 2 && n % 2 == 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-n %" PetscInt_FMT ": an even number >= 2", n);
  pb->n[0] = pb->n[1] = n + 1;
  pb->n[2]            = n / 2 + 1;
  pb->h               = 1.0 / n;
  H                   = 0.5;
  pb->mu              = E / (2 * (1 + nu));
  pb->lambda          = E * nu / ((1 + nu) * (1 - 2 * nu));
  pb->dirichletScale  = pb->mu * pb->h;
  pb->press[0]        = shift * H;
  pb->press[1]        = 0;
  pb->press[2]        = -press * H;
  pb->centre[0] = pb->centre[1] = 0.5;
  pb->centre[2]                 = -pb->radius;
  PetscCall(DMDACreate3d(comm, DM_BOUNDARY_NONE, DM_BOUNDARY_NONE, DM_BOUNDARY_NONE, DMDA_STENCIL_BOX, pb->n[0], pb->n[1], pb->n[2], PETSC_DECIDE, PETSC_DECIDE, 1, 3, 1, NULL, NULL, NULL, &pb->da));
  PetscCall(DMSetFromOptions(pb->da));
  PetscCall(DMSetUp(pb->da));
  PetscCall(DMDASetUniformCoordinates(pb->da, 0, 1, 0, 1, 0, H));
  PetscCall(DMCreateLocalVector(pb->da, &pb->local));
  PetscCall(DMCreateMatrix(pb->da, J));
  PetscCall(DMGetCoordinates(pb->da, &coords));
  PetscCall(MatNullSpaceCreateRigidBody(coords, &nsp));
  PetscCall(MatSetNearNullSpace(*J, nsp)); /* the multigrid of the Newton steps on the whole body */
  PetscCall(MatNullSpaceDestroy(&nsp));
  PetscCall(DMCreateGlobalVector(pb->da, u));
  /* the contact nodes: the bottom face (k = 0) */
  PetscCall(DMDAGetCorners(pb->da, &xs, &ys, &zs, &xm, &ym, &zm));
  PetscCall(VecGetOwnershipRange(*u, &rstart, NULL));
  pb->rstart   = rstart;
  pb->ncontact = zs == 0 ? xm * ym : 0;
  PetscCall(PetscMalloc1(3 * pb->ncontact + 1, &dofs));
  PetscCall(PetscMalloc1(3 * pb->ncontact + 1, &pb->X));
  for (PetscInt j = 0; j < (zs == 0 ? ym : 0); j++)
    for (PetscInt i = 0; i < xm; i++, m++)
      for (PetscInt d = 0; d < 3; d++) {
        dofs[3 * m + d]  = rstart + 3 * (j * xm + i) + d;
        pb->X[3 * m + d] = d == 0 ? (xs + i) * pb->h : d == 1 ? (ys + j) * pb->h : 0;
      }
  PetscCall(ISCreateGeneral(comm, 3 * pb->ncontact, dofs, PETSC_OWN_POINTER, &pb->dofs));
  PetscCall(VecCreateMPI(comm, 3 * pb->ncontact, PETSC_DETERMINE, &pb->normals));
  PetscCall(VecCreateMPI(comm, pb->ncontact, PETSC_DETERMINE, &pb->gaps));
  PetscCall(VecZeroEntries(pb->gaps));
  PetscCall(VecGetArray(pb->normals, &ua));
  for (PetscInt i = 0; i < pb->ncontact; i++) ua[3 * i] = ua[3 * i + 1] = 0, ua[3 * i + 2] = 1; /* the plane z = 0 */
  PetscCall(VecRestoreArray(pb->normals, &ua));
  if (pb->ball) PetscCall(MeasureBall(pb, *u));
  /* the initial guess: the top at its prescribed place, the rest following it linearly in z (no element inverted) */
  PetscCall(VecGetArray(*u, &ua));
  for (PetscInt k = 0; k < zm; k++)
    for (PetscInt j = 0; j < ym; j++)
      for (PetscInt i = 0; i < xm; i++)
        for (PetscInt d = 0; d < 3; d++) ua[3 * ((k * ym + j) * xm + i) + d] = pb->press[d] * (zs + k) / (pb->n[2] - 1);
  PetscCall(VecRestoreArray(*u, &ua));
  PetscCall(SNESSetFunction(snes, NULL, BlockFunction, pb));
  PetscCall(SNESSetJacobian(snes, *J, *J, BlockJacobian, pb));
  PetscFunctionReturn(0);
}

/* ---------------------------------------------------------------- the prism's K and b, stiffened */

static PetscErrorCode CubicFunction(SNES snes, Vec u, Vec f, void *ctx)
{
  Problem           *pb = (Problem *)ctx;
  const PetscScalar *ua;
  PetscScalar       *fa;
  PetscInt           n;

  PetscFunctionBeginUser;
  PetscCall(MatMult(pb->K, u, f));
  PetscCall(VecAXPY(f, -1.0, pb->b));
  PetscCall(VecGetLocalSize(u, &n));
  PetscCall(VecGetArrayRead(u, &ua));
  PetscCall(VecGetArray(f, &fa));
  for (PetscInt i = 0; i < n; i++) fa[i] += pb->kappa * ua[i] * ua[i] * ua[i];
  PetscCall(VecRestoreArray(f, &fa));
  PetscCall(VecRestoreArrayRead(u, &ua));
  PetscFunctionReturn(0);
}

static PetscErrorCode CubicJacobian(SNES snes, Vec u, Mat J, Mat Jp, void *ctx)
{
  Problem *pb = (Problem *)ctx;
  Vec      d;

  PetscFunctionBeginUser;
  PetscCall(MatCopy(pb->K, J, SAME_NONZERO_PATTERN));
  PetscCall(VecDuplicate(u, &d));
  PetscCall(VecPointwiseMult(d, u, u));
  PetscCall(VecScale(d, 3 * pb->kappa));
  PetscCall(MatDiagonalSet(J, d, ADD_VALUES));
  PetscCall(VecDestroy(&d));
  PetscFunctionReturn(0);
}

/* A Vec of the file, whole on every rank */
static PetscErrorCode LoadEverywhere(PetscViewer viewer, Vec *all)
{
  Vec        v;
  VecScatter toAll;

  PetscFunctionBeginUser;
  PetscCall(VecCreate(PetscObjectComm((PetscObject)viewer), &v));
  PetscCall(VecLoad(v, viewer));
  PetscCall(VecScatterCreateToAll(v, &toAll, all));
  PetscCall(VecScatterBegin(toAll, v, *all, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(toAll, v, *all, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterDestroy(&toAll));
  PetscCall(VecDestroy(&v));
  PetscFunctionReturn(0);
}

/*
   The reproduction: the affine model (kappa = 0, declared affine) solved first, kappa chosen so that the
   stiffening at its largest displacement is s max|b|, and how far off equilibrium F(u) = K u + kappa u^3 - b is at the
   free dofs of that point (what a solver that assumes an affine residual would call converged)
*/
static PetscErrorCode ChooseStiffening(Problem *pb, Mat J, Vec u)
{
  SNES            snes;
  Vec             f;
  PetscReal       s = 0.5, umax, off = 0;
  PetscErrorCode (*setAffine)(SNES, PetscBool);
  const PetscScalar *fa;
  const PetscInt    *idx;
  PetscInt           n, rstart;
  PetscBool         *contact;
  SNESConvergedReason reason;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-stiffening", &s, NULL));
  pb->kappa = 0;
  PetscCall(SNESCreate(PetscObjectComm((PetscObject)J), &snes));
  PetscCall(SNESSetOptionsPrefix(snes, "affine_"));
  PetscCall(SNESSetType(snes, "ssstar"));
  PetscCall(SNESSetFunction(snes, NULL, CubicFunction, pb));
  PetscCall(SNESSetJacobian(snes, J, J, CubicJacobian, pb));
  PetscCall(SNESSetFromOptions(snes));
  PetscCall(DeclareContact(snes, pb));
  PetscCall(PetscObjectQueryFunction((PetscObject)snes, "SNESSSStarSetAffine_C", &setAffine));
  PetscCheck(setAffine, PETSC_COMM_WORLD, PETSC_ERR_ARG_WRONG, "the type ssstar is not loaded: -dll_append <dir>/libssstar.so");
  PetscCall((*setAffine)(snes, PETSC_TRUE));
  PetscCall(VecZeroEntries(u));
  PetscCall(SNESSolve(snes, NULL, u));
  PetscCall(SNESGetConvergedReason(snes, &reason));
  PetscCheck(reason > 0, PETSC_COMM_WORLD, PETSC_ERR_NOT_CONVERGED, "the affine model did not converge (%s)", SNESConvergedReasons[reason]);
  PetscCall(SNESDestroy(&snes));
  PetscCall(VecNorm(u, NORM_INFINITY, &umax));
  pb->kappa = s * pb->bmax / (umax * umax * umax);
  PetscCall(VecDuplicate(u, &f));
  PetscCall(CubicFunction(NULL, u, f, pb));
  PetscCall(VecGetLocalSize(u, &n));
  PetscCall(VecGetOwnershipRange(u, &rstart, NULL));
  PetscCall(PetscCalloc1(n + 1, &contact));
  PetscCall(ISGetIndices(pb->dofs, &idx));
  for (PetscInt k = 0; k < 3 * pb->ncontact; k++) contact[idx[k] - rstart] = PETSC_TRUE;
  PetscCall(ISRestoreIndices(pb->dofs, &idx));
  PetscCall(VecGetArrayRead(f, &fa));
  for (PetscInt j = 0; j < n; j++)
    if (!contact[j]) off = PetscMax(off, PetscAbsScalar(fa[j]));
  PetscCall(VecRestoreArrayRead(f, &fa));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &off, 1, MPIU_REAL, MPIU_MAX, PETSC_COMM_WORLD));
  PetscCall(PetscFree(contact));
  PetscCall(VecDestroy(&f));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "kappa = %g: at the affine model's solution F is off equilibrium by %.3g of max|b| at the free dofs\n", (double)pb->kappa, (double)(off / pb->bmax)));
  PetscCall(VecZeroEntries(u));
  PetscFunctionReturn(0);
}

static PetscErrorCode CreateCubic(MPI_Comm comm, Problem *pb, SNES snes, Mat *J, Vec *u)
{
  char               file[PETSC_MAX_PATH_LEN] = "";
  PetscViewer        viewer;
  Vec                idx, nrm, gap;
  const PetscScalar *ia, *na, *ga;
  PetscInt           N, rstart, rend, m = 0, *dofs;
  PetscScalar       *a, *b;
  PetscBool          set;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsGetString(NULL, NULL, "-load", file, sizeof(file), &set));
  PetscCheck(set, comm, PETSC_ERR_USER, "-problem cubic needs -load <file> (examples/prism -save_whole <file>)");
  PetscCall(PetscViewerBinaryOpen(comm, file, FILE_MODE_READ, &viewer));
  PetscCall(MatCreate(comm, &pb->K));
  PetscCall(MatSetType(pb->K, MATAIJ));
  PetscCall(MatSetBlockSize(pb->K, 3)); /* a node's dofs on one rank */
  PetscCall(MatLoad(pb->K, viewer));
  PetscCall(MatCreateVecs(pb->K, u, &pb->b));
  PetscCall(VecLoad(pb->b, viewer));
  PetscCall(LoadEverywhere(viewer, &idx));
  PetscCall(LoadEverywhere(viewer, &nrm));
  PetscCall(LoadEverywhere(viewer, &gap));
  PetscCall(PetscViewerDestroy(&viewer));
  /* the contact nodes whose dofs this rank owns */
  PetscCall(MatGetOwnershipRange(pb->K, &rstart, &rend));
  PetscCall(VecGetSize(gap, &N));
  PetscCall(VecGetArrayRead(idx, &ia));
  PetscCall(VecGetArrayRead(nrm, &na));
  PetscCall(VecGetArrayRead(gap, &ga));
  for (PetscInt i = 0; i < N; i++) m += PetscRealPart(ia[3 * i]) >= rstart && PetscRealPart(ia[3 * i]) < rend;
  pb->ncontact = m;
  PetscCall(PetscMalloc1(3 * m + 1, &dofs));
  PetscCall(VecCreateMPI(comm, 3 * m, PETSC_DETERMINE, &pb->normals));
  PetscCall(VecCreateMPI(comm, m, PETSC_DETERMINE, &pb->gaps));
  PetscCall(VecGetArray(pb->normals, &a));
  PetscCall(VecGetArray(pb->gaps, &b));
  m = 0;
  for (PetscInt i = 0; i < N; i++) {
    const PetscInt first = (PetscInt)PetscRealPart(ia[3 * i]);

    if (first < rstart || first >= rend) continue;
    for (PetscInt k = 0; k < 3; k++) {
      dofs[3 * m + k] = (PetscInt)PetscRealPart(ia[3 * i + k]);
      a[3 * m + k]    = na[3 * i + k];
      PetscCheck(dofs[3 * m + k] < rend, PETSC_COMM_SELF, PETSC_ERR_SUP, "contact node %" PetscInt_FMT " straddles two ranks", i);
    }
    b[m++] = ga[i];
  }
  PetscCall(VecRestoreArray(pb->gaps, &b));
  PetscCall(VecRestoreArray(pb->normals, &a));
  PetscCall(VecRestoreArrayRead(gap, &ga));
  PetscCall(VecRestoreArrayRead(nrm, &na));
  PetscCall(VecRestoreArrayRead(idx, &ia));
  PetscCall(VecDestroy(&idx));
  PetscCall(VecDestroy(&nrm));
  PetscCall(VecDestroy(&gap));
  PetscCall(ISCreateGeneral(comm, 3 * pb->ncontact, dofs, PETSC_OWN_POINTER, &pb->dofs));
  PetscCall(VecNorm(pb->b, NORM_INFINITY, &pb->bmax));
  PetscCall(MatDuplicate(pb->K, MAT_COPY_VALUES, J));
  PetscCall(ChooseStiffening(pb, *J, *u));
  PetscCall(SNESSetFunction(snes, NULL, CubicFunction, pb));
  PetscCall(SNESSetJacobian(snes, *J, *J, CubicJacobian, pb));
  PetscFunctionReturn(0);
}

/* ---------------------------------------------------------------- the checks of an answer */

/*
   F at the solution: max |F| over the dofs that are neither contact nor Dirichlet dofs, and the contact law at every
   contact node in the frame of its normal (as measured at the solution: the ball's exact gap there), both relative to
   the largest contact force F and the largest displacement U of the body, as docs/derivation.md (12.3) bounds them. Coulomb with phi; the
   tangential displacement is the static problem's, (q - n n) u.
*/
static PetscErrorCode Check(SNES snes, Problem *pb, Vec u, PetscReal *equilibrium, PetscReal *law, PetscInt counts[3])
{
  Vec                f;
  const PetscScalar *ua, *fa, *na, *ga;
  const PetscInt    *idx;
  PetscInt           n, rstart, ndir = 0, *dir = NULL;
  PetscBool         *skip;
  PetscReal          scales[2] = {0, 0}, worst[2] = {0, 0};

  PetscFunctionBeginUser;
  if (pb->ball) PetscCall(MeasureBall(pb, u)); /* the exact geometry at the solution */
  PetscCall(VecDuplicate(u, &f));
  PetscCall(SNESComputeFunction(snes, u, f));
  PetscCall(VecGetLocalSize(u, &n));
  PetscCall(VecGetOwnershipRange(u, &rstart, NULL));
  PetscCall(PetscCalloc1(n + 1, &skip));
  if (pb->type == PROBLEM_BLOCK) PetscCall(DirichletRows(pb, &ndir, &dir));
  for (PetscInt r = 0; r < ndir; r++) skip[dir[r] - rstart] = PETSC_TRUE;
  PetscCall(PetscFree(dir));
  PetscCall(ISGetIndices(pb->dofs, &idx));
  PetscCall(VecGetArrayRead(u, &ua));
  PetscCall(VecGetArrayRead(f, &fa));
  PetscCall(VecGetArrayRead(pb->normals, &na));
  PetscCall(VecGetArrayRead(pb->gaps, &ga));
  for (PetscInt k = 0; k < 3 * pb->ncontact; k++) {
    skip[idx[k] - rstart] = PETSC_TRUE;
    scales[0]             = PetscMax(scales[0], PetscAbsScalar(ua[idx[k] - rstart]));
    scales[1]             = PetscMax(scales[1], PetscAbsScalar(fa[idx[k] - rstart]));
  }
  if (pb->type == PROBLEM_CUBIC) scales[1] = PetscMax(scales[1], pb->bmax);
  for (PetscInt j = 0; j < n; j++) scales[0] = PetscMax(scales[0], PetscAbsScalar(ua[j])); /* the body's: every contact point may stick */
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, scales, 2, MPIU_REAL, MPIU_MAX, PetscObjectComm((PetscObject)u)));
  for (PetscInt j = 0; j < n; j++)
    if (!skip[j]) worst[0] = PetscMax(worst[0], PetscAbsScalar(fa[j]) / scales[1]);
  counts[0] = counts[1] = counts[2] = 0;
  for (PetscInt i = 0; i < pb->ncontact; i++) {
    const PetscScalar *nv = &na[3 * i];
    PetscReal          x[3], r[3], wn = PetscRealPart(ga[i]), rn = 0, wt[3], rt[3], wtn, rtn, v;

    for (PetscInt k = 0; k < 3; k++) {
      x[k] = PetscRealPart(ua[idx[3 * i + k] - rstart]);
      r[k] = PetscRealPart(fa[idx[3 * i + k] - rstart]);
      wn += PetscRealPart(nv[k]) * x[k];
      rn += PetscRealPart(nv[k]) * r[k];
    }
    for (PetscInt k = 0; k < 3; k++) {
      wt[k] = x[k] - (wn - PetscRealPart(ga[i])) * PetscRealPart(nv[k]);
      rt[k] = r[k] - rn * PetscRealPart(nv[k]);
    }
    wtn = PetscSqrtReal(wt[0] * wt[0] + wt[1] * wt[1] + wt[2] * wt[2]);
    rtn = PetscSqrtReal(rt[0] * rt[0] + rt[1] * rt[1] + rt[2] * rt[2]);
    v   = PetscMax(-wn / scales[0], -rn / scales[1]);
    v   = PetscMax(v, PetscMin(PetscAbsReal(wn) / scales[0], PetscAbsReal(rn) / scales[1])); /* complementarity */
    v   = PetscMax(v, (rtn - pb->phi * rn) / scales[1]);
    if (wn <= CHECK_TOL * scales[0] && wtn > CHECK_TOL * scales[0]) /* sliding: the force against the slip */
      for (PetscInt k = 0; k < 3; k++) v = PetscMax(v, PetscAbsReal(rt[k] + pb->phi * rn * wt[k] / wtn) / scales[1]);
    worst[1] = PetscMax(worst[1], v);
    counts[wn > CHECK_TOL * scales[0] ? 0 : (wtn > CHECK_TOL * scales[0] ? 1 : 2)]++;
  }
  PetscCall(VecRestoreArrayRead(pb->gaps, &ga));
  PetscCall(VecRestoreArrayRead(pb->normals, &na));
  PetscCall(VecRestoreArrayRead(f, &fa));
  PetscCall(VecRestoreArrayRead(u, &ua));
  PetscCall(ISRestoreIndices(pb->dofs, &idx));
  PetscCall(PetscFree(skip));
  PetscCall(VecDestroy(&f));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, worst, 2, MPIU_REAL, MPIU_MAX, PetscObjectComm((PetscObject)u)));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, counts, 3, MPIU_INT, MPI_SUM, PetscObjectComm((PetscObject)u)));
  *equilibrium = worst[0];
  *law         = worst[1];
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  Problem             pb;
  SNES                snes;
  Mat                 J;
  Vec                 u;
  PetscInt            its, counts[3], jacobians = -1, updates = -1, nfuncs;
  PetscReal           equilibrium = PETSC_MAX_REAL, law = PETSC_MAX_REAL;
  PetscBool           affine = PETSC_FALSE, ok, isssstar;
  SNESConvergedReason reason;
  MPI_Comm            comm;

  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  comm = PETSC_COMM_WORLD;
  PetscCall(PetscMemzero(&pb, sizeof(pb)));
  pb.phi    = 0.3;
  pb.radius = 2;
  PetscCall(PetscOptionsGetEnum(NULL, NULL, "-problem", ProblemTypes, (PetscEnum *)&pb.type, NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-snes_ssstar_friction", &pb.phi, NULL));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-affine", &affine, NULL));
  PetscCall(SNESCreate(comm, &snes));
  if (pb.type == PROBLEM_BLOCK) PetscCall(CreateBlock(comm, &pb, snes, &J, &u));
  else PetscCall(CreateCubic(comm, &pb, snes, &J, &u));
  PetscCall(SNESSetFromOptions(snes));
  PetscCall(PetscObjectTypeCompare((PetscObject)snes, "ssstar", &isssstar));
  if (isssstar) { /* another type (newtonls -snes_test_jacobian) solves the block without its contact */
    PetscErrorCode (*setAffine)(SNES, PetscBool);
    PetscErrorCode (*setUpdate)(SNES, PetscErrorCode (*)(SNES, Vec, void *), void *);

    PetscCall(DeclareContact(snes, &pb));
    if (affine) {
      PetscCall(Composed(snes, "SNESSSStarSetAffine_C", (void (**)(void))&setAffine));
      PetscCall((*setAffine)(snes, PETSC_TRUE));
    }
    if (pb.ball) {
      PetscCall(Composed(snes, "SNESSSStarSetContactUpdate_C", (void (**)(void))&setUpdate));
      PetscCall((*setUpdate)(snes, ContactUpdate, &pb));
    }
  }
  PetscCall(SNESSolve(snes, NULL, u));
  PetscCall(SNESGetConvergedReason(snes, &reason));
  PetscCall(SNESGetIterationNumber(snes, &its));
  PetscCall(SNESGetNumberFunctionEvals(snes, &nfuncs));
  if (isssstar) {
    PetscErrorCode (*getCounts)(SNES, PetscInt *, PetscInt *);

    PetscCall(Composed(snes, "SNESSSStarGetNonlinearCounts_C", (void (**)(void))&getCounts));
    PetscCall((*getCounts)(snes, &jacobians, &updates));
  }
  PetscCall(Check(snes, &pb, u, &equilibrium, &law, counts));
  ok = (PetscBool)(equilibrium <= CHECK_TOL && law <= CHECK_TOL);
  PetscCall(PetscPrintf(comm, "%s after %" PetscInt_FMT " iterations, %" PetscInt_FMT " Jacobian evaluations, %" PetscInt_FMT " function evaluations, %" PetscInt_FMT " contact updates; separated/sliding/sticking %" PetscInt_FMT "/%" PetscInt_FMT "/%" PetscInt_FMT "; F at the free dofs %.1e, contact law violation %.1e of the force and displacement scales: %s\n",
                        SNESConvergedReasons[reason], its, jacobians, nfuncs, updates, counts[0], counts[1], counts[2], (double)equilibrium, (double)law, ok ? "the answer holds" : "THE ANSWER DOES NOT HOLD"));
  PetscCall(SNESDestroy(&snes));
  PetscCall(MatDestroy(&J));
  PetscCall(VecDestroy(&u));
  PetscCall(ISDestroy(&pb.dofs));
  PetscCall(VecDestroy(&pb.normals));
  PetscCall(VecDestroy(&pb.gaps));
  PetscCall(PetscFree(pb.X));
  PetscCall(VecDestroy(&pb.local));
  PetscCall(DMDestroy(&pb.da));
  PetscCall(MatDestroy(&pb.K));
  PetscCall(VecDestroy(&pb.b));
  PetscCall(PetscFinalize());
  return reason <= 0 ? 2 : ok ? 0 : 1;
}
