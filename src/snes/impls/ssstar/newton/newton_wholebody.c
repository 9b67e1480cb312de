/*
   The Newton step on the whole body, P never formed (reduction none). With Q the rotation into the nodes' frames at
   the contact dofs (identity elsewhere), K' = Q K Q^T and dv = Q du, the system of newtonimpl.h divided by gamma is

     free dof j:      (K' dv)_j                               = y_j / gamma
     contact node i:  S_i (K' dv)_i + T_i dv_i / gamma        = y_i / gamma

   i.e. M = Shat K' + That / gamma with Shat = blockdiag(S_i, 1), That = blockdiag(T_i, 0). The rows with S row = 0 and
   T row = e_r (sticking nodes, the normal of a node in contact) say dv = y: they are eliminated symmetrically
   (MatZeroRowsColumns, unit rows scaled by 1/gamma). Interior and separated rows are K's; a sliding node's tangential
   rows add phi om times its normal row of K' and W/gamma (docs/derivation.md section 5): the only unsymmetric part. M
   differs from K only in the contact rows and columns: it is formed in K's own storage for each linear solve and K is
   put back after it (wholebodymatrix.c), so the step holds no copy of K. The system is solved by the SNES's KSP: CG where
   it is symmetric, GMRES (right preconditioned) where it is not, both preconditioned by algebraic multigrid (PCGAMG
   with K's near-null space, the rigid-body modes, rotated like K'), to the tolerances the iteration sets (inexact
   Newton). The multigrid of an earlier step is kept while few nodes changed their known rows, and built anew
   (its coarse operators) when more did.

   Floating bodies (docs/derivation.md (14.5)): where the step's states leave rigid-body motions U free, the Krylov
   solver runs on M + Shat (c/gamma) U U^T (a shell: M and the low-rank term), preconditioned by the multigrid of M
   with a small shift on the free motions' unknown contact dofs, which makes it regular: the preconditioned Newton matrix
   has one outlier eigenvalue per free motion, which the Krylov iteration removes in about as many iterations.
*/
#include "newtonimpl.h"
#include "../../../../sys/meminfo.h"

/* GMRES's restart when ssstar chooses GMRES: restarts stall it on the hard steps, and its basis is affordable */
#define SSSTAR_GMRES_RESTART 100
/* GAMG's smoothers unless the options name others: one sweep of SOR per level and direction (bench/levers.py) */
#define SSSTAR_SMOOTHER_OPTIONS 4
/* floating bodies: the preconditioner's shift on the free motions' unknown contact dofs, in units of 1/gamma */
#define SSSTAR_FREE_SHIFT (1e-2 * SSSTAR_FREE_STIFFNESS)

typedef struct {
  SSStarWholeBodyMatrix wm;          /* the Newton matrix in K's storage                                              */
  MatNullSpace     nearNull;    /* K's near-null space in the nodes' frames, or NULL                             */
  Vec              rhs, dv;     /* of the step, dv = Q du                                                        */
  PetscInt         rstart;      /* first row of K on this rank                                                   */
  PetscInt         nknown, *known; /* global rows of the known dofs of the step                                  */
  unsigned char   *mask, *pcMask; /* per local node: bits of its unknown rows, now and when the multigrid was built */
  PetscReal       *S, *T;       /* the blocks of the last step (SSStarNewtonRefine forms its matrix again)        */
  PetscBool        pcBuilt;
  PetscBool        refinable;   /* the KSP holds the last step's solution (SSStarNewtonRefine)                   */
  PetscInt         nnodesGlobal;
  PetscBool        userKSPType, userTolerances, userRestart;
  PetscBool        plain, wCycle, allAtOnce; /* ssstar's multigrid choices in effect (the options did not choose) */
  PetscBool        plainAggregation; /* the multigrid aggregates plainly: ssstar's choice or the options'         */
  PetscBool        plainBySize;      /* ssstar's choice of plain aggregation was by K's size, not by the memory     */
  PetscBool        byEstimate;       /* the memory's verdict was the caller's estimate's (SNESSSStarSetSmoothedAggregationFits()) */
  PetscReal       *Sknown, *Tknown; /* S = 0, T = I per node: every contact dof known                            */
  char            *smoother[SSSTAR_SMOOTHER_OPTIONS]; /* the options database entries ssstar set, cleared at reset  */
  Mat              M;           /* the Newton matrix of the step, while it is formed (SSStarWholeBodyMatrixForm)        */
  Mat              shell;       /* floating bodies: M + the proximal term on the step's free motions             */
  unsigned char   *touched;     /* per local node: a free motion of the step moves it                            */
  PetscInt         pcFree;      /* free motions when the multigrid was built                                     */
  PetscInt         indefinite;  /* steps CG stopped on with DIVERGED_INDEFINITE_PC since the set-up: GMRES since  */
  PetscReal        ocScale;     /* the interpolations into the ocLevels finest levels are scaled by it (1: as built) */
  PetscInt         ocLevels, wLevels; /* the levels scaled; the finest levels W-cycled by ssstar's choice             */
} Newton_WholeBody;

/* dv = Q du: each contact node's 3 entries of a vector of K turned into its frame (R NULL: nothing to do) */
static PetscErrorCode RotateToFrames(const SSStarContactLayout *L, Vec v)
{
  PetscScalar *a;

  PetscFunctionBegin;
  if (!L->frames) PetscFunctionReturn(0);
  PetscCall(VecGetArray(v, &a));
  for (PetscInt i = 0; i < L->nnodes; i++) {
    const PetscReal *R = &L->frames[9 * i];
    const PetscInt  *d = &L->dofs[3 * i];
    const PetscScalar x[3] = {a[d[0]], a[d[1]], a[d[2]]};

    for (PetscInt k = 0; k < 3; k++) a[d[k]] = R[3 * k] * x[0] + R[3 * k + 1] * x[1] + R[3 * k + 2] * x[2];
  }
  PetscCall(VecRestoreArray(v, &a));
  PetscFunctionReturn(0);
}

/* du = Q^T dv */
static PetscErrorCode RotateBack(const SSStarContactLayout *L, Vec dv, Vec du)
{
  PetscScalar *a;

  PetscFunctionBegin;
  PetscCall(VecCopy(dv, du));
  if (!L->frames) PetscFunctionReturn(0);
  PetscCall(VecGetArray(du, &a));
  for (PetscInt i = 0; i < L->nnodes; i++) {
    const PetscInt   *d = &L->dofs[3 * i];
    const PetscScalar y[3] = {a[d[0]], a[d[1]], a[d[2]]};
    PetscScalar       x[3];

    SSStarRotateBack(&L->frames[9 * i], y, x);
    for (PetscInt k = 0; k < 3; k++) a[d[k]] = x[k];
  }
  PetscCall(VecRestoreArray(du, &a));
  PetscFunctionReturn(0);
}

/* K's near-null space (the rigid-body modes a scene attaches to K), rotated like K' */
static PetscErrorCode CreateNearNullSpace(SSStarNewton nt)
{
  Newton_WholeBody *nw = (Newton_WholeBody *)nt->data;
  MatNullSpace nsp;
  PetscBool    hasConstant;
  PetscInt     n;
  const Vec   *vecs;
  Vec         *rotated;

  PetscFunctionBegin;
  PetscCall(MatGetNearNullSpace(nt->A, &nsp));
  if (!nsp) PetscFunctionReturn(0);
  PetscCall(MatNullSpaceGetVecs(nsp, &hasConstant, &n, &vecs));
  PetscCall(PetscMalloc1(n, &rotated));
  for (PetscInt k = 0; k < n; k++) {
    PetscCall(VecDuplicate(vecs[k], &rotated[k]));
    PetscCall(VecCopy(vecs[k], rotated[k]));
    PetscCall(RotateToFrames(&nt->layout, rotated[k]));
  }
  PetscCall(MatNullSpaceCreate(PetscObjectComm((PetscObject)nt->A), hasConstant, n, rotated, &nw->nearNull));
  for (PetscInt k = 0; k < n; k++) PetscCall(VecDestroy(&rotated[k]));
  PetscCall(PetscFree(rotated));
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
  Newton_WholeBody *nw = (Newton_WholeBody *)nt->data;
  PetscOptions options = NULL; /* PCMG's levels read the default database, whatever the PC's */
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
    PetscCall(PetscStrallocpy(name, &nw->smoother[k]));
  }
  PetscFunctionReturn(0);
}

/*
   Unless the options name the smoothing steps: plain aggregation (-pc_gamg_agg_nsmooths 0), whose interpolation has a
   sixth of the entries, with W-cycles and the products all at once (CycleDefaults, GalerkinProductBegin), on K of at
   least -snes_ssstar_plain_aggregation_dofs dofs or where the smoothed set-up would not fit the memory the SNES may plan
   for (-snes_ssstar_memory_limit, else MemAvailable): prism level 24 on 2 ranks, the peak 0.890 GB per rank instead of
   1.56, as many Krylov iterations (docs/guide/scale.md). Smoothed aggregation (GAMG's default) below that size: fewer
   Krylov iterations on small and soft bodies, where its memory does not matter. Whether the smoothed one fits is the
   caller's estimate before the work where it gave one (SNESSSStarSetSmoothedAggregationFits(): the scenes' printed
   estimate), one verdict for every set-up of every solve; else judged here from the rank's resident memory now, which
   also holds what was freed and not given back (a nested start's coarse solves: prism level 12 on 2 ranks, 0.19 GB
   resident where 0.13 is in use), so that it takes plain aggregation more often than the estimate would
*/
static PetscErrorCode ChooseAggregation(SSStarNewton nt, PC pc)
{
  Newton_WholeBody *nw = (Newton_WholeBody *)nt->data;
  SNES_SSStar      *ss = (SNES_SSStar *)nt->snes->data;
  PetscBool         isgamg, set, fits;
  PetscInt          m, M, nsmooths = 1;
  PetscMPIInt       size;
  PetscLogDouble    now = 0;

  PetscFunctionBegin;
  nw->plain = nw->plainAggregation = nw->plainBySize = nw->byEstimate = PETSC_FALSE;
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCGAMG, &isgamg));
  if (!isgamg) PetscFunctionReturn(0);
  PetscCall(PetscOptionsGetInt(((PetscObject)pc)->options, ((PetscObject)pc)->prefix, "-pc_gamg_agg_nsmooths", &nsmooths, &set));
  nw->plainAggregation = (PetscBool)(set && nsmooths == 0);
  if (set) PetscFunctionReturn(0);
  PetscCall(MatGetSize(nt->A, &M, NULL));
  if (nt->plainDofs >= 0 && M >= nt->plainDofs) {
    PetscCall(PCGAMGSetNSmooths(pc, 0));
    nw->plain = nw->plainAggregation = nw->plainBySize = PETSC_TRUE;
    PetscFunctionReturn(0);
  }
  if (nt->smoothedFits >= 0) {
    fits           = (PetscBool)nt->smoothedFits;
    nw->byEstimate = PETSC_TRUE;
  } else {
    PetscCall(MatGetLocalSize(nt->A, &m, NULL));
    PetscCallMPI(MPI_Comm_size(PetscObjectComm((PetscObject)pc), &size));
    /* a limit per rank bounds the peak: what the rank holds now counts; MemAvailable already leaves it out */
    if (ss->problem.memoryLimit > 0) PetscCall(PetscMemoryGetCurrentUsage(&now));
    PetscCall(SSStarReductionFitsMemory(PetscObjectComm((PetscObject)pc), ss->problem.memoryLimit, now, SSSTAR_SOLVE_BYTES(size, PETSC_FALSE) * m, &fits));
  }
  if (fits) PetscFunctionReturn(0);
  PetscCall(PCGAMGSetNSmooths(pc, 0));
  nw->plain = nw->plainAggregation = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/*
   With plain aggregation, GAMG's Galerkin products P^T A P all at once (-matptap_via allatonce) unless the options
   choose: PETSc's default for several ranks keeps A P, rows of A by the columns of P, through the set-up and for the
   next one (bench/memory.py: level 16 on 2 ranks, 59 MB per rank where the all-at-once product holds 11). MatPtAP()
   reads the option from the default database, for any product of the program: it is there only while the multigrid is
   set up. One rank's products (SeqAIJ) hold no A P and have no such algorithm.
*/
static PetscErrorCode GalerkinProductBegin(PC pc, PetscBool plain, PetscBool *set)
{
  PetscBool   given;
  PetscMPIInt size;

  PetscFunctionBegin;
  *set = PETSC_FALSE;
  PetscCall(PetscOptionsHasName(NULL, NULL, "-matptap_via", &given));
  PetscCallMPI(MPI_Comm_size(PetscObjectComm((PetscObject)pc), &size));
  if (!plain || given || size == 1) PetscFunctionReturn(0);
  PetscCall(PetscOptionsSetValue(NULL, "-matptap_via", "allatonce"));
  *set = PETSC_TRUE;
  PetscFunctionReturn(0);
}

static PetscErrorCode GalerkinProductEnd(PetscBool set)
{
  PetscFunctionBegin;
  if (set) PetscCall(PetscOptionsClearValue(NULL, "-matptap_via"));
  PetscFunctionReturn(0);
}

/*
   With plain aggregation, a W-cycle on the -snes_ssstar_mg_w_levels finest levels of GAMG's hierarchy (each visits the next
   coarser level twice), a V-cycle below, unless the options name the cycle (-pc_mg_cycle_type): plain aggregation's
   piecewise rigid interpolation needs the second coarse correction (prism level 16, 2 ranks: 86 Krylov iterations on
   the finest mesh with V-cycles, 55 with these, 57 for smoothed aggregation with V-cycles, in fewer flops than either);
   on the coarser levels it adds messages, not iterations (59 with W-cycles on all six levels). Their coarse corrections
   are then over-corrected (ScaleCoarseCorrections)
*/
static PetscErrorCode CycleDefaults(PC pc, PetscBool plain, PetscInt wLevels, PetscBool *wCycle)
{
  PetscBool set;
  PetscInt  nlevels;

  PetscFunctionBegin;
  *wCycle = PETSC_FALSE;
  PetscCall(PetscOptionsHasName(((PetscObject)pc)->options, ((PetscObject)pc)->prefix, "-pc_mg_cycle_type", &set));
  if (!plain || set) PetscFunctionReturn(0);
  PetscCall(PCMGGetLevels(pc, &nlevels));
  for (PetscInt l = 1; l < nlevels; l++) PetscCall(PCMGSetCycleTypeOnLevel(pc, l, l >= nlevels - wLevels ? PC_MG_CYCLE_W : PC_MG_CYCLE_V));
  *wCycle = (PetscBool)(wLevels > 0);
  PetscFunctionReturn(0);
}

/*
   The interpolations into the wLevels finest levels scaled by s, after GAMG's set-up (the coarse operators stay
   the Galerkin ones of the interpolations as built): their coarse corrections P A_c^-1 P^T become s^2 times as large,
   the same on both sides, so the multigrid stays symmetric. Plain aggregation's piecewise rigid interpolation leaves the
   smooth error under-corrected; an over-correction of alpha = s^2 = -snes_ssstar_mg_overcorrection makes up for it
   (Vanek; Notay). Measured (docs/guide/scale.md, "The multigrid's rate"): prism level 24 on 2 ranks, 60 Krylov
   iterations on the finest mesh instead of 71, 11 % fewer flops, the same memory; on K alone 38 CG iterations instead
   of 55. On the V-cycled levels below it made CG's multigrid indefinite: only the W-cycled ones are scaled. A new set-up
   (GAMG's products on the interpolations it keeps) is preceded by the scaling back (1/s)
*/
static PetscErrorCode ScaleCoarseCorrections(PC pc, PetscInt wLevels, PetscReal s)
{
  PetscInt nlevels;

  PetscFunctionBegin;
  PetscCall(PCMGGetLevels(pc, &nlevels));
  for (PetscInt l = nlevels - 1; l >= 1 && l >= nlevels - wLevels; l--) {
    Mat P;

    PetscCall(PCMGGetInterpolation(pc, l, &P));
    PetscCall(MatScale(P, s));
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode SSStarNewtonSetUp_WholeBody(SSStarNewton nt)
{
  Newton_WholeBody               *nw  = (Newton_WholeBody *)nt->data;
  const SSStarContactLayout *L   = &nt->layout;
  KSP                        ksp = nt->snes->ksp;
  PC                         pc;
  PetscBool                  isgamg, set;

  PetscFunctionBegin;
  PetscCall(MatGetOwnershipRange(nt->A, &nw->rstart, NULL));
  PetscCall(MPIU_Allreduce(&L->nnodes, &nw->nnodesGlobal, 1, MPIU_INT, MPI_SUM, PetscObjectComm((PetscObject)nt->A)));
  PetscCall(SSStarWholeBodyMatrixCreate(nt->A, L, &nw->wm));
  PetscCall(CreateNearNullSpace(nt));
  PetscCall(MatCreateVecs(nt->A, &nw->dv, &nw->rhs));
  PetscCall(PetscMalloc3(3 * L->nnodes, &nw->known, L->nnodes, &nw->mask, L->nnodes, &nw->touched));
  PetscCall(PetscCalloc1(L->nnodes, &nw->pcMask));
  PetscCall(PetscMalloc4(9 * L->nnodes, &nw->Sknown, 9 * L->nnodes, &nw->Tknown, 9 * L->nnodes, &nw->S, 9 * L->nnodes, &nw->T));
  for (PetscInt i = 0; i < L->nnodes; i++)
    for (PetscInt k = 0; k < 9; k++) {
      nw->Sknown[9 * i + k] = 0;
      nw->Tknown[9 * i + k] = (PetscReal)(k % 4 == 0);
    }
  nw->pcBuilt    = PETSC_FALSE;
  nw->indefinite = 0;
  nw->ocScale    = 1;

  /* the SNES's KSP: GMRES or CG with GAMG unless the options name others (they are read again for the new types) */
  PetscCall(PetscOptionsHasName(((PetscObject)ksp)->options, ((PetscObject)ksp)->prefix, "-ksp_type", &nw->userKSPType));
  PetscCall(PetscOptionsHasName(((PetscObject)ksp)->options, ((PetscObject)ksp)->prefix, "-ksp_rtol", &nw->userTolerances));
  PetscCall(PetscOptionsHasName(((PetscObject)ksp)->options, ((PetscObject)ksp)->prefix, "-ksp_gmres_restart", &nw->userRestart));
  PetscCall(SSStarNewtonSetKSPDefaults(nt, KSPGMRES, PCGAMG));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCGAMG, &isgamg));
  PetscCall(PetscOptionsHasName(((PetscObject)pc)->options, ((PetscObject)pc)->prefix, "-pc_gamg_use_sa_esteig", &set));
  /* the smoothed aggregation's eigenvalue estimate made the Chebyshev smoothers unstable on these matrices (an
     indefinite preconditioner for an SPD Newton matrix, and GMRES 40 % slower): the smoothers estimate their own */
  if (isgamg && !set) PetscCall(PCGAMGSetUseSAEstEig(pc, PETSC_FALSE));
  PetscCall(ChooseAggregation(nt, pc));
  PetscCall(SetSmootherDefaults(nt, pc));
  PetscCall(KSPSetFromOptions(ksp));
  PetscFunctionReturn(0);
}

/* A new gamma changes the unit rows and W/gamma: the multigrid is built again */
static PetscErrorCode SSStarNewtonSetScaling_WholeBody(SSStarNewton nt)
{
  PetscFunctionBegin;
  ((Newton_WholeBody *)nt->data)->pcBuilt = PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* The nodes the step's free motions move (none without floating bodies) */
static PetscErrorCode MarkFreeMotions(SSStarNewton nt)
{
  Newton_WholeBody        *nw = (Newton_WholeBody *)nt->data;
  const SSStarFloating *fb = nt->layout.floating;
  const PetscInt      n3 = 3 * nt->layout.nnodes;

  PetscFunctionBegin;
  for (PetscInt i = 0; i < nt->layout.nnodes; i++) {
    nw->touched[i] = 0;
    for (PetscInt f = 0; fb && f < fb->nfree; f++)
      for (PetscInt r = 0; r < 3; r++)
        if (fb->free[f * n3 + 3 * i + r] != 0.0) nw->touched[i] = 1;
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
  Newton_WholeBody               *nw;
  const SSStarContactLayout *L;
  const SSStarFloating        *fb;
  const PetscScalar         *xa;
  PetscScalar               *ya;
  PetscReal                 *t;
  PetscInt                   n3;

  PetscFunctionBegin;
  PetscCall(MatShellGetContext(A, &nt));
  nw = (Newton_WholeBody *)nt->data;
  L  = &nt->layout;
  fb = L->floating;
  n3 = 3 * L->nnodes;
  PetscCall(MatMult(nw->M, x, y));
  PetscCall(PetscCalloc1(fb->nfree, &t));
  PetscCall(VecGetArrayRead(x, &xa));
  for (PetscInt f = 0; f < fb->nfree; f++)
    for (PetscInt d = 0; d < n3; d++) t[f] += fb->free[f * n3 + d] * PetscRealPart(xa[L->dofs[d]]);
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, t, fb->nfree, MPIU_REAL, MPIU_SUM, PetscObjectComm((PetscObject)A)));
  PetscCall(VecGetArray(y, &ya));
  for (PetscInt i = 0; i < L->nnodes; i++) {
    const PetscReal *S = &nw->S[9 * i];
    PetscReal        Ut[3] = {0, 0, 0};

    if (!nw->touched[i]) continue;
    for (PetscInt f = 0; f < fb->nfree; f++)
      for (PetscInt k = 0; k < 3; k++) Ut[k] += fb->free[f * n3 + 3 * i + k] * t[f];
    for (PetscInt r = 0; r < 3; r++) {
      const PetscInt d = L->dofs[3 * i + r];

      if (!(nw->mask[i] & (1 << r))) continue;
      ya[d] += (S[3 * r] * Ut[0] + S[3 * r + 1] * Ut[1] + S[3 * r + 2] * Ut[2]) * SSSTAR_FREE_STIFFNESS / nt->gamma - SSSTAR_FREE_SHIFT / nt->gamma * xa[d];
    }
  }
  PetscCall(VecRestoreArray(y, &ya));
  PetscCall(VecRestoreArrayRead(x, &xa));
  PetscCall(PetscFree(t));
  PetscFunctionReturn(0);
}

/* The Newton matrix the Krylov solver applies: M, or the shell of MultFree when the step leaves motions free */
static PetscErrorCode KrylovNewtonMatrix(SSStarNewton nt, Mat *A)
{
  Newton_WholeBody *nw = (Newton_WholeBody *)nt->data;
  PetscInt     m, N;

  PetscFunctionBegin;
  *A = nw->M;
  if (!nt->layout.floating || !nt->layout.floating->nfree) PetscFunctionReturn(0);
  if (!nw->shell) {
    PetscCall(MatGetLocalSize(nw->M, &m, NULL));
    PetscCall(MatGetSize(nw->M, &N, NULL));
    PetscCall(MatCreateShell(PetscObjectComm((PetscObject)nw->M), m, m, N, N, nt, &nw->shell));
    PetscCall(MatShellSetOperation(nw->shell, MATOP_MULT, (void (*)(void))MultFree));
  }
  *A = nw->shell;
  PetscFunctionReturn(0);
}

/*
   M, rhs = y / gamma with the known dofs eliminated, and whether M is symmetric: it is unless some unknown row
   combines K's rows (S row other than e_r: the sliding law's phi om) or T is unsymmetric on the unknown dofs
*/
static PetscErrorCode AssembleNewtonMatrix(SSStarNewton nt, const PetscReal S[], const PetscReal T[], Vec y, Mat *M, PetscBool *symmetric)
{
  Newton_WholeBody               *nw  = (Newton_WholeBody *)nt->data;
  const SSStarContactLayout *L   = &nt->layout;
  const PetscReal            ig  = 1 / nt->gamma;
  PetscBool                  sym = PETSC_TRUE;

  PetscFunctionBegin;
  nw->nknown = 0;
  for (PetscInt i = 0; i < L->nnodes; i++) {
    const PetscReal *Si = &S[9 * i], *Ti = &T[9 * i];

    nw->mask[i] = 0;
    for (PetscInt r = 0; r < 3; r++) {
      if (SSStarKnownRow(Si, Ti, r)) nw->known[nw->nknown++] = nw->rstart + L->dofs[3 * i + r];
      else nw->mask[i] |= (unsigned char)(1 << r);
    }
    for (PetscInt r = 0; r < 3; r++) {
      if (!(nw->mask[i] & (1 << r))) continue;
      for (PetscInt k = 0; k < 3; k++) {
        if (Si[3 * r + k] != (PetscReal)(k == r)) sym = PETSC_FALSE;
        if ((nw->mask[i] & (1 << k)) && Ti[3 * r + k] != Ti[3 * k + r]) sym = PETSC_FALSE;
      }
    }
  }
  PetscCall(PetscArraycpy(nw->S, S, 9 * L->nnodes));
  PetscCall(PetscArraycpy(nw->T, T, 9 * L->nnodes));
  PetscCall(MarkFreeMotions(nt));
  for (PetscInt i = 0; i < L->nnodes; i++) /* the preconditioner's shift (known rows: eliminated) */
    for (PetscInt r = 0; r < 3 && nw->touched[i]; r++) nw->T[9 * i + 4 * r] += SSSTAR_FREE_SHIFT;
  PetscCall(VecCopy(y, nw->rhs));
  PetscCall(VecScale(nw->rhs, ig));
  PetscCall(SSStarWholeBodyMatrixForm(nw->wm, nw->S, nw->T, ig, nw->nknown, nw->known, y, nw->rhs, M));
  nw->M = *M;
  PetscCall(MPIU_Allreduce(&sym, symmetric, 1, MPIU_BOOL, MPI_LAND, PetscObjectComm((PetscObject)nt->A)));
  PetscFunctionReturn(0);
}

/* Keep the multigrid of an earlier step while at most pcReuse of the nodes changed their known rows since */
static PetscErrorCode ChoosePreconditioner(SSStarNewton nt, PetscBool *reuse)
{
  Newton_WholeBody               *nw      = (Newton_WholeBody *)nt->data;
  const SSStarContactLayout *L       = &nt->layout;
  const PetscInt             nfree   = L->floating ? L->floating->nfree : 0;
  PetscInt                   changed = 0;

  PetscFunctionBegin;
  for (PetscInt i = 0; i < L->nnodes; i++) changed += nw->mask[i] != nw->pcMask[i];
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &changed, 1, MPIU_INT, MPI_SUM, PetscObjectComm((PetscObject)nt->A)));
  /* the shift of free motions changes the matrix of the multigrid: a new one when they change */
  *reuse = (PetscBool)(nw->pcBuilt && changed <= nt->pcReuse * nw->nnodesGlobal && nfree == nw->pcFree);
  if (!*reuse) {
    PetscCall(PetscArraycpy(nw->pcMask, nw->mask, L->nnodes));
    nw->pcBuilt = PETSC_TRUE;
    nw->pcFree  = nfree;
  }
  PetscFunctionReturn(0);
}

/* The multigrid for M (a new one or an earlier one kept), built with K's near-null space in the nodes' frames */
static PetscErrorCode SetUpPreconditioner(SSStarNewton nt, Mat M, PetscBool reuse)
{
  Newton_WholeBody *nw  = (Newton_WholeBody *)nt->data;
  KSP          ksp = nt->snes->ksp;
  MatNullSpace own = NULL;
  Mat          op;
  PC           pc;
  PetscBool    allAtOnce;
  PetscLogDouble t0, t1;

  PetscFunctionBegin;
  PetscCall(PetscTime(&t0));
  PetscCall(KSPSetReusePreconditioner(ksp, reuse));
  PetscCall(KrylovNewtonMatrix(nt, &op));
  PetscCall(KSPSetOperators(ksp, op, M));
  if (nw->nearNull) { /* M is K's storage: its own near-null space goes back after the set-up */
    PetscCall(MatGetNearNullSpace(M, &own));
    PetscCall(PetscObjectReference((PetscObject)own));
    PetscCall(MatSetNearNullSpace(M, nw->nearNull));
  }
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PetscLogEventBegin(SSSTAR_NewtonFactor, nt->snes, 0, 0, 0));
  if (!reuse && nw->ocScale != 1) { /* GAMG's products of a new set-up take the interpolations as they were built */
    PetscCall(ScaleCoarseCorrections(pc, nw->ocLevels, 1 / nw->ocScale));
    nw->ocScale = 1;
  }
  PetscCall(GalerkinProductBegin(pc, nw->plainAggregation, &allAtOnce));
  PetscCall(KSPSetUp(ksp));
  PetscCall(GalerkinProductEnd(allAtOnce));
  if (!reuse) { /* the levels of a new hierarchy */
    PetscCall(CycleDefaults(pc, nw->plainAggregation, nt->wLevels, &nw->wCycle));
    nw->wLevels = nt->wLevels;
    nw->allAtOnce = allAtOnce;
    if (nw->wCycle && nt->overCorrection != 1) {
      nw->ocScale  = PetscSqrtReal(nt->overCorrection);
      nw->ocLevels = nt->wLevels;
      PetscCall(ScaleCoarseCorrections(pc, nw->ocLevels, nw->ocScale));
    }
  }
  PetscCall(PetscLogEventEnd(SSSTAR_NewtonFactor, nt->snes, 0, 0, 0));
  if (nw->nearNull) {
    PetscCall(MatSetNearNullSpace(M, own));
    PetscCall(MatNullSpaceDestroy(&own));
  }
  if (reuse) nt->nReused++;
  else nt->nFactor++;
  PetscCall(PetscTime(&t1));
  if (!reuse) nt->factorSeconds += t1 - t0;
  PetscFunctionReturn(0);
}

/* The Krylov solve of the step from dv (nonzero: on from the last solution), du = Q^T dv; K is put back after it */
static PetscErrorCode KrylovSolve(SSStarNewton nt, PetscBool nonzero, Vec du, KSPConvergedReason *reason, PetscInt *its)
{
  Newton_WholeBody *nw  = (Newton_WholeBody *)nt->data;
  KSP          ksp = nt->snes->ksp;

  PetscFunctionBegin;
  PetscCall(KSPSetInitialGuessNonzero(ksp, nonzero));
  PetscCall(PetscLogEventBegin(SSSTAR_NewtonKrylov, nt->snes, 0, 0, 0));
  PetscCall(KSPSolve(ksp, nw->rhs, nw->dv));
  PetscCall(PetscLogEventEnd(SSSTAR_NewtonKrylov, nt->snes, 0, 0, 0));
  PetscCall(KSPSetInitialGuessNonzero(ksp, PETSC_FALSE));
  PetscCall(SSStarWholeBodyMatrixRestore(nw->wm));
  PetscCall(KSPGetConvergedReason(ksp, reason));
  PetscCall(KSPGetIterationNumber(ksp, its));
  nt->nKrylov += *its;
  nt->snes->linear_its += *its;
  if (*reason > 0 || *reason == KSP_DIVERGED_ITS) PetscCall(RotateBack(&nt->layout, nw->dv, du));
  PetscFunctionReturn(0);
}

/*
   CG stopped with DIVERGED_INDEFINITE_PC: the multigrid of a Newton matrix that is positive definite is not always so
   (GAMG's smoothers on the frictionless stack of floating bodies on 4 ranks: the residual grew after 8 iterations). CG
   needs a definite preconditioner, GMRES does not: the step is solved again by GMRES (right preconditioned, the
   residual unpreconditioned as before) on the same multigrid, and every later step with this stiffness too. The same
   for DIVERGED_INDEFINITE_MAT: the Newton matrix itself is indefinite (the tangent of a Saint Venant-Kirchhoff body
   compressed past its limit point, docs/derivation.md section 18), which CG cannot solve and GMRES can
*/
static PetscErrorCode IndefiniteFallback(SSStarNewton nt, Vec du, KSPConvergedReason *reason, PetscInt *its)
{
  Newton_WholeBody *nw  = (Newton_WholeBody *)nt->data;
  KSP               ksp = nt->snes->ksp;
  PetscInt          cgIts = *its;
  KSPConvergedReason cgReason = *reason;

  PetscFunctionBegin;
  nw->indefinite++;
  PetscCall(KSPSetType(ksp, KSPGMRES));
  PetscCall(KSPSetPCSide(ksp, PC_RIGHT));
  PetscCall(KSPSetNormType(ksp, KSP_NORM_UNPRECONDITIONED));
  if (!nw->userRestart) PetscCall(KSPGMRESSetRestart(ksp, SSSTAR_GMRES_RESTART));
  PetscCall(KSPSetReusePreconditioner(ksp, PETSC_TRUE)); /* the multigrid CG was given, for the matrix formed again */
  PetscCall(SSStarWholeBodyMatrixForm(nw->wm, nw->S, nw->T, 1 / nt->gamma, nw->nknown, nw->known, NULL, NULL, &nw->M));
  PetscCall(KrylovSolve(nt, PETSC_FALSE, du, reason, its));
  PetscCall(PetscInfo(nt->snes, "CG stopped with %s after %" PetscInt_FMT " iterations: the multigrid or the matrix is indefinite; the step solved again by GMRES on it: %s after %" PetscInt_FMT " iterations (GMRES from now on)\n", KSPConvergedReasons[cgReason], cgIts, KSPConvergedReasons[*reason], *its));
  PetscFunctionReturn(0);
}

static PetscErrorCode SSStarNewtonSolve_WholeBody(SSStarNewton nt, const PetscReal S[], const PetscReal T[], Vec y, Vec du, PetscBool *solved)
{
  Newton_WholeBody       *nw  = (Newton_WholeBody *)nt->data;
  KSP                ksp = nt->snes->ksp;
  KSPConvergedReason reason;
  PetscBool          symmetric, reuse;
  PetscInt           its;
  PetscReal          rnorm, bnorm;
  Mat                M;

  PetscFunctionBegin;
  PetscCall(PetscLogEventBegin(SSSTAR_NewtonAssemble, nt->snes, 0, 0, 0));
  PetscCall(AssembleNewtonMatrix(nt, S, T, y, &M, &symmetric));
  PetscCall(PetscLogEventEnd(SSSTAR_NewtonAssemble, nt->snes, 0, 0, 0));
  if (!nw->userKSPType) { /* the residual unpreconditioned, in the units of the tolerances */
    symmetric = (PetscBool)(symmetric && !nw->indefinite); /* CG found a multigrid indefinite: GMRES since */
    PetscCall(KSPSetType(ksp, symmetric ? KSPCG : KSPGMRES));
    PetscCall(KSPSetPCSide(ksp, symmetric ? PC_LEFT : PC_RIGHT));
    PetscCall(KSPSetNormType(ksp, KSP_NORM_UNPRECONDITIONED));
    if (!symmetric && !nw->userRestart) PetscCall(KSPGMRESSetRestart(ksp, SSSTAR_GMRES_RESTART));
  }
  if (!nw->userTolerances) PetscCall(KSPSetTolerances(ksp, nt->rtol, nt->atol, PETSC_DEFAULT, PETSC_DEFAULT));
  PetscCall(ChoosePreconditioner(nt, &reuse));
  PetscCall(SetUpPreconditioner(nt, M, reuse));
  PetscCall(KrylovSolve(nt, PETSC_FALSE, du, &reason, &its));
  if ((reason == KSP_DIVERGED_INDEFINITE_PC || reason == KSP_DIVERGED_INDEFINITE_MAT) && !nw->userKSPType) PetscCall(IndefiniteFallback(nt, du, &reason, &its));
  /* an iteration limit that still reduced the residual tenfold is an inexact step; a breakdown is a failure */
  PetscCall(KSPGetResidualNorm(ksp, &rnorm));
  PetscCall(VecNorm(nw->rhs, NORM_2, &bnorm));
  *solved       = (PetscBool)(reason > 0 || (reason == KSP_DIVERGED_ITS && rnorm <= 0.1 * bnorm));
  nw->refinable = *solved;
  if (!*solved) {
    nw->pcBuilt = PETSC_FALSE;
    PetscCall(PetscInfo(nt->snes, "Newton step on the whole body not solved: %s after %" PetscInt_FMT " iterations, residual %g of %g\n", KSPConvergedReasons[reason], its, (double)rnorm, (double)bnorm));
  }
  PetscFunctionReturn(0);
}

/* Every contact dof known (S = 0, T = I): the free dofs follow into equilibrium */
static PetscErrorCode SSStarNewtonSolveKnown_WholeBody(SSStarNewton nt, Vec y, Vec du, PetscBool *solved)
{
  Newton_WholeBody *nw = (Newton_WholeBody *)nt->data;

  PetscFunctionBegin;
  PetscCall(SSStarNewtonSolve_WholeBody(nt, nw->Sknown, nw->Tknown, y, du, solved));
  nw->refinable = PETSC_FALSE;
  PetscFunctionReturn(0);
}

/*
   The last step's Krylov solve continued from its solution (its matrix formed again, the same right-hand side and
   multigrid) to the tolerances set since, unless it met them already or the user fixed the tolerances (-ksp_rtol)
*/
static PetscErrorCode SSStarNewtonRefine_WholeBody(SSStarNewton nt, Vec du, PetscBool *refined)
{
  Newton_WholeBody       *nw  = (Newton_WholeBody *)nt->data;
  KSP                ksp = nt->snes->ksp;
  KSPConvergedReason reason;
  PetscInt           its;
  PetscReal          rnorm, bnorm;
  Mat                M;

  PetscFunctionBegin;
  if (!nw->refinable || nw->userTolerances) PetscFunctionReturn(0);
  PetscCall(KSPGetResidualNorm(ksp, &rnorm));
  PetscCall(VecNorm(nw->rhs, NORM_2, &bnorm));
  if (rnorm <= PetscMax(nt->atol, nt->rtol * bnorm)) PetscFunctionReturn(0);
  PetscCall(KSPSetTolerances(ksp, nt->rtol, nt->atol, PETSC_DEFAULT, PETSC_DEFAULT));
  PetscCall(PetscLogEventBegin(SSSTAR_NewtonAssemble, nt->snes, 0, 0, 0));
  PetscCall(SSStarWholeBodyMatrixForm(nw->wm, nw->S, nw->T, 1 / nt->gamma, nw->nknown, nw->known, NULL, NULL, &M));
  nw->M = M;
  PetscCall(PetscLogEventEnd(SSSTAR_NewtonAssemble, nt->snes, 0, 0, 0));
  PetscCall(KrylovSolve(nt, PETSC_TRUE, du, &reason, &its));
  *refined = (PetscBool)(reason > 0 || reason == KSP_DIVERGED_ITS);
  if (!*refined) {
    nw->refinable = PETSC_FALSE;
    PetscCall(PetscInfo(nt->snes, "Newton step on the whole body not refined: %s after %" PetscInt_FMT " iterations\n", KSPConvergedReasons[reason], its));
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode SSStarNewtonView_WholeBody(SSStarNewton nt, PetscViewer viewer)
{
  Newton_WholeBody *nw = (Newton_WholeBody *)nt->data;
  PetscBool    inPlace;

  PetscFunctionBegin;
  PetscCall(SSStarWholeBodyMatrixInPlace(nw->wm, &inPlace));
  PetscCall(PetscViewerASCIIPrintf(viewer, "  Newton step on the whole body (P never formed): K with each contact node's rows, known dofs eliminated, solved by the KSP below%s\n", nw->nearNull ? " (multigrid with K's near-null space)" : ""));
  PetscCall(PetscViewerASCIIPrintf(viewer, "    the Newton matrix is formed %s\n", inPlace ? "in K's storage for each linear solve (no copy of K)" : "in an AIJ copy of K (K is not AIJ, or its contact nodes' 3 x 3 blocks are incomplete)"));
  if (nw->plain || nw->wCycle || nw->allAtOnce) {
    char cycle[128] = "";

    if (nw->wCycle) PetscCall(PetscSNPrintf(cycle, sizeof(cycle), " W-cycles on the %" PetscInt_FMT " finest levels (-snes_ssstar_mg_w_levels), V below (-pc_mg_cycle_type);", nw->wLevels));
    PetscCall(PetscViewerASCIIPrintf(viewer, "    multigrid by ssstar's choice:%s%s%s%s\n", !nw->plain ? "" : nw->plainBySize ? " plain aggregation: K has at least -snes_ssstar_plain_aggregation_dofs dofs;" : " plain aggregation: the set-up of the smoothed one would not fit the memory (-snes_ssstar_memory_limit or MemAvailable", !nw->plain || nw->plainBySize ? "" : nw->byEstimate ? ", by the estimate before the work);" : ", by the memory in use at the set-up);", cycle, nw->allAtOnce ? " Galerkin products P^T A P all at once (-matptap_via)" : ""));
  }
  if (nw->ocScale != 1) PetscCall(PetscViewerASCIIPrintf(viewer, "    the W-cycled levels' coarse corrections times %g (over-correction, -snes_ssstar_mg_overcorrection)\n", (double)(nw->ocScale * nw->ocScale)));
  PetscCall(PetscViewerASCIIPrintf(viewer, "    the multigrid of an earlier step is kept while at most %g%% of the nodes changed their known rows\n", (double)(100 * nt->pcReuse)));
  if (nw->indefinite) PetscCall(PetscViewerASCIIPrintf(viewer, "    CG stopped on an indefinite multigrid (DIVERGED_INDEFINITE_PC) in %" PetscInt_FMT " step%s since the set-up: solved again by GMRES on it, which needs no definite preconditioner, and every later step by GMRES\n", nw->indefinite, nw->indefinite > 1 ? "s" : ""));
  if (nt->nSteps) PetscCall(PetscViewerASCIIPrintf(viewer, "    last solve: %" PetscInt_FMT " linear solves, %" PetscInt_FMT " Krylov iterations (%.1f per solve), %" PetscInt_FMT " preconditioner set-ups, %" PetscInt_FMT " solves on an earlier one, %" PetscInt_FMT " inexact steps solved on to the floor after a failed full step\n", nt->nSteps, nt->nKrylov, (double)nt->nKrylov / nt->nSteps, nt->nFactor, nt->nReused, nt->nRefined));
  PetscFunctionReturn(0);
}

static PetscErrorCode SSStarNewtonReset_WholeBody(SSStarNewton nt)
{
  Newton_WholeBody *nw = (Newton_WholeBody *)nt->data;

  PetscFunctionBegin;
  PetscCall(SSStarWholeBodyMatrixDestroy(&nw->wm));
  PetscCall(MatNullSpaceDestroy(&nw->nearNull));
  PetscCall(VecDestroy(&nw->rhs));
  PetscCall(VecDestroy(&nw->dv));
  PetscCall(PetscFree3(nw->known, nw->mask, nw->touched));
  PetscCall(MatDestroy(&nw->shell));
  PetscCall(PetscFree(nw->pcMask));
  PetscCall(PetscFree4(nw->Sknown, nw->Tknown, nw->S, nw->T));
  nw->ocScale = 1;
  for (PetscInt k = 0; k < SSSTAR_SMOOTHER_OPTIONS; k++) {
    if (nw->smoother[k]) PetscCall(PetscOptionsClearValue(NULL, nw->smoother[k]));
    PetscCall(PetscFree(nw->smoother[k]));
  }
  PetscCall(KSPReset(nt->snes->ksp));
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarNewtonCreate_WholeBody(SSStarNewton nt)
{
  Newton_WholeBody *nw;

  PetscFunctionBegin;
  nt->snes->usesksp = PETSC_TRUE; /* the SNES's KSP solves the Newton systems */
  PetscCall(PetscNew(&nw));
  nt->data           = nw;
  nt->ops.setup      = SSStarNewtonSetUp_WholeBody;
  nt->ops.setscaling = SSStarNewtonSetScaling_WholeBody;
  nt->ops.solve      = SSStarNewtonSolve_WholeBody;
  nt->ops.solveknown = SSStarNewtonSolveKnown_WholeBody;
  nt->ops.refine     = SSStarNewtonRefine_WholeBody;
  nt->ops.view       = SSStarNewtonView_WholeBody;
  nt->ops.reset      = SSStarNewtonReset_WholeBody;
  PetscFunctionReturn(0);
}
