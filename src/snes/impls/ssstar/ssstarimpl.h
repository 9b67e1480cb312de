#ifndef SSSTARIMPL_H
#define SSSTARIMPL_H

#include <ssstar.h>
#include <ssstarreduction.h>
#include <petsc/private/snesimpl.h>

PETSC_EXTERN PetscLogEvent SSSTAR_ApproxStep, SSSTAR_NewtonStep, SSSTAR_LineSearch;
/* parts of the Newton step with a dense P: A_RR and its right-hand side, LU factorizations, Krylov solves on old factors */
PETSC_EXTERN PetscLogEvent SSSTAR_NewtonAssemble, SSSTAR_NewtonFactor, SSSTAR_NewtonKrylov;

/*
   The Newton step (newton/: newton.c and one file per implementation, newtonimpl.h, registered by name): for the per-node
   blocks S, T of docs/derivation.md section 5 it solves the Newton system on the stiffness A of the solve (P, or K on
   the whole body) and returns du in the global frame. Created with the SNES (it keeps the settings); each SNESSolve
   gives it the stiffness A, the name of the implementation that fits it and the contact nodes' layout. Counts are of the
   current SNESSolve.
*/
#define SSSTARNEWTONDENSE     "dense"     /* dense P: known dofs eliminated, LU of the rest, GMRES on an older LU        */
#define SSSTARNEWTONSPARSE    "sparse"    /* sparse P (the user's): the Newton matrix factored by the SNES's KSP         */
#define SSSTARNEWTONWHOLEBODY "wholebody" /* the whole body: K with the contact rows, Krylov + algebraic multigrid      */

/*
   K's null space (floating/floating.c): the rigid-body motions of the bodies held by contact alone, as declared on K
   (MatSetNullSpace()), and what the iteration derives from them (docs/derivation.md section 14): whether the friction
   laws can balance the load at all, the motions a Newton step's states leave free, the least-norm solution
*/
typedef struct {
  PetscInt   m;          /* motions (0: K is regular and nothing here acts)                                    */
  Vec       *modes;      /* orthonormal, in the layout of the SNES vector (global axes)                        */
  PetscInt   nnodes;     /* local contact nodes                                                                */
  const PetscReal *frames; /* theirs (the contact's), or NULL for identities                                   */
  PetscReal *Rc;         /* motion k at node i in its frame, (B rho_k)_i: Rc[(3 i + r) m + k]                  */
  PetscReal *G;          /* m x m: Rc^T Rc over every node                                                     */
  PetscInt   nbodies;    /* the floating bodies: groups of motions that move common dofs                      */
  PetscInt  *body;       /* per motion, its body                                                               */
  PetscInt   nfixed;     /* motions no contact point can resist (frictionless): the least-norm solution        */
  Vec       *fixed;      /* orthonormal                                                                        */
  Vec       *pmodes;     /* the motions in the points' variables, T^-1 rho_k (the layout of the whole body's K)   */
  PetscInt   nfree;      /* the motions the states of the current Newton step leave free                      */
  PetscReal *free, *freeGlobal; /* 3 nnodes x nfree, column-major: in the nodes' frames, in global axes       */
  PetscReal *Y;          /* m x nfree: their coefficients on the motions                                     */
  Vec        motion;     /* no equilibrium: the rigid motion whose work no admissible contact force balances    */
  PetscInt   movingBody; /* the body it moves most                                                            */
  PetscReal  direction[3]; /* the direction it slides in at that body's contact points (global axes, unit)      */
  PetscReal  translation[3]; /* that body's mean translation along the motion, unit                           */
  PetscReal  unbalanced; /* the unbalanced part of the load, relative to its part on the motions             */
} SSStarFloating;

/* Where the contact nodes are in A's vectors, their frames, and K's null space */
typedef struct {
  PetscInt            nnodes; /* local contact nodes                                              */
  const PetscInt     *dofs;   /* 3 per node: the local offsets of its dofs in A's vectors       */
  const PetscReal    *frames; /* 9 per node (rows t1, t2, n), or NULL for identities                */
  SSStarFloating     *floating; /* floating bodies, or NULL                                           */
} SSStarContactLayout;

/* Whether bytes per rank fit the memory limit (GB per rank, 0: each node's MemAvailable): the reductions' check (src/reduction) */
PETSC_INTERN PetscErrorCode SSStarReductionFitsMemory(MPI_Comm, PetscReal, PetscLogDouble, PetscLogDouble, PetscBool *);
/* the law residual's displacement scale is at least this fraction of |u_C| (and of the path's largest, as its force
   scale of the path's largest force): the rounding of w = R u + o, 1e-16 of |u|, stays 100 times below the default
   tolerance of the law */
#define SSSTAR_LAW_FLOOR 1e-6
/* its force scale is at least this fraction of |A| |u| + |f|: 10 times the worst round-off of r = A u - f, 2e-16 of
   that, at the default tolerance 1e-8 (a stiff body far from its reference computes its forces to no better) */
#define SSSTAR_LAW_FORCE_FLOOR 2e-7
/* the tolerance of the law residual of a converged iterate is max(rtol, this) unless -snes_ssstar_law_rtol sets it */
#define SSSTAR_LAW_RTOL_DEFAULT 1e-8
/* whole body: a step solved to the floor that is not the likely last one (after a remedy, polishing, the start's
   equilibrium) leaves this fraction of the stopping rule in its linear residual (-snes_ssstar_ksp_floor: the last one) */
#define SSSTAR_FLOOR_FRACTION 0.1
/* polishing steps without halving the law residual before the solve stops (it is at its round-off floor) */
#define SSSTAR_LAW_MAX_STALLS 3

/* the multigrid of an earlier Newton matrix is kept while at most this fraction of the nodes changed known rows */
#define SSSTAR_PC_REUSE_DEFAULT 0.3
/* the whole body's plain-aggregation multigrid: its W-cycled levels' coarse corrections times this (docs/guide/scale.md) */
#define SSSTAR_MG_OVERCORRECTION 1.8
/* and its finest levels that W-cycle (V below) */
#define SSSTAR_MG_W_LEVELS 2

typedef struct _n_SSStarNewton *SSStarNewton;
PETSC_EXTERN PetscFunctionList SSStarNewtonList;
PETSC_INTERN PetscErrorCode    SSStarNewtonRegister(const char[], PetscErrorCode (*)(SSStarNewton));
PETSC_INTERN PetscErrorCode    SSStarNewtonRegisterAll(void);
PETSC_EXTERN PetscBool         SSStarNewtonRegisterAllCalled;
PETSC_INTERN PetscErrorCode    SSStarNewtonCreate(SNES, SSStarNewton *);
PETSC_INTERN PetscErrorCode    SSStarNewtonSetReuse(SSStarNewton, PetscReal);
PETSC_INTERN PetscErrorCode    SSStarNewtonGetReuse(SSStarNewton, PetscReal *);
PETSC_INTERN PetscErrorCode    SSStarNewtonSetPCReuse(SSStarNewton, PetscReal);
PETSC_INTERN PetscErrorCode    SSStarNewtonGetPCReuse(SSStarNewton, PetscReal *);
PETSC_INTERN PetscErrorCode    SSStarNewtonSetPlainAggregationDofs(SSStarNewton, PetscInt);
PETSC_INTERN PetscErrorCode    SSStarNewtonGetPlainAggregationDofs(SSStarNewton, PetscInt *);
PETSC_INTERN PetscErrorCode    SSStarNewtonSetSmoothedAggregationFits(SSStarNewton, PetscBool);
PETSC_INTERN PetscErrorCode    SSStarNewtonSetMGOverCorrection(SSStarNewton, PetscReal, PetscInt);
PETSC_INTERN PetscErrorCode    SSStarNewtonGetMGOverCorrection(SSStarNewton, PetscReal *, PetscInt *);
PETSC_INTERN PetscErrorCode    SSStarNewtonSetLUThreads(SSStarNewton, PetscInt);
PETSC_INTERN PetscErrorCode    SSStarNewtonGetLUThreads(SSStarNewton, PetscInt *);
PETSC_INTERN PetscErrorCode    SSStarNewtonSetStiffness(SSStarNewton, const char[], Mat, PetscReal, const SSStarContactLayout *);
PETSC_INTERN PetscErrorCode    SSStarNewtonUpdateStiffness(SSStarNewton, const char[], Mat, const SSStarContactLayout *);
PETSC_INTERN PetscErrorCode    SSStarNewtonSetScaling(SSStarNewton, PetscReal);
PETSC_INTERN PetscErrorCode    SSStarNewtonSetTolerances(SSStarNewton, PetscReal, PetscReal);
PETSC_INTERN PetscErrorCode    SSStarNewtonSolve(SSStarNewton, const PetscReal[], const PetscReal[], Vec, Vec, PetscBool *);
PETSC_INTERN PetscErrorCode    SSStarNewtonSolveKnown(SSStarNewton, Vec, Vec, PetscBool *);
PETSC_INTERN PetscErrorCode    SSStarNewtonRefine(SSStarNewton, Vec, PetscBool *);
PETSC_INTERN PetscErrorCode    SSStarNewtonGetConditionEstimate(SSStarNewton, PetscReal *);
PETSC_INTERN PetscErrorCode    SSStarNewtonGetCounts(SSStarNewton, PetscInt *, PetscInt *, PetscInt *);
PETSC_INTERN PetscErrorCode    SSStarNewtonGetFactorTime(SSStarNewton, PetscLogDouble *);
PETSC_INTERN PetscErrorCode    SSStarNewtonGetSteps(SSStarNewton, PetscInt *);
PETSC_INTERN PetscErrorCode    SSStarNewtonView(SSStarNewton, PetscViewer);
PETSC_INTERN PetscErrorCode    SSStarNewtonReset(SSStarNewton);
PETSC_INTERN PetscErrorCode    SSStarNewtonDestroy(SSStarNewton *);

/*
   The contact (contact.c): what the user declared (the contact points with their rows of the contact operator B, the
   friction laws and their parameters) and what the solver derives from it per node. A point i has three own dofs and
   w_i = B_i u + g_i in its frame (t1, t2, n), w_i3 >= 0 (contactoperator.c). SNESSSStarSetContactNodes() declares points
   against rigid planes: B's rows are built from the normals (each node's own dofs turned into its frame).
*/

/* A law parameter as declared: one value for every node (-snes_ssstar_<name>) and/or one per node */
typedef struct {
  char      name[64];
  PetscInt  size;    /* values per node: 1, or 3 for a direction                   */
  PetscBool set;     /* value is the default of the nodes without their own         */
  PetscReal value[3];
  Vec       perNode; /* size entries per contact node (SSSTAR_NOT_GIVEN: the default), or NULL */
} SSStarLawSetting;

typedef struct {
  /* as declared by the user */
  IS                dofs;      /* contact dofs of the SNES vector, 3 per owned node; NULL: every dof     */
  Vec               normals;   /* 3 per node, or NULL for (0, 0, 1) (without B)                         */
  Mat               B;         /* the contact operator given, or NULL: built from the normals           */
  Vec               gaps;      /* 1 per node, or NULL for 0                                            */
  Vec               offsets;   /* 3 per node, or NULL: a load path's step (read at every solve; not a declaration) */
  SSStarLaw         law;       /* of the nodes without a law of their own                              */
  PetscInt         *nodeLaws;  /* index into the table of laws per owned node, or NULL                   */
  PetscInt          nNodeLaws;
  PetscInt          nsettings; /* the law parameters declared                                          */
  SSStarLawSetting *settings;
  PetscObjectState  declared;  /* bumped by every setter: the per-node data are rebuilt when it moved  */
  PetscErrorCode  (*update)(SNES, Vec, void *); /* SNESSSStarSetContactUpdate(): declares the contact measured at an iterate, or NULL */
  void             *updateCtx;

  /* derived, in the solver's node order (nodes sorted by their first dof) */
  PetscObjectState built;       /* value of declared the per-node data were built for                  */
  PetscInt         nnodes;      /* owned contact nodes                                                  */
  IS               isC, isI;    /* contact dofs in the solver's order, and the other owned dofs         */
  PetscInt        *order;       /* solver's node i is the user's node order[i]                          */
  PetscReal       *frames;      /* 9 per node (rows t1, t2, n), or NULL when every frame is the identity */
  PetscReal       *gap;         /* per node (g_i / d_i), or NULL                                        */
  PetscReal       *offset;      /* 3 per node (o_i / d_i) of this solve, replacing (0, 0, gap), or NULL  */
  PetscReal       *pointScale;  /* d_i of each point (its block of B at its own dofs is d_i R_i)        */
  Mat              T;           /* with master dofs: u = T v, the change to the points' variables       */
  SSStarFriction  *nodeFriction; /* per node; forces as forces (the kernels see them times gamma)        */
  PetscInt         nlaws;       /* the size of the table of laws when built                             */
  PetscInt        *lawCounts;   /* nodes per law of the table (global)                                  */
  PetscInt         coupled;     /* nodes whose friction depends on the normal force (global)            */
} SSStarContact;

PETSC_INTERN PetscErrorCode SSStarContactInitialize(SSStarContact *);
PETSC_INTERN PetscErrorCode SSStarContactSetUp(SNES, SSStarContact *, PetscBool *);
PETSC_INTERN PetscErrorCode SSStarContactReset(SSStarContact *);
PETSC_INTERN PetscErrorCode SSStarContactDestroy(SSStarContact *);
PETSC_INTERN PetscErrorCode SSStarContactView(SSStarContact *, PetscViewer);
PETSC_INTERN PetscErrorCode SSStarContactGetNodeCount(SNES, SSStarContact *, PetscInt *);
PETSC_INTERN PetscErrorCode SSStarContactSetLaw(SSStarContact *, const char[]);
PETSC_INTERN PetscErrorCode SSStarContactSetParameter(MPI_Comm, SSStarContact *, const char[], PetscInt, const PetscReal[]);
PETSC_INTERN PetscErrorCode SSStarContactGetParameter(SSStarContact *, const char[], PetscInt *, PetscReal[], PetscBool *);
PETSC_INTERN PetscErrorCode SSStarContactViewParameters(SSStarContact *, PetscViewer);
PETSC_INTERN PetscErrorCode SSStarContactSetUpOffsets(MPI_Comm, SSStarContact *, PetscReal *);
/* contact.c's checks and helpers of a declaration, shared with friction.c (the laws and their parameters) */
#define SSSTAR_MESSAGE_LEN 512 /* the message of the first failed check of this rank; checks after it are skipped */
PETSC_INTERN PetscErrorCode SSStarContactCheckNodeVector(MPI_Comm, Vec, PetscInt, PetscInt, const char[]);
PETSC_INTERN PetscErrorCode SSStarContactCheckNodeArrays(SNES, SSStarContact *, PetscInt, const char[]);
PETSC_INTERN PetscErrorCode SSStarContactReplaceVec(Vec *, Vec);
PETSC_INTERN PetscErrorCode SSStarContactDeclaredNodes(SSStarContact *, PetscInt *);
PETSC_INTERN PetscErrorCode SSStarContactFindSetting(SSStarContact *, const char[], SSStarLawSetting **);
/* Every declaration change invalidates the per-node data and the problem */
static inline void SSStarContactDeclared(SSStarContact *ct)
{
  ct->declared++;
}
/* contactoperator.c: the frames and scales of the points from B, and the change of variables T */
PETSC_INTERN PetscErrorCode SSStarContactOperatorSetUp(MPI_Comm, SSStarContact *, Mat, Vec);
PETSC_INTERN PetscErrorCode SSStarContactTransformStiffness(SSStarContact *, Mat, Mat *);
PETSC_INTERN PetscErrorCode SSStarContactToPointVariables(SSStarContact *, Vec, Vec);

/*
   The problem the iteration runs on (problem.c): c(u) = A u - f. The solver's unknown u lives in the vectors of A: the
   contact dofs in the global frame (3 per node; in node i's frame v_i = R_i u_i + g_i e_3, with v_i3 >= 0) and, on the
   whole body, the other dofs too (free dofs).

     reduced use:          A = the user's P (every dof a contact dof), u = u_C
     whole body, a Schur reduction of K:  A = P = K_CC - K_CI K_II^-1 K_IC, load f, u = u_C
     whole body, reduction none:          A = K, load b, u = the whole displacement (P never formed)

   It is kept while K and the declaration are unchanged. A residual treated as nonlinear (nonlinear.c, docs/derivation.md
   section 17) has c(u) = T^T F(T u) from F itself and A = T^T J T with J evaluated again at the iterates: on the whole
   body (reduction none) or in the reduced use, never through a Schur reduction.
*/
typedef struct {
  /* settings */
  char             reductionType[64]; /* a registered reduction, or auto                              */
  PetscReal        memoryLimit;       /* GB per rank for the reduction; 0: MemAvailable of the node per rank */

  SSStarReduction  reduction;       /* NULL in the reduced use                                              */
  Mat              K;               /* the Jacobian the problem was set up from                             */
  Mat              Kw;              /* K in the points' variables, T^T K T (K itself without masters)       */
  PetscObjectState Kstate;
  PetscReal        meanDiag;        /* mean of the diagonal of K_CC (P in the reduced use)                  */
  PetscReal        maxRowSum;       /* largest sum |K_ij| of a contact row: a bound of lambda_max(P)        */
  Mat              A;               /* the stiffness the iteration runs on: P, or K (reduction none)        */
  Vec              b, bw, f;        /* the whole load b = -F(0), T^T b, and A's load f (reduced, or bw)     */
  PetscBool        wholeBody;       /* A is K: the free dofs are unknowns too (the reduction says)          */
  PetscObjectState built;           /* the contact's built state it was set up for                          */
  IS               isC;             /* the contact dofs it was set up for (a redeclaration may keep them)   */
  const char      *newtonType;      /* the Newton step that fits A                                          */
  PetscInt        *layoutDofs;      /* 3 per node: its dofs' local offsets in A's vectors                   */
  PetscInt         nfree, *free;    /* the other local offsets of A's vectors (free dofs; none when reduced) */
  SSStarFloating   floating;        /* K's null space: the bodies held by contact alone                      */

  /* the residual (nonlinear.c, docs/derivation.md section 17) */
  PetscBool        affineSet, affineDeclared; /* SNESSSStarSetAffine() (unset: affine iff F is SNESSSStarSetLinearProblem()'s) */
  PetscBool        affine;          /* this solve's F is affine: its Jacobian is evaluated once                */
  PetscBool        nonlinear;       /* this solve iterates on F itself: not affine, or the contact measured at the iterates */
  Vec              x, Fx, v;        /* an iterate as the SNES vector, F there, and T^T F (work)              */
  Vec              xJ, xMeasured;   /* where the Jacobian was evaluated last, where the contact was measured last */
  PetscInt         jacobians;       /* Jacobian evaluations of this solve (the set-up's included)            */
  PetscInt         measures;        /* contact updates of this solve                                         */
  PetscReal        affineMismatch;  /* an affine residual at the solution: max |F - the model's c| / its force scale */
  PetscInt         builds;          /* times A was built (K reduced, or taken whole): the progress line's    */
} SSStarProblem;

PETSC_INTERN PetscErrorCode SSStarProblemSetUp(SNES, SSStarContact *, SSStarProblem *);
PETSC_INTERN PetscErrorCode SSStarProblemGetLayout(SSStarContact *, SSStarProblem *, SSStarContactLayout *);
PETSC_INTERN PetscErrorCode SSStarProblemGetInitialGuess(SSStarContact *, SSStarProblem *, Vec, Vec);
PETSC_INTERN PetscErrorCode SSStarProblemSetSolution(SSStarContact *, SSStarProblem *, Vec, Vec, Vec);
PETSC_INTERN PetscErrorCode SSStarProblemSetReductionType(SSStarProblem *, const char[]);
PETSC_INTERN PetscErrorCode SSStarProblemGetReductionType(SSStarProblem *, const char *[]);
PETSC_INTERN PetscErrorCode SSStarProblemView(SSStarContact *, SSStarProblem *, PetscViewer);
PETSC_INTERN PetscErrorCode SSStarProblemReset(SSStarProblem *);
PETSC_INTERN PetscErrorCode SSStarProblemIterateVector(SSStarContact *, SSStarProblem *, Vec, Vec);
PETSC_INTERN PetscErrorCode SSStarProblemFunctionResidual(SNES, Vec, Vec);
PETSC_INTERN PetscErrorCode SSStarProblemComputeJacobian(SNES, Vec, Mat *);
PETSC_INTERN PetscErrorCode SSStarProblemTakeJacobian(SNES, SSStarContact *, SSStarProblem *, Mat);
PETSC_INTERN PetscErrorCode SSStarProblemTakeMeasuredContact(SNES, SSStarContact *, SSStarProblem *, PetscBool *, PetscBool *);
PETSC_INTERN PetscErrorCode SSStarProblemIsAffine(SNES, SSStarProblem *, PetscBool *);

/*
   The residual treated as nonlinear (nonlinear.c, docs/derivation.md section 17): c(u) from F itself (problem.c's
   SSStarProblemFunctionResidual()), the Jacobian evaluated again at the iterates (-snes_lag_jacobian), the contact
   measured again at them (SNESSSStarSetContactUpdate), and a residual declared affine checked at the solution
*/
PETSC_INTERN PetscErrorCode SSStarNonlinearMeasureAtStart(SNES);
PETSC_INTERN PetscErrorCode SSStarNonlinearBegin(SNES);
PETSC_INTERN PetscErrorCode SSStarNonlinearMeasureContact(SNES);
PETSC_INTERN PetscErrorCode SSStarNonlinearJacobian(SNES, PetscInt);
PETSC_INTERN PetscErrorCode SSStarNonlinearCheckAffine(SNES);
PETSC_INTERN PetscErrorCode SSStarNonlinearView(SNES, PetscViewer);
PETSC_INTERN PetscErrorCode SSStarNonlinearFormatCounts(SNES, char[], size_t);
PETSC_INTERN PetscErrorCode SNESSSStarComposeNonlinear(SNES, PetscBool);

/*
   The globalization (globalization.c): damped steps on the merit function ||z||, detection of cycles and
   stagnation, and the remedies of SSStarRemedy. docs/guide/converged.md, "When it does not converge".
*/
typedef enum {
  SSSTAR_DETECTED_NONE,
  SSSTAR_DETECTED_CYCLE,      /* states as two iterations ago and ||z|| back to its value then, twice in a row */
  SSSTAR_DETECTED_STAGNATION  /* no new smallest ||z|| for stagnationIts iterations                            */
} SSStarDetection;

typedef struct {
  /* settings */
  PetscBool on;            /* damped steps and remedies; off: the plain iteration of docs/derivation.md section 7   */
  PetscReal dampingMin;    /* smallest damping factor alpha of the line search                                 */
  PetscInt  stagnationIts; /* iterations without a new smallest ||z|| before the solve stops                   */

  /* per solve */
  PetscReal       zbest;                      /* smallest ||z|| since the start or the last rescaling         */
  PetscInt        kbest;                      /* its iteration                                                  */
  PetscReal       zhist[4];                   /* ||z|| at k, k-1, k-2, k-3                                      */
  PetscInt        nhist;                      /* iterations recorded since the start or the last rescaling      */
  PetscBool       recurred;                   /* the previous iteration recurred to the one two before it      */
  SSStarState    *older[2];                   /* local states at k-1 and k-2                                     */
  PetscInt        nnodes;                     /* local nodes of older[]                                          */
  PetscInt        lsFailures;                 /* failed line searches: odd ones take the full step, even rescale */
  PetscInt        counts[SSSTAR_NUM_REMEDIES];
  PetscInt        cycles;                     /* cycles detected                                                 */
  PetscReal       gamma0;                     /* the scaling the solve started with                              */

  /* the remedies on the way to the next iterate, and those that led to the current one with what was detected at
     it (printed by -snes_ssstar_monitor_states) */
  PetscBool       pending[SSSTAR_NUM_REMEDIES], shown[SSSTAR_NUM_REMEDIES];
  PetscReal       alpha, shownAlpha;          /* damping of the step (1: full, 0: no step)                      */
  SSStarDetection detected;
  PetscInt        flipping;                   /* nodes whose state has period 2                                 */
  PetscInt        changed;                    /* nodes whose state is not that of the previous iterate (-1: none) */
  PetscReal      *slip;                       /* 2 per local node: d_t at the last iterate if it slid, else 0     */
  PetscInt        reversed, shownStuck;       /* nodes stuck at a twice-reversed slip on the way to the next iterate, to this one (section 19c) */
  PetscInt        stuck;                      /* the same, summed over the solve                                 */
} SSStarGlobalization;

typedef struct {
  SSStarContact contact;
  SSStarProblem problem;

  /* the method */
  SSStarMethod method;       /* Newton (default) or the fixed-point baseline                          */
  PetscReal    scaling_user; /* gamma as set by the user; 0 means 1/mean(diag K_CC)                  */
  PetscReal    scaling;      /* gamma in use for the current solve                                    */
  PetscReal    state_tol;    /* tau of the classification (section 2)                                 */
  PetscReal    scale;        /* ||gamma f||: the problem's displacement scale in the stopping rule    */
  PetscReal    offsetScale;  /* ||o_t||, the tangential offsets of a load path's step (10.4): part of that scale */
  PetscReal    fnorm_inf;    /* ||f||_inf, f the load reduced to the contact dofs                     */
  PetscReal    coarseLoad[2]; /* SNESSSStarSetCoarseLoadScale(): ||f||, ||f||_inf of a coarser mesh's solve */
  PetscInt     coarseNodes;  /* ... and its contact nodes; 0: none given (start.c)                      */
  PetscBool    freeUnbalanced; /* the first iterate's free dofs not put in equilibrium (start.c)      */
  PetscReal    etaMax;       /* whole body: the loosest relative tolerance of a Newton step's solve   */
  PetscReal    kspFloor;     /* whole body: the last step's linear residual, a fraction of the stopping rule */
  PetscBool    lastStep;     /* whole body: the step being solved is likely the last (its states repeated) */
  SSStarReason reason;
  PetscReal    tolerance;    /* the threshold of the last convergence test: max(atol, rtol max(||u||, ||gamma f||)) */

  /* what a converged iterate guarantees as written (docs/derivation.md section 12): its law residual rho is at most
     SNESSSStarLawTolerance() */
  PetscReal  lawRtol;                   /* the tolerance of rho as set, or 0: max(rtol, SSSTAR_LAW_RTOL_DEFAULT)      */
  PetscReal  lawResidual;               /* rho of the last iterate                                                */
  PetscReal  lawDisplacement, lawForce; /* U and F of it                                                          */
  PetscReal  pathDisplacement, pathForce; /* the largest U and F of the solves since the set-up (a load path's)    */
  PetscReal  lawBest;                   /* the smallest rho of this solve's polishing steps                       */
  PetscInt   lawStalls;                 /* polishing steps that did not halve it                                  */
  PetscBool  polishing;                 /* ||z|| is below its threshold, rho not: Newton steps solved to the floor */
  PetscReal *start;                     /* u and c = A u - f at the contact dofs of the solve's first iterate (6 per node) */

  /* the iteration, per local node in the solver's order */
  SSStarState *states;                     /* at the last iterate                                   */
  SSStarState *userStates;                 /* the same in the user's node order                     */
  PetscInt     counts[SSSTAR_NUM_STATES];  /* global counts per state                               */
  PetscReal   *S, *T;                      /* blocks of the Newton system, 9 per node               */
  /* in the layout of A's vectors (the contact nodes' entries in the global frame, unless said) */
  Vec          u, c, z, y, dv;             /* u, c = A u - f, dv; z, y: the nodes' frames at the contact dofs */
  Vec          ut, ct, ua, ca;             /* trial iterates and their A u - f: the full step, a damped one  */
  Vec          d, b;                       /* 3 per node, the nodes' frames                                 */
  SSStarNewton newton;
  SSStarGlobalization glob;

  /* -snes_ssstar_monitor_progress: when the solve started, and the time, Krylov iterations, LUs (multigrids) at the last iterate */
  PetscLogDouble tStart, tLast;
  PetscInt       krylovLast, factorizationsLast, jacobiansLast;
  PetscLogDouble factorSecondsLast; /* SSStarNewtonGetFactorTime() at the last progress line */
  PetscInt       buildsShown; /* the problem's builds the progress lines have reported */
} SNES_SSStar;

/* nodesteps.c: the per-node work of an iteration on any iterate (u, c), and the norms and linear solves around it */
/* start.c: the load's scale and the first iterate's equilibrium */
PETSC_INTERN PetscErrorCode SNESSSStarStart(SNES);
PETSC_INTERN PetscErrorCode SNESSSStarStartNorm(SNES, PetscReal, PetscReal *);
PETSC_INTERN PetscErrorCode SNESSSStarResidual(SNES, Vec, Vec);
PETSC_INTERN PetscErrorCode SNESSSStarContactNorm(SNES, Vec, PetscReal *);
PETSC_INTERN PetscErrorCode SNESSSStarApproximationStep(SNES, Vec, Vec, PetscReal *);
PETSC_INTERN void           SNESSSStarStickNode(SNES_SSStar *, PetscInt, const PetscScalar *, PetscScalar *, PetscScalar *);
PETSC_INTERN PetscErrorCode SNESSSStarClassify(SNES);
PETSC_INTERN PetscErrorCode SNESSSStarLawResidual(SNES, Vec, Vec);
PETSC_INTERN PetscReal      SNESSSStarLawTolerance(SNES);
PETSC_INTERN PetscErrorCode SNESSSStarRecordStart(SNES, Vec, Vec);
PETSC_INTERN PetscErrorCode SNESSSStarElasticTrial(SNES, PetscBool *);
PETSC_INTERN PetscErrorCode SNESSSStarNewtonStep(SNES, PetscReal, PetscReal, PetscBool, PetscBool *);
PETSC_INTERN PetscErrorCode SNESSSStarRefineNewtonStep(SNES, PetscReal, PetscBool *);
PETSC_INTERN PetscErrorCode SNESSSStarFixedPointStep(SNES, Vec, Vec, PetscBool *);
PETSC_INTERN PetscErrorCode SNESSSStarSetLinearTolerances(SNES, PetscReal, PetscReal);
PETSC_INTERN PetscErrorCode SNESSSStarLinearFloor(SNES, PetscReal *);
PETSC_INTERN void           SNESSSStarNodeRotate(const SSStarContact *, const SSStarProblem *, PetscInt, const PetscScalar *, PetscReal[3]);
PETSC_INTERN void           SNESSSStarNodeIterate(const SSStarContact *, const SSStarProblem *, PetscInt, const PetscScalar *, PetscReal[3]);
PETSC_INTERN SSStarFriction SNESSSStarScaledFriction(SNES_SSStar *, PetscInt, PetscReal);

/* floating/: floating.c, balance.c: bodies held by contact alone (K's null space; docs/derivation.md section 14) */
PETSC_INTERN PetscErrorCode SSStarFloatingSetUp(SSStarContact *, Mat, PetscBool, SSStarFloating *);
PETSC_INTERN PetscErrorCode SSStarFloatingFreeMotions(SSStarFloating *, const unsigned char[], const PetscReal[]);
PETSC_INTERN PetscErrorCode SSStarFloatingLeastNorm(SSStarFloating *, Vec);
PETSC_INTERN PetscErrorCode SSStarFloatingView(SSStarFloating *, PetscViewer);
PETSC_INTERN PetscErrorCode SSStarFloatingReset(SSStarFloating *);
PETSC_INTERN PetscErrorCode SNESSSStarCheckEquilibrium(SNES);
PETSC_INTERN PetscErrorCode SNESSSStarExtendFreeStep(SNES);

/*
   The type's implementations of the public functions (SNESSSStar*_C), each beside its public function in the file of
   its concept, composed on the SNES by that file's table: on (SNESCreate_SSStar()) and off (SNESDestroy_SSStar()).
   Setters are no-ops on a SNES of another type (PetscTryMethod), so a program may declare its contact nodes and still
   run with -snes_type ksponly. Every collective entry checks its input on every rank (SSStarCheckAllRanks()).
*/
typedef struct {
  const char       *name;
  PetscVoidFunction fn;
} SSStarComposed;

static inline PetscErrorCode SNESSSStarComposeTable(SNES snes, const SSStarComposed table[], size_t n, PetscBool on)
{
  PetscFunctionBegin;
  for (size_t k = 0; k < n; k++) PetscCall(PetscObjectComposeFunction((PetscObject)snes, table[k].name, on ? table[k].fn : NULL));
  PetscFunctionReturn(0);
}
PETSC_INTERN PetscErrorCode SNESSSStarComposeContact(SNES, PetscBool);       /* contact.c       */
PETSC_INTERN PetscErrorCode SNESSSStarComposeFriction(SNES, PetscBool);      /* friction.c      */
PETSC_INTERN PetscErrorCode SNESSSStarComposeProblem(SNES, PetscBool);       /* problem.c       */
PETSC_INTERN PetscErrorCode SNESSSStarComposeNewton(SNES, PetscBool);        /* newton/newton.c */
PETSC_INTERN PetscErrorCode SNESSSStarComposeNodeSteps(SNES, PetscBool);     /* nodesteps.c     */
PETSC_INTERN PetscErrorCode SNESSSStarComposeStart(SNES, PetscBool);         /* start.c         */
PETSC_INTERN PetscErrorCode SNESSSStarComposeGlobalization(SNES, PetscBool); /* globalization.c */
PETSC_INTERN PetscErrorCode SNESSSStarComposeFloating(SNES, PetscBool);      /* floating/balance.c */
/* view.c: options, -snes_view, -snes_converged_reason's line */
PETSC_INTERN PetscErrorCode SNESSetFromOptions_SSStar(SNES, PetscOptionItems *);
PETSC_INTERN PetscErrorCode SNESView_SSStar(SNES, PetscViewer);
PETSC_INTERN PetscErrorCode SNESSSStarConvergedReasonView(SNES, void *);
PETSC_INTERN PetscErrorCode SNESSSStarFormatStateCounts(const PetscInt[], char[], size_t);

/* globalization.c */
PETSC_INTERN PetscErrorCode SSStarGlobalizationBegin(SNES);
PETSC_INTERN PetscErrorCode SSStarGlobalizationDetect(SNES, PetscInt, PetscReal);
PETSC_INTERN PetscErrorCode SSStarGlobalizationReversedSlips(SNES);
PETSC_INTERN PetscErrorCode SSStarGlobalizationRecord(SSStarGlobalization *, SSStarRemedy);
PETSC_INTERN PetscErrorCode SSStarGlobalizationStep(SNES, PetscInt, PetscReal, PetscBool, SSStarReason *);
PETSC_INTERN PetscErrorCode SSStarGlobalizationBreakCycle(SNES, PetscBool *);
PETSC_INTERN PetscErrorCode SSStarGlobalizationFixedPoint(SNES, PetscReal, PetscBool *);
PETSC_INTERN PetscErrorCode SSStarGlobalizationView(SSStarGlobalization *, PetscViewer);
PETSC_INTERN PetscErrorCode SSStarGlobalizationViewCounts(SSStarGlobalization *, PetscViewer);
PETSC_INTERN PetscErrorCode SSStarGlobalizationFormatEvents(SSStarGlobalization *, char[], size_t);
PETSC_INTERN PetscErrorCode SSStarGlobalizationDestroy(SSStarGlobalization *);

#endif
