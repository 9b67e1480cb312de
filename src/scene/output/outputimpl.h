#ifndef SSSTAROUTPUTIMPL_H
#define SSSTAROUTPUTIMPL_H

/* The output's files share: HDF5 pieces (hdf5.c), the file order (fileorder.c), the contact datasets (contact.c), the
   metadata (metadata.c); output.c writes the files with them */
#include "../sceneimpl.h"
#include <petscviewerhdf5.h>

#define PetscCallH5(call) \
  do { \
    if ((call) < 0) SETERRQ(PETSC_COMM_SELF, PETSC_ERR_LIB, "HDF5 failed: %s", #call); \
  } while (0)

PETSC_INTERN PetscErrorCode SSStarH5GroupOpen(hid_t, const char[], hid_t *);
PETSC_INTERN PetscErrorCode SSStarH5AttrString(hid_t, const char[], const char[]);
PETSC_INTERN PetscErrorCode SSStarH5AttrReals(hid_t, const char[], PetscInt, const PetscReal[]);
PETSC_INTERN PetscErrorCode SSStarH5AttrReal(hid_t, const char[], PetscReal);
PETSC_INTERN PetscErrorCode SSStarH5AttrInts(hid_t, const char[], PetscInt, const PetscInt[]);
PETSC_INTERN PetscErrorCode SSStarH5AttrInt(hid_t, const char[], PetscInt);
PETSC_INTERN PetscErrorCode SSStarH5WriteRows(MPI_Comm, hid_t, const char[], PetscInt, PetscInt, const PetscReal[], const PetscInt[]);
PETSC_INTERN PetscErrorCode SSStarH5ObjectAttrString(hid_t, const char[], const char[], const char[]);
PETSC_INTERN PetscErrorCode SSStarJoinNames(PetscInt, const char *const[], char[], size_t);

PETSC_INTERN PetscErrorCode SSStarGhostPoints(DM, PetscBool **);
PETSC_INTERN int            SSStarCompareRows(const void *, const void *, void *);
PETSC_INTERN PetscErrorCode SSStarWriteMesh(SSStarScene, hid_t, Vec);
PETSC_INTERN PetscErrorCode SSStarFileOrder(MPI_Comm, PetscInt, const PetscInt[], PetscInt *, PetscInt **, PetscInt[]);
PETSC_INTERN PetscErrorCode SSStarWriteNodeField(MPI_Comm, hid_t, const char[], PetscInt, PetscInt, const PetscInt[], PetscInt, const PetscReal[], PetscBool);

/* What the solver used at each contact node (friction.c): the law and the parameters of the laws in use */
typedef struct {
  PetscBool          known;   /* the SNES is an ssstar: the laws and values are the solver's         */
  PetscInt           n;       /* local contact nodes                                                 */
  PetscInt          *law;     /* per node: its index in the table of laws                            */
  PetscInt           nparams; /* the parameters of the laws in use on any rank, in the table's order */
  const char       **param;   /* their names (the table's)                                           */
  PetscInt          *size;    /* their values per node: 1, or 3 for a direction                      */
  PetscReal        **value;   /* size values per node, 0 where the node's law has no such parameter  */
} SSStarNodeFriction;

PETSC_INTERN PetscErrorCode SSStarNodeFrictionGet(MPI_Comm, SNES, PetscInt, const PetscInt[], SSStarNodeFriction *);
PETSC_INTERN PetscErrorCode SSStarNodeFrictionWrite(MPI_Comm, hid_t, const char[], const SSStarNodeFriction *, PetscInt, const PetscInt[]);
PETSC_INTERN PetscErrorCode SSStarNodeFrictionDestroy(SSStarNodeFriction *);
PETSC_INTERN PetscErrorCode SSStarWriteContact(SSStarScene, hid_t, Vec, Vec, const SSStarState[], const SSStarNodeFriction *);
PETSC_INTERN PetscErrorCode SSStarWriteContactFaces(SSStarScene, hid_t, Vec, Vec, const SSStarState[], PetscInt *, PetscInt *);
PETSC_INTERN PetscErrorCode SSStarWriteScene(SSStarScene, hid_t, const SSStarNodeFriction *);
PETSC_INTERN PetscErrorCode SSStarWriteRun(SSStarScene, hid_t, SNES);

#endif
