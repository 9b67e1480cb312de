/*
   The Newton step on the whole body, P never formed (reduction none). With Q the rotation into the nodes' frames at
   the contact dofs (identity elsewhere), K' = Q K Q^T and dv = Q du, the system of newtonimpl.h divided by gamma is

     free dof j:      (K' dv)_j                               = y_j / gamma
     contact node i:  S_i (K' dv)_i + T_i dv_i / gamma        = y_i / gamma

   i.e. M = Shat K' + That / gamma with Shat = blockdiag(S_i, 1), That = blockdiag(T_i, 0). The rows with S row = 0 and
   T row = e_r (sticking nodes, the normal of a node in contact) say dv = y: they are eliminated symmetrically
   (MatZeroRowsColumns, unit rows scaled by 1/gamma). Interior and separated rows are K's; a sliding node's tangential
   rows add phi om times its normal row of K' and W/gamma (docs/derivation.md section 5): the only unsymmetric part. The
   system is solved by the SNES's KSP: CG where it is symmetric, GMRES (right preconditioned) where it is not, both
   preconditioned by algebraic multigrid (PCGAMG with K's near-null space, the rigid-body modes, rotated like K'),
   to the tolerances the iteration sets (inexact Newton). The multigrid of an earlier step is kept while few nodes
   changed their known rows, and built anew (interpolation included) when more did: an interpolation built for
   other rows known, even on the same matrix pattern, costs more Krylov iterations than its set-up saves.

   Floating bodies (docs/derivation.md (14.5)): where the step's states leave rigid-body motions U free, the Krylov
   solver runs on M + Shat (c/gamma) U U^T (a shell: M and the low-rank term), preconditioned by the multigrid of M
   with a small shift on the free motions' unknown contact dofs, which makes it regular: the preconditioned operator
   has one outlier eigenvalue per free motion, which the Krylov iteration removes in about as many iterations.
*/
#include "newtonimpl.h"

/* GMRES's restart when ssstar chooses GMRES: restarts stall it on the hard steps, and its basis is affordable */
#define SSSTAR_GMRES_RESTART 100
/* GAMG's smoothers unless the options name others: one sweep of SOR per level and direction (bench/levers.py) */
#define SSSTAR_SMOOTHER_OPTIONS 4
/* floating bodies: the preconditioner's shift on the free motions' unknown contact dofs, in units of 1/gamma */
#define SSSTAR_FREE_SHIFT (1e-2 * SSSTAR_FREE_STIFFNESS)

typedef struct {
  Mat            Kr;            /* K' = Q K Q^T; K itself (a reference) when there are no frames                 */
  Mat            Qt;            /* Q^T, block diagonal; NULL without frames                                      */
  Mat            Shat;          /* blockdiag(S_i, 1): fixed 3x3 pattern at the contact nodes                     */
  Mat            M;             /* the Newton matrix of the step                                                 */
  MatNullSpace   nearNull;      /* K's near-null space in the nodes' frames, or NULL                             */
  Vec            rhs, dv;       /* of the step, dv = Q du                                                        */
  PetscInt       rstart;        /* first row of K on this rank                                                   */
  PetscInt       bs;            /* K's block size (3: the dofs of a node)                                        */
  PetscInt       nknown, *known; /* global rows of the known dofs of the step                                    */
  unsigned char *mask, *pcMask; /* per local node: bits of its unknown rows, now and when the multigrid was built */
  PetscBool      pcBuilt;
  PetscBool      refinable;     /* the KSP holds the last step's system and solution (SSStarNewtonRefine)         */
  PetscInt       nnodesGlobal;
  PetscBool      userKSPType, userTolerances, userRestart;
  PetscReal     *Sknown, *Tknown; /* S = 0, T = I per node: every contact dof known                            */
  Mat            shell;         /* floating bodies: M + the proximal term on the step's free motions             */
  const PetscReal *S;           /* the step's S blocks, for the shell                                            */
  unsigned char *touched;       /* per local node: a free motion of the step moves it                            */
  PetscInt       pcFree;        /* free motions when the multigrid was built                                     */
  char          *smoother[SSSTAR_SMOOTHER_OPTIONS]; /* the options database entries ssstar set, cleared at reset  */
} Newton_Full;

/* Q^T: at contact node i the 3x3 block R_i^T (frame to global), identity on every other dof */
static PetscErrorCode CreateRotation(SSStarNewton nt, Mat *Qt)
{
  Newton_Full               *nf = (Newton_Full *)nt->data;
  const SSStarContactLayout *L  = &nt->layout;
  PetscInt                   m, *nnz;

  PetscFunctionBegin;
  PetscCall(MatGetLocalSize(nt->A, &m, NULL));
  PetscCall(PetscMalloc1(m, &nnz));
  for (PetscInt j = 0; j < m; j++) nnz[j] = 1;
  for (PetscInt k = 0; k < 3 * L->nnodes; k++) nnz[L->dofs[k]] = 3;
  PetscCall(MatCreateAIJ(PetscObjectComm((PetscObject)nt->A), m, m, PETSC_DETERMINE, PETSC_DETERMINE, 0, nnz, 0, NULL, Qt));
  PetscCall(PetscFree(nnz));
  PetscCall(MatSetBlockSize(*Qt, nf->bs));
  for (PetscInt j = 0; j < m; j++) PetscCall(MatSetValue(*Qt, nf->rstart + j, nf->rstart + j, 1.0, INSERT_VALUES));
  for (PetscInt i = 0; i < L->nnodes; i++) {
    const PetscReal *R = &L->frames[9 * i];
    PetscInt         rows[3];
    PetscScalar      RT[9];


    for (PetscInt k = 0; k < 3; k++) rows[k] = nf->rstart + L->dofs[3 * i + k];
    for (PetscInt r = 0; r < 3; r++)
      for (PetscInt c = 0; c < 3; c++) RT[3 * r + c] = R[3 * c + r];
    PetscCall(MatSetValues(*Qt, 3, rows, 3, rows, RT, INSERT_VALUES));
  }
  PetscCall(MatAssemblyBegin(*Qt, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(*Qt, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

/* K's near-null space (the rigid-body modes a scene attaches to K), rotated like K' */
static PetscErrorCode CreateNearNullSpace(SSStarNewton nt)
{
  Newton_Full  *nf = (Newton_Full *)nt->data;
  MatNullSpace  nsp;
  PetscBool     hasConstant;
  PetscInt      n;
  const Vec    *vecs;
  Vec          *rotated;

  PetscFunctionBegin;
  PetscCall(MatGetNearNullSpace(nt->A, &nsp));
  if (!nsp) PetscFunctionReturn(0);
  if (!nf->Qt) {
    PetscCall(PetscObjectReference((PetscObject)nsp));
    nf->nearNull = nsp;
    PetscFunctionReturn(0);
  }
  PetscCall(MatNullSpaceGetVecs(nsp, &hasConstant, &n, &vecs));
  PetscCall(PetscMalloc1(n, &rotated));
  for (PetscInt k = 0; k < n; k++) {
    PetscCall(VecDuplicate(vecs[k], &rotated[k]));
    PetscCall(MatMultTranspose(nf->Qt, vecs[k], rotated[k]));
  }
  PetscCall(MatNullSpaceCreate(PetscObjectComm((PetscObject)nt->A), hasConstant, n, rotated, &nf->nearNull));
  for (PetscInt k = 0; k < n; k++) PetscCall(VecDestroy(&rotated[k]));
  PetscCall(PetscFree(rotated));
  PetscFunctionReturn(0);
}

/* Shat with its pattern: a full 3x3 block per contact node (the identity for now), 1 on every free dof */
static PetscErrorCode CreateRowCombination(SSStarNewton nt)
{
  Newton_Full               *nf = (Newton_Full *)nt->data;
  const SSStarContactLayout *L  = &nt->layout;
  PetscInt                   m, *nnz;
  const PetscScalar          I3[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};

  PetscFunctionBegin;
  PetscCall(MatGetLocalSize(nt->A, &m, NULL));
  PetscCall(PetscMalloc1(m, &nnz));
  for (PetscInt j = 0; j < m; j++) nnz[j] = 1;
  for (PetscInt k = 0; k < 3 * L->nnodes; k++) nnz[L->dofs[k]] = 3;
  PetscCall(MatCreateAIJ(PetscObjectComm((PetscObject)nt->A), m, m, PETSC_DETERMINE, PETSC_DETERMINE, 0, nnz, 0, NULL, &nf->Shat));
  PetscCall(PetscFree(nnz));
  PetscCall(MatSetBlockSize(nf->Shat, nf->bs)); /* M inherits it: the multigrid aggregates nodes, not dofs */
  PetscCall(MatSetOption(nf->Shat, MAT_IGNORE_ZERO_ENTRIES, PETSC_FALSE));
  for (PetscInt j = 0; j < m; j++) PetscCall(MatSetValue(nf->Shat, nf->rstart + j, nf->rstart + j, 1.0, INSERT_VALUES));
  for (PetscInt i = 0; i < L->nnodes; i++) {
    PetscInt rows[3];

    for (PetscInt k = 0; k < 3; k++) rows[k] = nf->rstart + L->dofs[3 * i + k];
    PetscCall(MatSetValues(nf->Shat, 3, rows, 3, rows, I3, INSERT_VALUES));
  }
  PetscCall(MatAssemblyBegin(nf->Shat, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(nf->Shat, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

/*
   GAMG's smoothers, unless the options name the levels' KSP or PC: one SOR sweep (Richardson) before and after the
   coarse correction on every level, instead of GAMG's two Chebyshev steps preconditioned by Jacobi. Measured on the
   prism (bench/levers.py, levels 8-24, 2 ranks): a third fewer Krylov iterations and flops, no eigenvalue estimates in
   the set-ups, the same Newton iterations and solutions. GAMG's coarse operators have rows and columns of zeros (an
   aggregate with fewer dofs than the six rigid-body modes), on which SOR would divide by zero: its diagonal is shifted
   by 1e-12 of K's scale (1/gamma, the mean diagonal at the contact dofs), which leaves every other row as it is. The
   entries live in the options database (PCGAMG reads its levels' smoothers only from there) until the reset.
*/
static PetscErrorCode SetSmootherDefaults(SSStarNewton nt, PC pc)
{
  Newton_Full *nf = (Newton_Full *)nt->data;
  PetscOptions options = ((PetscObject)pc)->options;
  const char  *prefix  = ((PetscObject)pc)->prefix ? ((PetscObject)pc)->prefix : "";
  const char  *names[SSSTAR_SMOOTHER_OPTIONS] = {"mg_levels_ksp_type", "mg_levels_pc_type", "mg_levels_ksp_max_it", "mg_levels_pc_sor_diagonal_shift"};
  char         values[SSSTAR_SMOOTHER_OPTIONS][32] = {"richardson", "sor", "1", ""};
  PetscBool    isgamg, set[2];

  PetscFunctionBegin;
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCGAMG, &isgamg));
  if (!isgamg) PetscFunctionReturn(0);
  for (PetscInt k = 0; k < 2; k++) {
    char name[256];

    PetscCall(PetscSNPrintf(name, sizeof(name), "-%s%s", prefix, names[k]));
    PetscCall(PetscOptionsHasName(options, NULL, name, &set[k]));
  }
  if (set[0] || set[1]) PetscFunctionReturn(0);
  PetscCall(PetscSNPrintf(values[3], sizeof(values[3]), "%g", 1e-12 / nt->gamma));
  for (PetscInt k = 0; k < SSSTAR_SMOOTHER_OPTIONS; k++) {
    char      name[256];
    PetscBool given;

    PetscCall(PetscSNPrintf(name, sizeof(name), "-%s%s", prefix, names[k]));
    PetscCall(PetscOptionsHasName(options, NULL, name, &given));
    if (given) continue;
    PetscCall(PetscOptionsSetValue(options, name, values[k]));
    PetscCall(PetscStrallocpy(name, &nf->smoother[k]));
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode SSStarNewtonSetUp_Full(SSStarNewton nt)
{
  Newton_Full               *nf  = (Newton_Full *)nt->data;
  const SSStarContactLayout *L   = &nt->layout;
  KSP                        ksp = nt->snes->ksp;
  PC                         pc;
  PetscBool                  hasFrames, isgamg, set;

  PetscFunctionBegin;
  PetscCall(MatGetOwnershipRange(nt->A, &nf->rstart, NULL));
  PetscCall(MatGetBlockSize(nt->A, &nf->bs));
  PetscCall(MPIU_Allreduce(&L->nnodes, &nf->nnodesGlobal, 1, MPIU_INT, MPI_SUM, PetscObjectComm((PetscObject)nt->A)));
  hasFrames = (PetscBool)(L->frames != NULL); /* a rank without contact nodes has no frames but joins the PtAP */
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &hasFrames, 1, MPIU_BOOL, MPI_LOR, PetscObjectComm((PetscObject)nt->A)));
  if (hasFrames) {
    PetscCall(CreateRotation(nt, &nf->Qt));
    PetscCall(MatPtAP(nt->A, nf->Qt, MAT_INITIAL_MATRIX, PETSC_DEFAULT, &nf->Kr));
  } else {
    PetscCall(PetscObjectReference((PetscObject)nt->A));
    nf->Kr = nt->A;
  }
  PetscCall(CreateNearNullSpace(nt));
  PetscCall(CreateRowCombination(nt));
  PetscCall(MatCreateVecs(nt->A, &nf->dv, &nf->rhs));
  PetscCall(PetscMalloc3(3 * L->nnodes, &nf->known, L->nnodes, &nf->mask, L->nnodes, &nf->touched));
  PetscCall(PetscCalloc1(L->nnodes, &nf->pcMask));
  PetscCall(PetscMalloc2(9 * L->nnodes, &nf->Sknown, 9 * L->nnodes, &nf->Tknown));
  for (PetscInt i = 0; i < L->nnodes; i++)
    for (PetscInt k = 0; k < 9; k++) {
      nf->Sknown[9 * i + k] = 0;
      nf->Tknown[9 * i + k] = (PetscReal)(k % 4 == 0);
    }
  nf->pcBuilt = PETSC_FALSE;

  /* the SNES's KSP: GMRES or CG with GAMG unless the options name others (they are read again for the new types) */
  PetscCall(PetscOptionsHasName(((PetscObject)ksp)->options, ((PetscObject)ksp)->prefix, "-ksp_type", &nf->userKSPType));
  PetscCall(PetscOptionsHasName(((PetscObject)ksp)->options, ((PetscObject)ksp)->prefix, "-ksp_rtol", &nf->userTolerances));
  PetscCall(PetscOptionsHasName(((PetscObject)ksp)->options, ((PetscObject)ksp)->prefix, "-ksp_gmres_restart", &nf->userRestart));
  PetscCall(SSStarNewtonSetKSPDefaults(nt, KSPGMRES, PCGAMG));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCGAMG, &isgamg));
  PetscCall(PetscOptionsHasName(((PetscObject)pc)->options, ((PetscObject)pc)->prefix, "-pc_gamg_use_sa_esteig", &set));
  /* the smoothed aggregation's eigenvalue estimate made the Chebyshev smoothers unstable on these matrices (an
     indefinite preconditioner for an SPD Newton matrix, and GMRES 40 % slower): the smoothers estimate their own */
  if (isgamg && !set) PetscCall(PCGAMGSetUseSAEstEig(pc, PETSC_FALSE));
  PetscCall(SetSmootherDefaults(nt, pc));
  PetscCall(KSPSetFromOptions(ksp));
  PetscFunctionReturn(0);
}

/* A new gamma changes the unit rows and W/gamma: the multigrid is built again */
static PetscErrorCode SSStarNewtonSetScaling_Full(SSStarNewton nt)
{
  PetscFunctionBegin;
  ((Newton_Full *)nt->data)->pcBuilt = PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* The nodes the step's free motions move (none without floating bodies), and the step's S for the shell */
static PetscErrorCode MarkFreeMotions(SSStarNewton nt, const PetscReal S[])
{
  Newton_Full        *nf = (Newton_Full *)nt->data;
  const SSStarKernel *kn = nt->layout.kernel;
  const PetscInt      n3 = 3 * nt->layout.nnodes;

  PetscFunctionBegin;
  nf->S = S;
  for (PetscInt i = 0; i < nt->layout.nnodes; i++) {
    nf->touched[i] = 0;
    for (PetscInt f = 0; kn && f < kn->nfree; f++)
      for (PetscInt r = 0; r < 3; r++)
        if (kn->free[f * n3 + 3 * i + r] != 0.0) nf->touched[i] = 1;
  }
  PetscFunctionReturn(0);
}

/*
   The shell of a step with free motions U of floating bodies (in the nodes' frames, zero at the known dofs):
   y = M x - (shift / gamma) x on the touched unknown contact dofs + (c / gamma) Shat U U^T x, c = SSSTAR_FREE_STIFFNESS
*/
static PetscErrorCode MultFree(Mat A, Vec x, Vec y)
{
  SSStarNewton               nt;
  Newton_Full               *nf;
  const SSStarContactLayout *L;
  const SSStarKernel        *kn;
  const PetscScalar         *xa;
  PetscScalar               *ya;
  PetscReal                 *t;
  PetscInt                   n3;

  PetscFunctionBegin;
  PetscCall(MatShellGetContext(A, &nt));
  nf = (Newton_Full *)nt->data;
  L  = &nt->layout;
  kn = L->kernel;
  n3 = 3 * L->nnodes;
  PetscCall(MatMult(nf->M, x, y));
  PetscCall(PetscCalloc1(kn->nfree, &t));
  PetscCall(VecGetArrayRead(x, &xa));
  for (PetscInt f = 0; f < kn->nfree; f++)
    for (PetscInt d = 0; d < n3; d++) t[f] += kn->free[f * n3 + d] * PetscRealPart(xa[L->dofs[d]]);
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, t, kn->nfree, MPIU_REAL, MPIU_SUM, PetscObjectComm((PetscObject)A)));
  PetscCall(VecGetArray(y, &ya));
  for (PetscInt i = 0; i < L->nnodes; i++) {
    const PetscReal *S = &nf->S[9 * i];
    PetscReal        Ut[3] = {0, 0, 0};

    if (!nf->touched[i]) continue;
    for (PetscInt f = 0; f < kn->nfree; f++)
      for (PetscInt k = 0; k < 3; k++) Ut[k] += kn->free[f * n3 + 3 * i + k] * t[f];
    for (PetscInt r = 0; r < 3; r++) {
      const PetscInt d = L->dofs[3 * i + r];

      if (!(nf->mask[i] & (1 << r))) continue;
      ya[d] += (S[3 * r] * Ut[0] + S[3 * r + 1] * Ut[1] + S[3 * r + 2] * Ut[2]) * SSSTAR_FREE_STIFFNESS / nt->gamma - SSSTAR_FREE_SHIFT / nt->gamma * xa[d];
    }
  }
  PetscCall(VecRestoreArray(y, &ya));
  PetscCall(VecRestoreArrayRead(x, &xa));
  PetscCall(PetscFree(t));
  PetscFunctionReturn(0);
}

/* The Krylov solver's operator: M, or the shell of MultFree when the step leaves motions free */
static PetscErrorCode KrylovOperator(SSStarNewton nt, Mat *A)
{
  Newton_Full *nf = (Newton_Full *)nt->data;
  PetscInt     m, M;

  PetscFunctionBegin;
  *A = nf->M;
  if (!nt->layout.kernel || !nt->layout.kernel->nfree) PetscFunctionReturn(0);
  if (!nf->shell) {
    PetscCall(MatGetLocalSize(nf->M, &m, NULL));
    PetscCall(MatGetSize(nf->M, &M, NULL));
    PetscCall(MatCreateShell(PetscObjectComm((PetscObject)nf->M), m, m, M, M, nt, &nf->shell));
    PetscCall(MatShellSetOperation(nf->shell, MATOP_MULT, (void (*)(void))MultFree));
  }
  *A = nf->shell;
  PetscFunctionReturn(0);
}

/*
   M, rhs = y / gamma with the known dofs eliminated, and whether M is symmetric: it is unless some unknown row
   combines K's rows (S row other than e_r: the sliding law's phi om) or T is unsymmetric on the unknown dofs
*/
static PetscErrorCode AssembleNewtonMatrix(SSStarNewton nt, const PetscReal S[], const PetscReal T[], Vec y, PetscBool *symmetric)
{
  Newton_Full               *nf  = (Newton_Full *)nt->data;
  const SSStarContactLayout *L   = &nt->layout;
  const PetscReal            ig  = 1 / nt->gamma;
  PetscBool                  sym = PETSC_TRUE;

  PetscFunctionBegin;
  nf->nknown = 0;
  for (PetscInt i = 0; i < L->nnodes; i++) {
    const PetscReal *Si = &S[9 * i], *Ti = &T[9 * i];
    PetscInt         rows[3];
    PetscScalar      Sv[9];

    nf->mask[i] = 0;
    for (PetscInt r = 0; r < 3; r++) {
      rows[r] = nf->rstart + L->dofs[3 * i + r];
      if (SSStarKnownRow(Si, Ti, r)) nf->known[nf->nknown++] = rows[r];
      else nf->mask[i] |= (unsigned char)(1 << r);
    }
    for (PetscInt r = 0; r < 3; r++) {
      if (!(nf->mask[i] & (1 << r))) continue;
      for (PetscInt k = 0; k < 3; k++) {
        if (Si[3 * r + k] != (PetscReal)(k == r)) sym = PETSC_FALSE;
        if ((nf->mask[i] & (1 << k)) && Ti[3 * r + k] != Ti[3 * k + r]) sym = PETSC_FALSE;
      }
    }
    for (PetscInt k = 0; k < 9; k++) Sv[k] = Si[k];
    PetscCall(MatSetValues(nf->Shat, 3, rows, 3, rows, Sv, INSERT_VALUES));
  }
  PetscCall(MatAssemblyBegin(nf->Shat, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(nf->Shat, MAT_FINAL_ASSEMBLY));
  PetscCall(MatMatMult(nf->Shat, nf->Kr, nf->M ? MAT_REUSE_MATRIX : MAT_INITIAL_MATRIX, PETSC_DEFAULT, &nf->M));
  PetscCall(MarkFreeMotions(nt, S));
  for (PetscInt i = 0; i < L->nnodes; i++) {
    PetscInt    rows[3];
    PetscScalar Tv[9];

    for (PetscInt r = 0; r < 3; r++) rows[r] = nf->rstart + L->dofs[3 * i + r];
    for (PetscInt k = 0; k < 9; k++) Tv[k] = ig * T[9 * i + k];
    for (PetscInt r = 0; r < 3 && nf->touched[i]; r++) Tv[4 * r] += ig * SSSTAR_FREE_SHIFT; /* known rows: replaced below */
    PetscCall(MatSetValues(nf->M, 3, rows, 3, rows, Tv, ADD_VALUES));
  }
  PetscCall(MatAssemblyBegin(nf->M, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(nf->M, MAT_FINAL_ASSEMBLY));
  if (nf->nearNull) PetscCall(MatSetNearNullSpace(nf->M, nf->nearNull));
  PetscCall(VecCopy(y, nf->rhs));
  PetscCall(VecScale(nf->rhs, ig));
  PetscCall(MatZeroRowsColumns(nf->M, nf->nknown, nf->known, ig, y, nf->rhs));
  PetscCall(MPIU_Allreduce(&sym, symmetric, 1, MPIU_BOOL, MPI_LAND, PetscObjectComm((PetscObject)nt->A)));
  PetscFunctionReturn(0);
}

/* Keep the multigrid of an earlier step while at most pcReuse of the nodes changed their known rows since */
static PetscErrorCode ChoosePreconditioner(SSStarNewton nt, PetscBool *reuse)
{
  Newton_Full               *nf      = (Newton_Full *)nt->data;
  const SSStarContactLayout *L       = &nt->layout;
  const PetscInt             nfree   = L->kernel ? L->kernel->nfree : 0;
  PetscInt                   changed = 0;

  PetscFunctionBegin;
  for (PetscInt i = 0; i < L->nnodes; i++) changed += nf->mask[i] != nf->pcMask[i];
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &changed, 1, MPIU_INT, MPI_SUM, PetscObjectComm((PetscObject)nt->A)));
  /* the shift of free motions changes the matrix of the multigrid: a new one when they change */
  *reuse = (PetscBool)(nf->pcBuilt && changed <= nt->pcReuse * nf->nnodesGlobal && nfree == nf->pcFree);
  if (!*reuse) {
    PetscCall(PetscArraycpy(nf->pcMask, nf->mask, L->nnodes));
    nf->pcBuilt = PETSC_TRUE;
    nf->pcFree  = nfree;
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode SSStarNewtonSolve_Full(SSStarNewton nt, const PetscReal S[], const PetscReal T[], Vec y, Vec du, PetscBool *solved)
{
  Newton_Full       *nf  = (Newton_Full *)nt->data;
  KSP                ksp = nt->snes->ksp;
  KSPConvergedReason reason;
  Mat                op;
  PetscBool          symmetric, reuse;
  PetscInt           its;
  PetscReal          rnorm, bnorm;

  PetscFunctionBegin;
  PetscCall(PetscLogEventBegin(SSSTAR_NewtonAssemble, nt->snes, 0, 0, 0));
  PetscCall(AssembleNewtonMatrix(nt, S, T, y, &symmetric));
  PetscCall(PetscLogEventEnd(SSSTAR_NewtonAssemble, nt->snes, 0, 0, 0));
  if (!nf->userKSPType) { /* the residual unpreconditioned, in the units of the tolerances */
    PetscCall(KSPSetType(ksp, symmetric ? KSPCG : KSPGMRES));
    PetscCall(KSPSetPCSide(ksp, symmetric ? PC_LEFT : PC_RIGHT));
    PetscCall(KSPSetNormType(ksp, KSP_NORM_UNPRECONDITIONED));
    if (!symmetric && !nf->userRestart) PetscCall(KSPGMRESSetRestart(ksp, SSSTAR_GMRES_RESTART));
  }
  if (!nf->userTolerances) PetscCall(KSPSetTolerances(ksp, nt->rtol, nt->atol, PETSC_DEFAULT, PETSC_DEFAULT));
  PetscCall(ChoosePreconditioner(nt, &reuse));
  PetscCall(KSPSetReusePreconditioner(ksp, reuse));
  PetscCall(KrylovOperator(nt, &op));
  PetscCall(KSPSetOperators(ksp, op, nf->M));
  PetscCall(PetscLogEventBegin(SSSTAR_NewtonFactor, nt->snes, 0, 0, 0));
  PetscCall(KSPSetUp(ksp));
  PetscCall(PetscLogEventEnd(SSSTAR_NewtonFactor, nt->snes, 0, 0, 0));
  if (reuse) nt->nReused++;
  else nt->nFactor++;
  PetscCall(PetscLogEventBegin(SSSTAR_NewtonKrylov, nt->snes, 0, 0, 0));
  PetscCall(KSPSolve(ksp, nf->rhs, nf->dv));
  PetscCall(PetscLogEventEnd(SSSTAR_NewtonKrylov, nt->snes, 0, 0, 0));
  PetscCall(KSPGetConvergedReason(ksp, &reason));
  PetscCall(KSPGetIterationNumber(ksp, &its));
  nt->nKrylov += its;
  nt->snes->linear_its += its;
  /* an iteration limit that still reduced the residual tenfold is an inexact step; a breakdown is a failure */
  PetscCall(KSPGetResidualNorm(ksp, &rnorm));
  PetscCall(VecNorm(nf->rhs, NORM_2, &bnorm));
  *solved       = (PetscBool)(reason > 0 || (reason == KSP_DIVERGED_ITS && rnorm <= 0.1 * bnorm));
  nf->refinable = *solved;
  if (!*solved) {
    nf->pcBuilt = PETSC_FALSE;
    PetscCall(PetscInfo(nt->snes, "Newton step on the whole body not solved: %s after %" PetscInt_FMT " iterations, residual %g of %g\n", KSPConvergedReasons[reason], its, (double)rnorm, (double)bnorm));
    PetscFunctionReturn(0);
  }
  if (nf->Qt) PetscCall(MatMult(nf->Qt, nf->dv, du));
  else PetscCall(VecCopy(nf->dv, du));
  PetscFunctionReturn(0);
}

/* Every contact dof known (S = 0, T = I): the free dofs follow into equilibrium */
static PetscErrorCode SSStarNewtonSolveKnown_Full(SSStarNewton nt, Vec y, Vec du, PetscBool *solved)
{
  Newton_Full *nf = (Newton_Full *)nt->data;

  PetscFunctionBegin;
  PetscCall(SSStarNewtonSolve_Full(nt, nf->Sknown, nf->Tknown, y, du, solved));
  nf->refinable = PETSC_FALSE;
  PetscFunctionReturn(0);
}

/*
   The last step's Krylov solve continued from its solution (same matrix, right-hand side and multigrid) to the
   tolerances set since, unless it met them already or the user fixed the tolerances (-ksp_rtol)
*/
static PetscErrorCode SSStarNewtonRefine_Full(SSStarNewton nt, Vec du, PetscBool *refined)
{
  Newton_Full       *nf  = (Newton_Full *)nt->data;
  KSP                ksp = nt->snes->ksp;
  KSPConvergedReason reason;
  PetscInt           its;
  PetscReal          rnorm, bnorm;

  PetscFunctionBegin;
  if (!nf->refinable || nf->userTolerances) PetscFunctionReturn(0);
  PetscCall(KSPGetResidualNorm(ksp, &rnorm));
  PetscCall(VecNorm(nf->rhs, NORM_2, &bnorm));
  if (rnorm <= PetscMax(nt->atol, nt->rtol * bnorm)) PetscFunctionReturn(0);
  PetscCall(KSPSetTolerances(ksp, nt->rtol, nt->atol, PETSC_DEFAULT, PETSC_DEFAULT));
  PetscCall(KSPSetInitialGuessNonzero(ksp, PETSC_TRUE));
  PetscCall(PetscLogEventBegin(SSSTAR_NewtonKrylov, nt->snes, 0, 0, 0));
  PetscCall(KSPSolve(ksp, nf->rhs, nf->dv));
  PetscCall(PetscLogEventEnd(SSSTAR_NewtonKrylov, nt->snes, 0, 0, 0));
  PetscCall(KSPSetInitialGuessNonzero(ksp, PETSC_FALSE));
  PetscCall(KSPGetConvergedReason(ksp, &reason));
  PetscCall(KSPGetIterationNumber(ksp, &its));
  nt->nKrylov += its;
  nt->snes->linear_its += its;
  *refined = (PetscBool)(reason > 0 || reason == KSP_DIVERGED_ITS);
  if (!*refined) {
    nf->refinable = PETSC_FALSE;
    PetscCall(PetscInfo(nt->snes, "Newton step on the whole body not refined: %s after %" PetscInt_FMT " iterations\n", KSPConvergedReasons[reason], its));
    PetscFunctionReturn(0);
  }
  if (nf->Qt) PetscCall(MatMult(nf->Qt, nf->dv, du));
  else PetscCall(VecCopy(nf->dv, du));
  PetscFunctionReturn(0);
}

static PetscErrorCode SSStarNewtonView_Full(SSStarNewton nt, PetscViewer viewer)
{
  Newton_Full *nf = (Newton_Full *)nt->data;

  PetscFunctionBegin;
  PetscCall(PetscViewerASCIIPrintf(viewer, "  Newton step on the whole body (P never formed): K with each contact node's rows, known dofs eliminated, solved by the KSP below%s\n", nf->nearNull ? " (multigrid with K's near-null space)" : ""));
  PetscCall(PetscViewerASCIIPrintf(viewer, "    the multigrid of an earlier step is kept while at most %g%% of the nodes changed their known rows\n", (double)(100 * nt->pcReuse)));
  if (nt->nSteps) PetscCall(PetscViewerASCIIPrintf(viewer, "    last solve: %" PetscInt_FMT " linear solves, %" PetscInt_FMT " Krylov iterations (%.1f per solve), %" PetscInt_FMT " preconditioner set-ups, %" PetscInt_FMT " solves on an earlier one, %" PetscInt_FMT " inexact steps solved on to the floor after a failed full step\n", nt->nSteps, nt->nKrylov, (double)nt->nKrylov / nt->nSteps, nt->nFactor, nt->nReused, nt->nRefined));
  PetscFunctionReturn(0);
}

static PetscErrorCode SSStarNewtonReset_Full(SSStarNewton nt)
{
  Newton_Full *nf = (Newton_Full *)nt->data;

  PetscFunctionBegin;
  PetscCall(MatDestroy(&nf->Kr));
  PetscCall(MatDestroy(&nf->Qt));
  PetscCall(MatDestroy(&nf->Shat));
  PetscCall(MatDestroy(&nf->M));
  PetscCall(MatNullSpaceDestroy(&nf->nearNull));
  PetscCall(VecDestroy(&nf->rhs));
  PetscCall(VecDestroy(&nf->dv));
  PetscCall(PetscFree3(nf->known, nf->mask, nf->touched));
  PetscCall(MatDestroy(&nf->shell));
  PetscCall(PetscFree(nf->pcMask));
  PetscCall(PetscFree2(nf->Sknown, nf->Tknown));
  for (PetscInt k = 0; k < SSSTAR_SMOOTHER_OPTIONS; k++) {
    if (nf->smoother[k]) PetscCall(PetscOptionsClearValue(((PetscObject)nt->snes->ksp)->options, nf->smoother[k]));
    PetscCall(PetscFree(nf->smoother[k]));
  }
  PetscCall(KSPReset(nt->snes->ksp));
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarNewtonCreate_Full(SSStarNewton nt)
{
  Newton_Full *nf;

  PetscFunctionBegin;
  nt->snes->usesksp = PETSC_TRUE; /* the SNES's KSP solves the Newton systems */
  PetscCall(PetscNew(&nf));
  nt->data           = nf;
  nt->ops.setup      = SSStarNewtonSetUp_Full;
  nt->ops.setscaling = SSStarNewtonSetScaling_Full;
  nt->ops.solve      = SSStarNewtonSolve_Full;
  nt->ops.solveknown = SSStarNewtonSolveKnown_Full;
  nt->ops.refine     = SSStarNewtonRefine_Full;
  nt->ops.view       = SSStarNewtonView_Full;
  nt->ops.reset      = SSStarNewtonReset_Full;
  PetscFunctionReturn(0);
}
