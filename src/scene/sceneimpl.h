#ifndef SSSTARSCENEIMPL_H
#define SSSTARSCENEIMPL_H

#include <ssstarscene.h>
#include <ssstarhistory.h>
#include "contact/obstacles/obstacle.h"
#include <ssstargeometry.h>

#define SSSTAR_GROUP_NAME_LEN 128

typedef struct _n_SSStarSceneOutput *SSStarSceneOutput; /* output/outputimpl.h */

/* The kind of physical group an option needs */
typedef enum {
  SSSTAR_GROUP_ANY,     /* a surface or a volume */
  SSSTAR_GROUP_SURFACE,
  SSSTAR_GROUP_VOLUME
} SSStarGroupKind;

/* A group named by an option, to check in the mesh */
typedef struct {
  const char     *group;
  const char     *option;
  SSStarGroupKind kind;
} SSStarGroupUse;

/*
   A group with a vector of values: -traction_<G> (3), -material_<G> E,nu (2), -spring_<G> k (1). A traction is a load
   history (a constant without knots; docs/load-paths.md), value its value at the last knot.
*/
typedef struct {
  char          name[SSSTAR_GROUP_NAME_LEN];
  PetscReal     value[3];
  PetscInt      count;   /* the values given (-material_<G> E,nu or E,nu,rho) */
  SSStarHistory history; /* a traction's; NULL for the others */
} SSStarGroupValues;

/*
   A group whose displacement is prescribed (-displacement_<G> x,y,z; prescribed.c): each component a number or free,
   constant or a history of knots t:x,y,z;... (a component free in one knot is free in all); or rotated rigidly
   (-rotation_<G> rx,ry,rz about -rotation_center_<G>: the rotation vector in degrees, every component prescribed)
*/
typedef struct {
  char          name[SSSTAR_GROUP_NAME_LEN];
  SSStarHistory history;   /* 3 components; a free one is 0 in it; a rotation's: the rotation vector */
  PetscInt      free;      /* bit k: component k is free */
  PetscBool     rotation;  /* -rotation_<G> */
  PetscReal     center[3]; /* its center */
} SSStarPrescribed;

/* The material model of a volume group (-material_model_<G>) */
typedef struct {
  char                name[SSSTAR_GROUP_NAME_LEN];
  SSStarMaterialModel model;
} SSStarGroupModel;

/* A parameter of a contact group's friction law, given as -<parameter>_<G> (a name of SSStarLawGetParameterNames()) */
typedef struct {
  char      name[64];
  PetscInt  size;     /* its values: 1, or 3 for a direction */
  PetscReal value[3];
} SSStarGroupParameter;

/* Where a moving obstacle is (contact/motion.c): x = Q (X - c) + c + d for a point X of the obstacle, Q row-major */
typedef struct {
  PetscReal Q[9], d[3];
} SSStarPlacement;

/* The motion of a contact group's rigid obstacle (contact/motion.c, docs/derivation.md section 16) */
typedef struct {
  SSStarHistory   translation; /* -obstacle_<G>_motion: d(t), or NULL                                   */
  SSStarHistory   rotation;    /* -obstacle_<G>_rotation: t:ax,ay,az,angle (radians), or NULL            */
  PetscReal       center[3];   /* the obstacle's reference point c, about which it turns               */
  SSStarPlacement now, before; /* in the step being solved, and after the last accepted one            */
} SSStarMotion;
PETSC_INTERN void           SSStarPlacementIdentity(SSStarPlacement *);
PETSC_INTERN void           SSStarRotation(const PetscReal[3], PetscReal, PetscReal[9]);
PETSC_INTERN void           SSStarPlacementApply(const SSStarPlacement *, const PetscReal[3], const PetscReal[3], PetscReal[3]);
PETSC_INTERN void           SSStarPlacementInverse(const SSStarPlacement *, const PetscReal[3], const PetscReal[3], PetscReal[3]);
PETSC_INTERN PetscBool      SSStarPlacementEqual(const SSStarPlacement *, const SSStarPlacement *);
PETSC_INTERN PetscBool      SSStarMotionIsSet(const SSStarMotion *);
PETSC_INTERN PetscErrorCode SSStarMotionPlacementAt(const SSStarMotion *, PetscReal, SSStarPlacement *);
PETSC_INTERN PetscErrorCode SSStarMotionRotationVector(const SSStarMotion *, PetscReal, PetscReal[3]);
PETSC_INTERN PetscErrorCode SSStarMotionReadRotation(MPI_Comm, const char[], SSStarHistory *);
PETSC_INTERN PetscErrorCode SSStarMotionCheckRotation(MPI_Comm, const char[], SSStarHistory);
PETSC_INTERN PetscErrorCode SSStarMotionDestroy(SSStarMotion *);

/* A contact group: its contact source (a rigid obstacle, or the master surface of a pair) and its friction law */
typedef struct {
  char              name[SSSTAR_GROUP_NAME_LEN];
  SSStarObstacle    obstacle;           /* -obstacle_<G>: a registered shape (obstacle.c, obstacles/)   */
  PetscInt          law;                /* its friction law: an index of the table of laws (SSStarLawGetNames()) */
  PetscBool         lawSet;             /* -friction_law_<G> given                              */
  PetscInt          nparams;            /* the parameters given for G (grouplaws.c); the others are the solver's */
  SSStarGroupParameter *params;
  PetscInt          nodes;              /* contact nodes of the group (global)                  */
  PetscReal         gapMin, gapMax;     /* initial gaps of its nodes                            */
  char              master[SSSTAR_GROUP_NAME_LEN]; /* -contact_pair_<G> H: the master surface (empty: an obstacle) */
  SSStarMotion      motion;             /* its rigid obstacle's translation and rotation (none for a pair)         */
} SSStarContactGroup;

/* Where a load path measures the contact (-sliding): at the current configuration of each step, or at the reference */
typedef enum {
  SSSTAR_SLIDING_LARGE,
  SSSTAR_SLIDING_SMALL
} SSStarSliding;
PETSC_INTERN const char *const SSStarSlidings[];

/* How a pair's slave nodes are compared with the master surface (-pair_discretization) */
typedef enum {
  SSSTAR_PAIR_NODE_TO_SURFACE,
  SSSTAR_PAIR_DUAL_MORTAR
} SSStarPairDiscretization;
PETSC_INTERN const char *const SSStarPairDiscretizations[];

/* Where SSStarSceneAdvance() is on the way to its target (path/solve.c) */
typedef struct {
  PetscBool active;    /* a target is being reached                            */
  PetscReal target, t; /* the target time, the time of the next step            */
  PetscReal dt;        /* the sub-step after a cut, 0 before                    */
  PetscInt  cuts;      /* the halvings of this target's step                    */
} SSStarStepper;

/* Elastodynamics (dynamics/, docs/derivation.md section 16) */
typedef struct _n_SSStarDynamics *SSStarDynamics;
typedef enum {
  SSSTAR_DYNAMICS_STABILIZED, /* the predictor projected onto the admissible set (16.5): no energy gained at contact */
  SSSTAR_DYNAMICS_NEWMARK     /* the trapezoidal step (16.6) from the predictor as it is                        */
} SSStarDynamicsScheme;
PETSC_INTERN const char *const SSStarDynamicsSchemes[];

struct _n_SSStarScene {
  MPI_Comm comm;

  /* the description (options) */
  char               mesh[PETSC_MAX_PATH_LEN], geo[PETSC_MAX_PATH_LEN];
  char               meshCache[PETSC_MAX_PATH_LEN]; /* -mesh_cache: where meshes of -geo go ("": the default) */
  PetscInt           level;
  PetscInt           refine;    /* -dm_refine: refinements of the mesh in parallel (meshrefine.c)              */
  PetscInt           nested;    /* -nested_levels: coarser meshes solved first (nested.c); -1 auto             */
  PetscBool          smoothedFits; /* the estimate before the work: the multigrid's smoothed aggregation fits the memory */
  PetscBool          plain;        /* and the multigrid aggregates plainly (by K's size or by the memory)            */
  PetscReal          meshScale;
  PetscBool          progress;  /* -ssstar_progress: a line as each phase ends (SSStarSceneProgress())         */
  PetscReal          E, nu;
  PetscBool          hasE, hasNu;
  SSStarMaterialModel model;       /* -material_model: of the cells without -material_model_<G>                 */
  PetscInt           nModels;      /* -material_model_<G> groups                                               */
  SSStarGroupModel  *models;
  PetscBool          affine;       /* every model linear: F(u) = K u - b (residual.c)                          */
  Vec                problemLoad;  /* a hyperelastic scene: the load of SSStarSceneSetProblem(), F(u) = f(u) - load */
  Mat                Kref;         /* and its reference K' (the predictor of prescribed displacements, residual.c) */
  KSP                predictor;    /* its solver                                                               */
  PetscInt           nMaterials, nTractions, nSprings, nDirichlet, nContact, nVelocities;
  SSStarGroupValues *materials, *tractions, *springs, *velocities; /* velocities: -initial_velocity_<G> */
  char             **dirichlet;
  SSStarContactGroup *contact;
  PetscBool          hasGravity, hasDensity;
  SSStarDynamics     dynamics; /* -dynamics, or NULL                                                 */
  PetscReal          endTime;  /* -end_time: the end of a path without knots (-steps N), 0 without     */
  PetscReal          gravity[3], density; /* gravity: its value at the last knot of its history */
  SSStarHistory      gravityHistory;
  PetscInt           nDisplacements; /* -displacement_<G> groups, in the order of the options database */
  SSStarPrescribed  *displacements;

  /* set up */
  DM       dm;
  Vec      tags;          /* file index of each local vertex                                      */
  PetscInt nodesGlobal;   /* mesh nodes                                                           */
  PetscInt cellsGlobal;

  /*
     the held dofs (prescribed.c): the groups that hold nodes, -dirichlet's then -displacement_<G>'s ("held group" h:
     h < nDirichlet the -dirichlet group h, else the -displacement group h - nDirichlet); a -dirichlet node has no dofs
     (the section's constraints), a prescribed component of a -displacement node keeps its dof with an identity row of
     K (docs/derivation.md section 15)
  */
  PetscInt *heldBy;       /* 3 per local vertex: the held group of each component (the first), or -1 (free)   */
  Vec       diagK;        /* K's diagonal: b = diag(K) g at the dofs of prescribed components                   */
  Vec       lastLoad;     /* the load SSStarAssembleLoad() assembled last (a copy), to find a load's factor     */
  PetscReal loadFree[3];  /* of that load: the resultant of the tractions and gravity on the dofs not held        */
  PetscReal *loadHeld;    /* and on the held dofs of each held group (3 per held group)                          */
  char     **heldNames;   /* the held groups' names (SSStarSceneGetHeldGroups())                                */

  /* the owned contact nodes, in vertex order (their global dofs increase) */
  PetscInt   n, nGlobal;
  PetscInt  *tag;         /* index of the node in the mesh file                                   */
  PetscInt  *group;       /* its contact group                                                    */
  PetscReal *coords;      /* 3 per node                                                           */
  PetscReal *normal;      /* 3 per node: the normal of its obstacle or master surface, into the body */
  PetscReal *gap;         /* its initial normal gap to it                                        */
  PetscReal *area;        /* tributary area (a third of the adjacent faces of its group)         */
  PetscReal *obstaclePoint; /* 3 per node: the point of its obstacle it faces (closest), where the obstacle's option
                               puts it (the obstacle unmoved): its friction sees that point's motion (motion.c) */
  PetscInt  *contactHeld; /* 3 per node: the held group of each component (prescribed.c), or -1     */
  IS         isC;         /* the 3 global dofs of each node                                       */

  /* bodies (bodies.c) and contact pairs (pairs.c, mortar.c) */
  PetscInt   nPairs;      /* contact groups with -contact_pair_<G>                                */
  SSStarPairDiscretization pairMethod; /* -pair_discretization                                      */
  PetscInt   pairFallback; /* dual mortar: slave nodes the master does not cover (node-to-surface)  */
  PetscInt   nBodies;     /* connected components of the mesh                                     */
  PetscInt  *body;        /* per local vertex: its body (the smallest file index of its nodes)    */
  PetscInt   nFloating;   /* bodies held by contact alone: their rigid-body motions are K's null space */
  PetscInt  *floating;    /* their bodies (values of body[])                                      */
  char     **floatingName; /* "volume group \"block\" (the mesh nodes connected to node 0, ...)" */

  /* the contact operator (operator.c): 3 rows (t1, t2, n) per contact node, B_i = R_i (E_i - sum_j w_ij E_{m_j}) */
  PetscReal *frame;        /* R_i, 9 per node (rows t1, t2, n): the frame of its normal            */
  PetscInt  *masterStart;  /* n + 1: the masters of node i are masterStart[i] .. masterStart[i + 1] - 1 */
  PetscInt  *masterDof;    /* the x-dof of a master vertex m_j (y, z follow); none for a rigid obstacle */
  PetscReal *masterWeight; /* w_ij                                                                 */
  Mat        B;

  /* a load path (path.c, docs/derivation.md section 10): the step being solved and what the accepted steps left */
  PetscReal  stepTime;      /* the time of the step SSStarSceneSetStep() set                         */
  PetscReal  load[3];       /* the resultant of the load SSStarSceneAssembleLoad() assembled last       */
  PetscBool  stepped;       /* a step was accepted: the arrays below hold its kinematics              */
  PetscInt   accepted;      /* the steps accepted (SSStarSceneAcceptStep())                           */
  SSStarSliding sliding;     /* -sliding                                                                */
  PetscReal  smallSlidingTol; /* -small_sliding_tol: the first-order gap's error allowed, relative to |d| */
  Vec        uAccepted;     /* large sliding: the solution of the last accepted step (0 before)        */
  PetscReal  slidingTol;    /* -sliding_tol: the geometric error of a step, relative to its normal displacements */
  PetscInt   slidingMaxIt;  /* -sliding_max_it: linearizations of a step at its solution                */
  PetscInt   relinearizations; /* those of the step being solved                                      */
  PetscBool  lastLinearization; /* the linearization and solver states are the last accepted step's        */
  PetscReal *gapInitial;    /* the gaps of the reference configuration (scene->gap: of the step)       */
  PetscReal *slipPrev;      /* w_t after the last accepted step, 2 per node (frame)                   */
  PetscReal *slipIncrement; /* its increment in that step, 2 per node (frame)                         */
  PetscReal *slipPath;      /* the length of the slip path, per node                                  */
  PetscReal *dissipation;   /* the energy friction dissipated, per node (10.9)                        */
  Vec        offsets;       /* the offsets (10.4) handed to the SNES                                  */
  Vec        stepLoad;      /* the SNES's load, which a step assembles (SSStarSceneSetSolver())        */
  SNES       solver;        /* the SNES of SSStarSceneSetSolver() (not a reference)                    */
  Vec        stepStart;     /* the solution of the last accepted step, where the next one starts      */
  PetscReal  acceptedTime;  /* the time of the last accepted step                                    */
  SSStarStepper stepper;    /* SSStarSceneAdvance()'s way to its target                               */
  PetscInt   nSurfaces;     /* named surface groups whose mean displacement the output follows       */
  char     **surfaces;
  Vec       *surfaceWeights; /* per surface: its consistent load of a unit traction (area / 3 per node) */
  PetscReal *surfaceAreas;
  SSStarSceneOutput output; /* a file being written step by step, or NULL */
};

PETSC_INTERN PetscErrorCode SSStarMeshLoad(MPI_Comm, const char[], PetscInt, const SSStarGroupUse[], PetscInt, DM *, Vec *);
PETSC_INTERN PetscErrorCode SSStarMeshLoadCached(MPI_Comm, const char[], PetscInt, const SSStarGroupUse[], PetscInt, DM *, Vec *);
/*
   A mesh in slices (meshcache.c reads them, meshrefine.c refines them): rank r holds the vertices [v0, v0 + nv) of the
   NV (SSStarSliceStart()), some cells and some triangles of the surface groups, by global vertex numbers
*/
typedef struct {
  PetscInt   NV, v0, nv;
  PetscReal *coords;     /* 3 per vertex of the slice                                        */
  PetscInt   nc, *cells; /* 4 vertices per cell                                               */
  long long *cellGroups; /* per cell: bit g set when it is in the g-th volume group (with cells: PetscMalloc2) */
  PetscInt   ntri, *tri; /* 3 vertices (sorted) and -1 - group per triangle                   */
} SSStarMeshSlices;
PETSC_INTERN PetscErrorCode SSStarMeshRefine(MPI_Comm, SSStarMeshSlices *);
PETSC_INTERN PetscErrorCode SSStarMeshInterpolate(DM, Vec, DM, Vec);
PETSC_INTERN PetscLogDouble SSStarPeakFrom(PetscMPIInt, PetscReal, PetscLogDouble, PetscBool);
PETSC_INTERN PetscErrorCode SSStarEstimateWholeBody(MPI_Comm, PetscReal, PetscLogDouble, PetscLogDouble *, PetscBool *, PetscBool *, PetscLogDouble *, PetscBool *);
PETSC_INTERN PetscErrorCode SSStarPlainAggregationBySize(PetscReal, PetscBool *);
PETSC_INTERN PetscLogDouble SSStarPeakDenseFrom(PetscMPIInt, PetscReal, PetscReal, PetscLogDouble);
PETSC_INTERN PetscMPIInt    SSStarSliceOwner(PetscInt, PetscInt, PetscMPIInt);
PETSC_INTERN PetscInt       SSStarSliceStart(PetscMPIInt, PetscInt, PetscMPIInt);
PETSC_INTERN PetscErrorCode SSStarExchange(MPI_Comm, const PetscMPIInt[], size_t, const void *, PetscMPIInt[], void **);
PETSC_INTERN PetscErrorCode SSStarMeshCacheFromModel(const char[]);
/* meshfaces.c: the faces of the cached mesh, and vertex triples matched over the ranks */
PETSC_INTERN PetscErrorCode SSStarMeshAddFaces(DM, const PetscInt[], DM *);
PETSC_INTERN PetscMPIInt    SSStarTripleHomeRank(const PetscInt[3], PetscMPIInt);
PETSC_INTERN int            SSStarTripleCompare(const void *, const void *);
PETSC_INTERN void           SSStarTripleSort(PetscInt[3]);
PETSC_INTERN PetscErrorCode SSStarTripleExchange(MPI_Comm, PetscInt, const PetscMPIInt[], const PetscInt[], PetscInt *, PetscInt **);
PETSC_INTERN PetscErrorCode SSStarMeshCellVertices(DM, PetscInt, PetscInt[4]);
PETSC_INTERN PetscErrorCode SSStarMeshCreateSection(DM, PetscInt, char *const[]);
PETSC_INTERN PetscErrorCode SSStarMeshScale(DM, PetscReal);
/* The local cells with their vertices and materials (cells.c) */
typedef struct {
  PetscInt           cStart, cEnd, vStart, vEnd;
  PetscInt          *vertices; /* 4 per cell, numbered from vStart */
  PetscReal        (*lame)[2]; /* lambda, mu per cell              */
  SSStarMaterialModel *model; /* the material model per cell     */
  PetscSection       csec;
  Vec                coordinates;
  const PetscScalar *ca;
} SSStarCells;
/* Adding cells' matrices straight into K's rows once K holds its pattern (blockadd.c) */
typedef struct {
  Mat             K, part[2];     /* K; its diagonal and off-diagonal parts (MPIAIJ), or K and NULL */
  PetscInt        bstart, bend;   /* the owned blocks                                               */
  PetscInt       *col;            /* per local vertex: its first column in the part it falls in     */
  PetscBool      *inB;            /* per local vertex: its columns are in the off-diagonal part     */
  const PetscInt *ia[2], *ja[2];
  PetscScalar    *va[2];
} SSStarBlockAdd;
PETSC_INTERN PetscErrorCode SSStarBlockAddBegin(Mat, PetscInt, const PetscInt[], SSStarBlockAdd *);
PETSC_INTERN PetscErrorCode SSStarBlockAddCell(SSStarBlockAdd *, const PetscInt[4], const PetscInt[4], const PetscScalar[144]);
PETSC_INTERN PetscErrorCode SSStarBlockAddEnd(SSStarBlockAdd *);
PETSC_INTERN PetscReal      SSStarTetGradients(const PetscReal[12], PetscReal[4][3]);
PETSC_INTERN void           SSStarTetStiffness(const PetscReal[12], PetscReal, PetscReal, PetscScalar[144]);
PETSC_INTERN PetscErrorCode SSStarCellMaterials(SSStarScene, PetscInt, PetscInt, PetscReal (*)[2], SSStarMaterialModel[], PetscReal[]);
PETSC_INTERN PetscReal      SSStarDeterminant3(const PetscReal[9]);
PETSC_INTERN PetscErrorCode SSStarMaterialModelFromName(MPI_Comm, const char[], const char[], PetscInt *);
PETSC_INTERN PetscErrorCode SSStarCellsBegin(SSStarScene, SSStarCells *);
PETSC_INTERN PetscErrorCode SSStarCellsGet(const SSStarCells *, PetscInt, PetscReal[12]);
PETSC_INTERN PetscErrorCode SSStarCellsGetValues(const SSStarCells *, PetscSection, const PetscScalar[], PetscInt, PetscReal[12]);
PETSC_INTERN PetscErrorCode SSStarCellsEnd(SSStarCells *);
/* Prescribed displacements (prescribed.c) */
PETSC_INTERN PetscErrorCode SSStarPrescribedRead(SSStarScene, const char[], const char[], const char[], SSStarPrescribed *);
PETSC_INTERN PetscErrorCode SSStarPrescribedReadRotation(SSStarScene, const char[], const char[], const char[], SSStarPrescribed *);
PETSC_INTERN PetscErrorCode SSStarPrescribedDestroy(SSStarScene);
PETSC_INTERN PetscErrorCode SSStarPrescribedText(const SSStarPrescribed *, char[], size_t);
PETSC_INTERN PetscErrorCode SSStarSceneFindHeld(SSStarScene);
PETSC_INTERN PetscErrorCode SSStarHeldName(SSStarScene, PetscInt, char[], size_t);
PETSC_INTERN PetscErrorCode SSStarHeldValues(SSStarScene, PetscReal, PetscReal[]);
PETSC_INTERN PetscBool      SSStarHeldIdentityRow(SSStarScene, PetscInt, PetscInt);
PETSC_INTERN void           SSStarHeldElement(SSStarScene, const PetscInt[4], PetscScalar[144]);
PETSC_INTERN PetscErrorCode SSStarHeldLocalValues(SSStarScene, const PetscReal[], Vec);
PETSC_INTERN PetscErrorCode SSStarHeldLift(SSStarScene, const SSStarCells *, Vec, Vec);
PETSC_INTERN PetscErrorCode SSStarHeldDiagonal(SSStarScene, Vec, Vec, PetscBool);
PETSC_INTERN PetscErrorCode SSStarSceneCheckPartlyHeld(SSStarScene);
PETSC_INTERN PetscErrorCode SSStarSetRigidBodyModes(SSStarScene, Vec, Mat);
PETSC_INTERN PetscErrorCode SSStarSceneLoadFactor(SSStarScene, Vec, PetscReal *);
PETSC_INTERN PetscErrorCode SSStarAssembleElasticity(SSStarScene, PetscReal, Mat *, Vec *);
PETSC_INTERN PetscErrorCode SSStarVertexBlocks(DM, PetscInt, PetscInt, PetscInt **);
PETSC_INTERN void           SSStarTetMass(PetscReal, PetscReal, PetscBool, PetscScalar[144]);
PETSC_INTERN PetscErrorCode SSStarAssembleMass(SSStarScene, Mat, PetscBool, Mat *);
PETSC_INTERN PetscErrorCode SSStarInitialVelocity(SSStarScene, const PetscReal[3], Vec);
PETSC_INTERN PetscErrorCode SSStarDynamicsSetFromOptions(SSStarScene);
PETSC_INTERN PetscErrorCode SSStarDynamicsSetUp(SSStarScene, SNES, Mat, Vec);
PETSC_INTERN PetscErrorCode SSStarDynamicsBeginStep(SSStarScene, PetscReal, Vec, PetscBool, SNESConvergedReason *);
PETSC_INTERN PetscErrorCode SSStarDynamicsAccept(SSStarScene, SNES, Vec, Vec);
PETSC_INTERN PetscErrorCode SSStarDynamicsGetVelocity(SSStarScene, Vec *);
PETSC_INTERN PetscErrorCode SSStarDynamicsView(SSStarScene, PetscViewer);
PETSC_INTERN PetscErrorCode SSStarDynamicsDescribe(SSStarScene, const char **, PetscBool *, PetscReal[2], PetscReal[3]);
PETSC_INTERN PetscErrorCode SSStarDynamicsDestroy(SSStarScene);
PETSC_INTERN PetscErrorCode SSStarAssembleResidual(SSStarScene, Vec, Vec, Vec, PetscBool *);
PETSC_INTERN PetscErrorCode SSStarAssembleTangent(SSStarScene, Vec, Mat, PetscBool *);
PETSC_INTERN PetscErrorCode SSStarAddTraction(DM, const char[], const PetscReal[3], Vec);
PETSC_INTERN PetscErrorCode SSStarAssembleLoad(SSStarScene, PetscReal, Vec);
PETSC_INTERN PetscErrorCode SSStarGroupArea(DM, const char[], PetscReal *);

/* What a contact source adds to the rows of B: the masters of its nodes (node, x-dof, weight), in any order */
typedef struct {
  PetscInt   n, max;
  PetscInt  *node, *dof;
  PetscReal *weight;
} SSStarMasters;
PETSC_INTERN PetscErrorCode SSStarMastersAdd(SSStarMasters *, PetscInt, PetscInt, PetscReal);
PETSC_INTERN PetscErrorCode SSStarMastersDestroy(SSStarMasters *);

/* The boundary faces as triangles (faces.c), at the reference or at a displaced configuration */
typedef struct {
  DM                 dm;
  PetscSection       csec, gsec, lsec;
  Vec                coordinates, tags, uLocal; /* uLocal: the displacement of every local vertex, or NULL */
  const PetscScalar *xa, *ta, *ua;
  PetscInt           vStart, vEnd, fStart, fEnd;
  PetscBool         *leaf; /* leaf[f]: face f is owned by another rank */
} SSStarFaces;
PETSC_INTERN PetscErrorCode SSStarFacesBegin(SSStarScene, Vec, SSStarFaces *);
PETSC_INTERN PetscErrorCode SSStarFacesEnd(SSStarFaces *);
PETSC_INTERN PetscErrorCode SSStarFaceTriangle(const SSStarFaces *, PetscInt, PetscReal[9], PetscInt[3], PetscInt[3], PetscInt *, PetscReal[3], PetscReal *);

/* A node an error is about (nodes.c): its file index, group (and another), coordinates and gap */
typedef struct {
  PetscInt  tag, group, other;
  PetscReal x[3], gap;
} SSStarBadNode;
PETSC_INTERN PetscErrorCode SSStarSceneProgress(SSStarScene, PetscLogDouble *, const char[]);
PETSC_INTERN PetscErrorCode SSStarSceneShareBadNode(MPI_Comm, SSStarBadNode *, PetscBool *);

PETSC_INTERN PetscErrorCode SSStarSceneLastValue(SSStarHistory, PetscReal[3]);
PETSC_INTERN PetscErrorCode SSStarSceneGroupUses(SSStarScene, PetscInt *, SSStarGroupUse **, char ***);
PETSC_INTERN PetscErrorCode SSStarSceneFindBodies(SSStarScene);
PETSC_INTERN PetscErrorCode SSStarSceneDestroyFloating(SSStarScene);
PETSC_INTERN PetscErrorCode SSStarSceneFindContactNodes(SSStarScene);
PETSC_INTERN PetscErrorCode SSStarSceneContactTolerance(SSStarScene, PetscReal *);
PETSC_INTERN PetscErrorCode SSStarSceneObstacleGaps(SSStarScene, PetscInt, const PetscInt[], const PetscReal[], const SSStarPlacement[], PetscReal, PetscReal[], PetscReal[]);
PETSC_INTERN void           SSStarSceneObstacleDisplacement(SSStarScene, PetscInt, const SSStarPlacement *, PetscReal[3]);
PETSC_INTERN PetscErrorCode SSStarSceneCheckSmallSliding(SSStarScene, PetscInt, PetscReal);
PETSC_INTERN PetscErrorCode SSStarSceneMeasureContact(SSStarScene, SNES);
PETSC_INTERN PetscErrorCode SSStarSceneMeasureContactAt(SSStarScene, SNES, Vec);
PETSC_INTERN PetscErrorCode SSStarSceneRelinearizeContact(SSStarScene, SNES, Vec, PetscBool *, PetscReal *, PetscReal *);
PETSC_INTERN PetscErrorCode SSStarSceneBuildContactOperator(SSStarScene, Vec);
PETSC_INTERN PetscErrorCode SSStarPairsReadOption(SSStarScene, SSStarContactGroup *, const char[]);
PETSC_INTERN PetscErrorCode SSStarPairsCheckOptions(SSStarScene);
PETSC_INTERN PetscErrorCode SSStarPairRows(SSStarScene, PetscInt, const PetscReal[], Vec, SSStarMasters *);
PETSC_INTERN PetscErrorCode SSStarMortarRows(SSStarScene, PetscInt, const PetscReal[], Vec, SSStarSearch, PetscReal, PetscBool[], SSStarMasters *);
PETSC_INTERN PetscErrorCode SSStarSceneNodeVec(SSStarScene, PetscInt, const PetscReal[], Vec *);

/* The friction law of a contact group (grouplaws.c) */
PETSC_INTERN PetscErrorCode SSStarGroupLawRead(SSStarScene, SSStarContactGroup *, const char[]);
PETSC_INTERN PetscErrorCode SSStarGroupLawReadParameter(SSStarScene, SSStarContactGroup *, const char[], const char[]);
PETSC_INTERN PetscErrorCode SSStarGroupLawCheck(SSStarScene, const SSStarContactGroup *);
PETSC_INTERN PetscErrorCode SSStarGroupLawDestroy(SSStarContactGroup *);
PETSC_INTERN PetscErrorCode SSStarGroupLawHelp(char[], size_t);
PETSC_INTERN PetscErrorCode SSStarGroupLawView(const SSStarContactGroup *, PetscViewer);
PETSC_INTERN PetscErrorCode SSStarSceneSetContactLaws(SSStarScene, SNES);
PETSC_INTERN PetscErrorCode SSStarSceneContactKinematics(SSStarScene, Vec, Vec, PetscReal[], PetscReal[], PetscReal[], PetscReal[]);
PETSC_INTERN PetscErrorCode SSStarSceneRelativeDisplacement(SSStarScene, Vec, PetscReal[]);
PETSC_INTERN PetscErrorCode SSStarSceneFollowSurfaces(SSStarScene);
PETSC_INTERN PetscErrorCode SSStarSceneSurfaceDisplacements(SSStarScene, Vec, PetscReal[]);
PETSC_INTERN PetscErrorCode SSStarScenePathDestroy(SSStarScene);

#endif
