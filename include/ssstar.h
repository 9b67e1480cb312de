#ifndef SSSTAR_H
#define SSSTAR_H

/*
   ssstar: the semismooth* Newton method for 3D static contact with Coulomb friction
   (Gfrerer, Mandlmayr, Outrata, Valdman) as a PETSc SNES type.

   Whole body: the SNES function is F(u) = K u - b and the Jacobian K (SPD); SNESSSStarSetContactNodes()
   names the dofs of the contact nodes, the obstacle's normal and the initial gap of each. The solver
   reduces K to the contact dofs (a Schur complement P, load f) or keeps the whole body (reduction none,
   P never formed), solves the contact problem in the nodes' frames and returns the whole u.
   Reduced: without SNESSSStarSetContactNodes() every dof is a contact dof, the SNES function is
   c(u) = P u - f (or P u with SNESSolve(snes, f, u)) and the Jacobian P, on 3-blocks (u_t1, u_t2, u_n).
   In both, 0 in c(u) + Q(u) with non-penetration u_n + gap >= 0 and Q the friction law
   (docs/derivation.md section 0). Any other F(u) with its Jacobian J(u) (SNESSetFunction(), SNESSetJacobian()) is
   treated as nonlinear unless declared affine (SNESSSStarSetAffine()): the iteration evaluates F at its iterates and
   J again as -snes_lag_jacobian says, on the whole body (docs/derivation.md section 17).
*/
#include <petscsnes.h>
#include <ssstarreduction.h>

#if defined(PETSC_USE_COMPLEX)
  #error "ssstar needs a PETSc with real scalars"
#endif

#define SNESSSSTAR "ssstar"

#define SSSTAR_VERSION_MAJOR 0
#define SSSTAR_VERSION_MINOR 3
#define SSSTAR_VERSION_SUBMINOR 0

/* The contact states of Table 1 (docs/derivation.md section 2); values are written to output files. */
typedef enum {
  SSSTAR_STATE_L   = 0, /* no contact                                             */
  SSSTAR_STATE_M1  = 1, /* strong contact, sliding                                */
  SSSTAR_STATE_M2  = 2, /* weak contact, sliding                                  */
  SSSTAR_STATE_M3P = 3, /* strong contact, strong sticking                        */
  SSSTAR_STATE_M3M = 4, /* strong contact, weak sticking                          */
  SSSTAR_STATE_M4  = 5, /* weak contact, weak sticking                            */
  SSSTAR_STATE_LS  = 6  /* no contact, tangentially stuck (Tresca only: |r_t| < s) */
} SSStarState;
#define SSSTAR_NUM_STATES 7
PETSC_EXTERN const char *const SSStarStateNames[];

/*
   The friction laws: a table of laws registered by name (SSStarLawRegisterAll(), one file per law in
   src/snes/impls/ssstar/laws/); a law's index is its place in the table (the code of /contact/friction_law)
*/
#define SSSTARLAWNONE        "none"        /* frictionless: r_t = 0                                                  */
#define SSSTARLAWTRESCA      "tresca"      /* |r_t| <= s, a given slip bound s (a force), whatever r_n               */
#define SSSTARLAWCOULOMB     "coulomb"     /* |r_t| <= phi r_n                                                       */
#define SSSTARLAWORTHOTROPIC "orthotropic" /* |M^-1/2 r_t| <= r_n: phi_1 along a given direction, phi_2 across it   */
/* a node's value of a law parameter that is not given (SNESSSStarSetNodeLawParameter(); for a direction its first
   component): NaN, which no parameter takes (PETSC_DEFAULT, -2, is a direction's component like any other) */
#define SSSTAR_NOT_GIVEN ((PetscReal)NAN)
typedef struct _n_SSStarLaw *SSStarLaw;
/* What a law's parameter is: a coefficient (a number >= 0), a force (>= 0) or a direction (x, y, z in global axes) */
typedef enum {
  SSSTAR_LAW_COEFFICIENT,
  SSSTAR_LAW_FORCE,
  SSSTAR_LAW_DIRECTION
} SSStarLawParameterKind;
PETSC_EXTERN const char *const SSStarLawParameterKinds[];
PETSC_EXTERN PetscErrorCode SSStarLawRegister(const char[], PetscErrorCode (*)(SSStarLaw));
PETSC_EXTERN PetscErrorCode SSStarLawRegisterAll(void);
PETSC_EXTERN PetscErrorCode SSStarLawGetNames(PetscInt *, const char *const *[]);
PETSC_EXTERN PetscErrorCode SSStarLawGetIndex(const char[], PetscInt *);
PETSC_EXTERN PetscErrorCode SSStarLawGetInfo(PetscInt, const char *[], const char *[], PetscInt *, const char *const *[]);
PETSC_EXTERN PetscErrorCode SSStarLawHasParameter(PetscInt, const char[], PetscBool *);
PETSC_EXTERN PetscErrorCode SSStarLawGetParameterSize(const char[], PetscInt *);
PETSC_EXTERN PetscErrorCode SSStarLawGetParameterNames(PetscInt *, const char *const *[]);
PETSC_EXTERN PetscErrorCode SSStarLawGetParameterInfo(const char[], SSStarLawParameterKind *, PetscInt *, const char *[], const char *[], PetscBool *, PetscReal *);

/* Why an ssstar solve stopped, finer than SNESConvergedReason. */
typedef enum {
  SSSTAR_REASON_ITERATING = 0,
  SSSTAR_REASON_CONVERGED_ABS,    /* ||z|| <= atol, and the law residual rho <= max(rtol, law_rtol) */
  SSSTAR_REASON_CONVERGED_REL,    /* ||z|| <= rtol max(||u||, ||gamma f||), and the same rho         */
  SSSTAR_REASON_MAX_IT,           /* no convergence within -snes_max_it                            */
  SSSTAR_REASON_NAN,              /* ||z|| is NaN or Inf                                           */
  SSSTAR_REASON_SINGULAR_NEWTON,  /* the reduced Newton matrix S P + T is singular, even regularized */
  SSSTAR_REASON_STAGNATION,       /* ||z|| has not decreased for -snes_ssstar_stagnation_its          */
  SSSTAR_REASON_CYCLE,            /* the iterates cycle (period 2) and the remedies did not break it  */
  SSSTAR_REASON_LAW_STALLED,      /* ||z|| met its threshold, the law residual of the iterate stalled above its own */
  SSSTAR_REASON_NO_EQUILIBRIUM,   /* no contact forces the friction laws allow balance the load on a floating body */
  SSSTAR_REASON_USER,             /* a convergence test set with SNESSetConvergenceTest() decided     */
  SSSTAR_REASON_NOT_AFFINE        /* a residual declared affine is not: F at the solution is off the affine model's */
} SSStarReason;
PETSC_EXTERN const char *const SSStarReasons[];

/* What the globalization did to keep the iteration going (counted per solve; -snes_view, -snes_ssstar_monitor_states) */
typedef enum {
  SSSTAR_REMEDY_DAMPED,      /* a damped Newton step: the full step did not decrease ||z|| enough           */
  SSSTAR_REMEDY_FULL_STEP,   /* the full Newton step taken although no damping decreased ||z||           */
  SSSTAR_REMEDY_RESCALE,     /* the scaling gamma of the approximation step doubled (also breaks cycles) */
  SSSTAR_REMEDY_REGULARIZED, /* a Newton step with the normal-tangential coupling dropped (singular matrix) */
  SSSTAR_REMEDY_FIXED_POINT, /* approximation-step fixed-point iterations (no Newton step exists)        */
  SSSTAR_NUM_REMEDIES
} SSStarRemedy;
PETSC_EXTERN const char *const SSStarRemedies[];

/* The iteration of an ssstar solve */
typedef enum {
  SSSTAR_METHOD_NEWTON,     /* the semismooth* Newton method: approximation step, then Newton step (default) */
  SSSTAR_METHOD_FIXEDPOINT  /* the first-order baseline: u <- u + z, the approximation step alone            */
} SSStarMethod;
PETSC_EXTERN const char *const SSStarMethods[];

PETSC_EXTERN PetscErrorCode SSStarInitializePackage(void);
PETSC_EXTERN PetscErrorCode SSStarFinalizePackage(void);
PETSC_EXTERN PetscErrorCode SSStarGetVersionNumber(PetscInt *, PetscInt *, PetscInt *);

/* What ssstar's programs promise a scripted user: unknown options refused, a failed solve said by the exit status and the file */
#define SSSTAR_EXIT_NOT_CONVERGED 2 /* the exit status of a program whose solve did not converge (bad input: PETSc's error code) */
PETSC_EXTERN PetscErrorCode SSStarCheckOptionsUsed(MPI_Comm, const char *const[], SNES);
PETSC_EXTERN PetscErrorCode SSStarCheckOptionsUsedOf(MPI_Comm, PetscInt, const char *const[], const char *const[], SNES);
PETSC_EXTERN PetscErrorCode SSStarWriteOutcome(SNES, PetscViewer);
PETSC_EXTERN PetscErrorCode SSStarPushErrorHandler(void);
PETSC_EXTERN PetscErrorCode SSStarOptionsNameBadValue(const char[], char[], size_t);

/* Checks of a local condition that end every rank with the message of the first rank that failed */
PETSC_EXTERN PetscErrorCode SSStarCheckAllRanks(MPI_Comm, PetscErrorCode, const char[]);

/* The memory of the largest rank, now and at its peak (bytes): the progress lines and the summaries of the programs */
PETSC_EXTERN PetscErrorCode SSStarMemoryGetUsage(MPI_Comm, PetscLogDouble *, PetscLogDouble *);

/* The contact problem: the whole body (K u - b with contact nodes) or the reduced one (P u - f) */
PETSC_EXTERN PetscErrorCode SNESSSStarSetLinearProblem(SNES, Mat, Vec);
PETSC_EXTERN PetscErrorCode SNESSSStarSetContactNodes(SNES, IS, Vec, Vec);
PETSC_EXTERN PetscErrorCode SNESSSStarGetContactNodes(SNES, PetscInt *, IS *, Vec *, Vec *);
PETSC_EXTERN PetscErrorCode SNESSSStarSetContactOperator(SNES, IS, Mat, Vec);
PETSC_EXTERN PetscErrorCode SNESSSStarSetContactOffsets(SNES, Vec);
PETSC_EXTERN PetscErrorCode SNESSSStarGetContactOffsets(SNES, Vec *);
PETSC_EXTERN PetscErrorCode SNESSSStarGetReducedProblem(SNES, Mat *, Vec *);
PETSC_EXTERN PetscErrorCode SNESSSStarSetReductionType(SNES, SSStarReductionType);
PETSC_EXTERN PetscErrorCode SNESSSStarGetReductionType(SNES, SSStarReductionType *);
PETSC_EXTERN PetscErrorCode SNESSSStarSetMemoryLimit(SNES, PetscReal);

/* The residual: affine (K u - b, the Jacobian evaluated once) or nonlinear, and the contact measured at the iterates */
PETSC_EXTERN PetscErrorCode SNESSSStarSetAffine(SNES, PetscBool);
PETSC_EXTERN PetscErrorCode SNESSSStarGetAffine(SNES, PetscBool *);
PETSC_EXTERN PetscErrorCode SNESSSStarSetContactUpdate(SNES, PetscErrorCode (*)(SNES, Vec, void *), void *);
PETSC_EXTERN PetscErrorCode SNESSSStarGetNonlinearCounts(SNES, PetscInt *, PetscInt *);

/* The friction law and its parameters */
PETSC_EXTERN PetscErrorCode SNESSSStarSetFrictionLaw(SNES, const char[]);
PETSC_EXTERN PetscErrorCode SNESSSStarGetFrictionLaw(SNES, const char *[]);
PETSC_EXTERN PetscErrorCode SNESSSStarSetLawParameter(SNES, const char[], PetscInt, const PetscReal[]);
PETSC_EXTERN PetscErrorCode SNESSSStarSetFriction(SNES, PetscReal);
PETSC_EXTERN PetscErrorCode SNESSSStarGetFriction(SNES, PetscReal *);
PETSC_EXTERN PetscErrorCode SNESSSStarSetNodeLawParameter(SNES, const char[], Vec);
PETSC_EXTERN PetscErrorCode SNESSSStarSetNodeFrictionLaws(SNES, PetscInt, const PetscInt[]);
PETSC_EXTERN PetscErrorCode SNESSSStarGetNodeFrictionLaws(SNES, PetscInt, PetscInt[]);
PETSC_EXTERN PetscErrorCode SNESSSStarGetNodeLawParameter(SNES, const char[], PetscInt, PetscReal[]);

/* The method */
PETSC_EXTERN PetscErrorCode SNESSSStarSetScaling(SNES, PetscReal);
PETSC_EXTERN PetscErrorCode SNESSSStarGetScaling(SNES, PetscReal *);
PETSC_EXTERN PetscErrorCode SNESSSStarSetStateTolerance(SNES, PetscReal);
PETSC_EXTERN PetscErrorCode SNESSSStarSetMethod(SNES, SSStarMethod);
PETSC_EXTERN PetscErrorCode SNESSSStarGetMethod(SNES, SSStarMethod *);
PETSC_EXTERN PetscErrorCode SNESSSStarSetLUReuse(SNES, PetscReal);
PETSC_EXTERN PetscErrorCode SNESSSStarSetLUThreads(SNES, PetscInt);
PETSC_EXTERN PetscErrorCode SNESSSStarSetPCReuse(SNES, PetscReal);
PETSC_EXTERN PetscErrorCode SNESSSStarSetPlainAggregationDofs(SNES, PetscInt);
PETSC_EXTERN PetscErrorCode SNESSSStarSetSmoothedAggregationFits(SNES, PetscBool);
PETSC_EXTERN PetscErrorCode SNESSSStarSetMGOverCorrection(SNES, PetscReal, PetscInt);
PETSC_EXTERN PetscErrorCode SNESSSStarSetKSPRtolMax(SNES, PetscReal);
PETSC_EXTERN PetscErrorCode SNESSSStarSetKSPFloor(SNES, PetscReal);
PETSC_EXTERN PetscErrorCode SNESSSStarSetLawTolerance(SNES, PetscReal);
PETSC_EXTERN PetscErrorCode SNESSSStarGetLawResidual(SNES, PetscReal *, PetscReal *, PetscReal *, PetscReal *);
PETSC_EXTERN PetscErrorCode SNESSSStarGetNewtonStepCounts(SNES, PetscInt *, PetscInt *, PetscInt *);
PETSC_EXTERN PetscErrorCode SNESSSStarGetConditionEstimate(SNES, PetscReal *);
PETSC_EXTERN PetscErrorCode SNESSSStarGetStates(SNES, const SSStarState *[], PetscInt[SSSTAR_NUM_STATES]);
PETSC_EXTERN PetscErrorCode SNESSSStarGetReason(SNES, SSStarReason *);
PETSC_EXTERN PetscErrorCode SNESSSStarGetTolerance(SNES, PetscReal *);
PETSC_EXTERN PetscErrorCode SNESSSStarSetCoarseLoadScale(SNES, SNES);
PETSC_EXTERN PetscErrorCode SNESSSStarGetUnbalancedMotion(SNES, Vec *, PetscInt *, PetscReal[3], PetscReal *);
PETSC_EXTERN PetscErrorCode SNESSSStarSetGlobalization(SNES, PetscBool, PetscReal, PetscInt);
PETSC_EXTERN PetscErrorCode SNESSSStarGetRemedyCounts(SNES, PetscInt[SSSTAR_NUM_REMEDIES]);
PETSC_EXTERN PetscErrorCode SNESSSStarReleaseWork(SNES);
PETSC_EXTERN PetscErrorCode SNESSSStarMonitorStates(SNES, PetscInt, PetscReal, PetscViewerAndFormat *);
PETSC_EXTERN PetscErrorCode SNESSSStarMonitorProgress(SNES, PetscInt, PetscReal, PetscViewerAndFormat *);
PETSC_EXTERN PetscErrorCode SNESSSStarMonitorProgressAdd(SNES);
PETSC_EXTERN PetscErrorCode SNESConvergedSSStar(SNES, PetscInt, PetscReal, PetscReal, PetscReal, SNESConvergedReason *, void *);

/*
   Per-node kernels: pure functions on 3-vectors in the node's frame (tangential components first, normal last).
   Matrices are 3x3, row-major.
*/
#define SSSTAR_LAW_MAX_VALUES 6
typedef struct {
  SSStarLaw law;
  PetscReal value[SSSTAR_LAW_MAX_VALUES]; /* the law's parameters in its order (SSStarLawGetInfo()); a force in the
                                             units of the kernels' c (times gamma), a direction in the node's frame */
} SSStarFriction;
PETSC_EXTERN PetscErrorCode SSStarFrictionSet(SSStarFriction *, const char[], PetscInt, const PetscReal[]);

/* Approximation step (11)-(12), docs/derivation.md section 1: from the iterate u and c = P u - f. */
PETSC_EXTERN void SSStarApproximationStep(const SSStarFriction *, const PetscReal u[3], const PetscReal c[3], PetscReal z[3], PetscReal d[3], PetscReal b[3]);
/* Table 1 for (d, b) in gph Q, section 2. */
PETSC_EXTERN SSStarState SSStarClassify(const SSStarFriction *, const PetscReal d[3], const PetscReal b[3], PetscReal tol_d, PetscReal tol_b);
/* G, H with range [G; H] = tangent space of gph Q at (d, b), section 3. */
PETSC_EXTERN void SSStarTangentBlocks(SSStarState, const SSStarFriction *, const PetscReal d[3], const PetscReal b[3], PetscReal G[9], PetscReal H[9]);
/* S, T of the 3p Newton system (S P + T) du = (S + T) z, section 5. */
PETSC_EXTERN void SSStarReducedBlocks(SSStarState, const SSStarFriction *, const PetscReal d[3], const PetscReal b[3], PetscReal S[9], PetscReal T[9]);
/* The node's frame from the obstacle's normal n (into the body): rows t1, t2, n of R; R = I for n = (0, 0, 1). */
PETSC_EXTERN void SSStarNodeFrame(const PetscReal n[3], PetscReal R[9]);

#endif
