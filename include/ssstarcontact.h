#ifndef SSSTARCONTACT_H
#define SSSTARCONTACT_H

/*
   The contact problem of an elastic body on a rigid plane z = 0: gmsh meshes on DMPlex, P1 linear
   elasticity, reduction of the stiffness to the contact dofs (P, f), recovery and output.
   Kept apart from the SNES type: any program can hand its own P, f to "ssstar".
*/
#include <petscdmplex.h>
#include <petscksp.h>
#include <ssstarreduction.h>

PETSC_EXTERN PetscLogEvent SSSTAR_Assembly;

/* Physical groups a mesh must have (by name): the Dirichlet face, two loaded faces, the contact face. */
#define SSSTAR_GROUP_DIRICHLET "dirichlet"
#define SSSTAR_GROUP_TOP       "top"
#define SSSTAR_GROUP_RIGHT     "right"
#define SSSTAR_GROUP_CONTACT   "contact"

typedef struct {
  PetscReal E, nu;              /* Young's modulus, Poisson ratio            */
  PetscReal traction_top[3];    /* constant traction on the group "top"      */
  PetscReal traction_right[3];  /* constant traction on the group "right"    */
} SSStarScene;

/* The owned contact nodes of a distributed mesh: group "contact" minus group "dirichlet". */
typedef struct {
  PetscInt   n;        /* owned contact nodes                                     */
  PetscInt  *tag;      /* index of the node in the mesh file (gmsh node order)     */
  PetscReal *coords;   /* 3n coordinates                                          */
  IS         isC, isI; /* owned global dofs of the contact nodes / of all others  */
} SSStarContactNodes;

PETSC_EXTERN PetscErrorCode SSStarMeshGeneratePrism(MPI_Comm, const char geo[], PetscInt level, const char msh[]);
PETSC_EXTERN PetscErrorCode SSStarMeshLoad(MPI_Comm, const char file[], DM *, Vec *);
PETSC_EXTERN PetscErrorCode SSStarMeshScale(DM, PetscReal);
PETSC_EXTERN PetscErrorCode SSStarAssembleElasticity(DM, const SSStarScene *, Mat *, Vec *);
PETSC_EXTERN PetscErrorCode SSStarContactNodesCreate(DM, Vec, SSStarContactNodes *);
PETSC_EXTERN PetscErrorCode SSStarContactNodesDestroy(SSStarContactNodes *);

/* HDF5 + XDMF: the full displacement on the mesh and the group /contact (README, "Output") */
PETSC_EXTERN PetscErrorCode SSStarCheckOutputFile(MPI_Comm, const char[]);
PETSC_EXTERN PetscErrorCode SSStarWriteSolution(const char[], DM, Vec, const SSStarContactNodes *, Vec, Vec, const PetscInt[]);

#endif
