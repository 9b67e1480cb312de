#ifndef SSSTARSCENEIMPL_H
#define SSSTARSCENEIMPL_H

#include <ssstarcontact.h>
#include "obstacle.h"

#define SSSTAR_GROUP_NAME_LEN 128

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

/* A group with a vector of values: -traction_<G> (3), -material_<G> E,nu (2), -spring_<G> k (1) */
typedef struct {
  char      name[SSSTAR_GROUP_NAME_LEN];
  PetscReal value[3];
} SSStarGroupValues;

/* A contact group: its rigid obstacle and its friction law */
typedef struct {
  char              name[SSSTAR_GROUP_NAME_LEN];
  SSStarObstacle    obstacle;           /* -obstacle_<G>: a plane, ball, cylinder or mesh (obstacle.c) */
  SSStarFrictionLaw law;
  PetscBool         lawSet, phiSet, boundSet; /* -friction_law_<G>, -friction_<G>, -slip_bound_<G> given */
  PetscReal         phi, bound;         /* Coulomb coefficient, Tresca slip bound (a force)      */
  PetscInt          nodes;              /* contact nodes of the group (global)                  */
  PetscReal         gapMin, gapMax;     /* initial gaps of its nodes                            */
  char              master[SSSTAR_GROUP_NAME_LEN]; /* -contact_pair_<G> H: the master surface (empty: an obstacle) */
} SSStarContactGroup;

/* How a pair's slave nodes are compared with the master surface (-pair_discretization) */
typedef enum {
  SSSTAR_PAIR_NODE_TO_SURFACE,
  SSSTAR_PAIR_DUAL_MORTAR
} SSStarPairDiscretization;
PETSC_INTERN const char *const SSStarPairDiscretizations[];

struct _n_SSStarScene {
  MPI_Comm comm;

  /* the description (options) */
  char               mesh[PETSC_MAX_PATH_LEN], geo[PETSC_MAX_PATH_LEN];
  PetscInt           level;
  PetscReal          meshScale;
  PetscReal          E, nu;
  PetscBool          hasE, hasNu;
  PetscInt           nMaterials, nTractions, nSprings, nDirichlet, nContact;
  SSStarGroupValues *materials, *tractions, *springs;
  char             **dirichlet;
  SSStarContactGroup *contact;
  PetscBool          hasGravity;
  PetscReal          gravity[3], density;

  /* set up */
  DM       dm;
  Vec      tags;          /* file index of each local vertex                                      */
  PetscInt nodesGlobal;   /* mesh nodes                                                           */
  PetscInt cellsGlobal;

  /* the owned contact nodes, in vertex order (their global dofs increase) */
  PetscInt   n, nGlobal;
  PetscInt  *tag;         /* index of the node in the mesh file                                   */
  PetscInt  *group;       /* its contact group                                                    */
  PetscReal *coords;      /* 3 per node                                                           */
  PetscReal *normal;      /* 3 per node: the normal of its plane                                  */
  PetscReal *gap;         /* initial distance to its plane                                        */
  PetscReal *area;        /* tributary area (a third of the adjacent faces of its group)         */
  IS         isC;         /* the 3 global dofs of each node                                       */

  /* bodies and contact pairs (pairs.c) */
  PetscInt   nPairs;      /* contact groups with -contact_pair_<G>                                */
  SSStarPairDiscretization pairMethod; /* -pair_discretization                                      */
  PetscInt   pairFallback; /* dual mortar: slave nodes the master does not cover (node-to-surface)  */
  PetscInt   nBodies;     /* connected components of the mesh                                     */
  PetscInt  *body;        /* per local vertex: its body (the smallest file index of its nodes)    */
  Mat        B;           /* with pairs: the contact operator, 3 rows (t1, t2, n) per contact node */
  PetscReal *frame;       /* with pairs: the frame of each contact node (9, rows t1, t2, n)       */
  PetscReal *weight;      /* with pairs: per node the master dofs (3, -1: none) and weights (3)   */
};

PETSC_INTERN PetscErrorCode SSStarMeshLoad(MPI_Comm, const char[], PetscInt, const SSStarGroupUse[], DM *, Vec *);
PETSC_INTERN PetscErrorCode SSStarMeshLoadCached(MPI_Comm, const char[], PetscInt, const SSStarGroupUse[], DM *, Vec *);
PETSC_INTERN PetscErrorCode SSStarMeshCacheFromModel(const char[]);
PETSC_INTERN PetscErrorCode SSStarMeshCellVertices(DM, PetscInt, PetscInt[4]);
PETSC_INTERN PetscErrorCode SSStarMeshCreateSection(DM, PetscInt, char *const[]);
PETSC_INTERN PetscErrorCode SSStarMeshScale(DM, PetscReal);
PETSC_INTERN PetscErrorCode SSStarAssembleElasticity(SSStarScene, Mat *, Vec *);
PETSC_INTERN PetscErrorCode SSStarAddTraction(DM, const char[], const PetscReal[3], Vec);

PETSC_INTERN PetscErrorCode SSStarPairsReadOption(SSStarScene, SSStarContactGroup *, const char[]);
PETSC_INTERN PetscErrorCode SSStarPairsCheckOptions(SSStarScene);
PETSC_INTERN PetscErrorCode SSStarSceneFindBodies(SSStarScene);
PETSC_INTERN PetscErrorCode SSStarPairsSetUp(SSStarScene);
PETSC_INTERN PetscErrorCode SSStarSceneContactKinematics(SSStarScene, Vec, Vec, PetscReal[], PetscReal[], PetscReal[], PetscReal[]);

#endif
