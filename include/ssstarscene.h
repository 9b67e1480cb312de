#ifndef SSSTARSCENE_H
#define SSSTARSCENE_H

/*
   The scene library (src/scene): elastic bodies (gmsh meshes on DMPlex, P1 linear elasticity) with the effects a scene
   names -- Dirichlet groups, tractions, gravity, soft springs, contact groups against rigid obstacles or against
   another body, with a friction law each -- and their output. Kept apart from the solver: a scene assembles K and b
   and declares its contact to an "ssstar" SNES through the contact operator B.
*/
#include <petscdmplex.h>
#include <petscksp.h>
#include <ssstar.h>

PETSC_EXTERN PetscLogEvent SSSTAR_Mesh, SSSTAR_Assembly, SSSTAR_Output;
PETSC_EXTERN PetscLogEvent SSSTAR_MeshGmsh, SSSTAR_MeshCache, SSSTAR_MeshBuild, SSSTAR_MeshFaces, SSSTAR_MeshLabel;

/*
   A scene: the body, its material, supports and loads, and its contact groups, read from the options
   (docs/guide/scenes.md: -mesh or -geo/-level, -E, -nu, -material_<G>, -dirichlet, -displacement_<G>, -traction_<G>,
   -spring_<G>, -gravity,
   -density, -contact, -obstacle_<G>, -friction_law_<G> and -<parameter>_<G> for every parameter of the table of laws
   (-friction_<G>, -slip_bound_<G>, -friction_1_<G>, ...), -mesh_scale; two bodies: -contact_pair_<G> H,
   -pair_discretization).
*/
typedef struct _n_SSStarScene *SSStarScene;

PETSC_EXTERN PetscErrorCode SSStarSceneCreate(MPI_Comm, SSStarScene *);
PETSC_EXTERN PetscErrorCode SSStarSceneSetFromOptions(SSStarScene);
PETSC_EXTERN PetscErrorCode SSStarSceneSetProgress(SSStarScene, PetscBool);
PETSC_EXTERN PetscErrorCode SSStarSceneCheckOptionsUsed(SSStarScene, const char[], SNES);
PETSC_EXTERN PetscErrorCode SSStarSceneCheckOptionsUsedOf(SSStarScene, PetscInt, const char *const[], const char[], SNES);
PETSC_EXTERN PetscErrorCode SSStarSceneSetUp(SSStarScene);
PETSC_EXTERN PetscErrorCode SSStarSceneView(SSStarScene, PetscViewer);
PETSC_EXTERN PetscErrorCode SSStarSceneDestroy(SSStarScene *);
PETSC_EXTERN PetscErrorCode SSStarSceneGetDM(SSStarScene, DM *);
PETSC_EXTERN PetscErrorCode SSStarSceneGetSizes(SSStarScene, PetscInt *, PetscInt *);
PETSC_EXTERN PetscErrorCode SSStarSceneAssemble(SSStarScene, Mat *, Vec *);
PETSC_EXTERN PetscErrorCode SSStarSceneHasContact(SSStarScene, PetscBool *);
PETSC_EXTERN PetscErrorCode SSStarSceneGetContactDofs(SSStarScene, IS *);
PETSC_EXTERN PetscErrorCode SSStarSceneGetContactNodes(SSStarScene, PetscInt *, const PetscReal *[], const PetscReal *[], const PetscReal *[], const PetscReal *[]);
PETSC_EXTERN PetscErrorCode SSStarSceneSetContact(SSStarScene, SNES);
PETSC_EXTERN PetscErrorCode SSStarSceneSolveNested(SSStarScene, SNES, Vec);

/* What the contact nodes of a group (or of all groups) carry at a solution */
typedef struct {
  PetscInt  nodes, separated, sliding, sticking; /* states L, LS / M1, M2 / M3+, M3-, M4                 */
  PetscReal area;                                /* tributary area of the nodes in contact               */
  PetscReal normal_force;                        /* sum of r.n, the force of the plane(s) on the body    */
  PetscReal force[3];                            /* sum of r in global axes                              */
  PetscReal tangential_force[3];                 /* sum of r - (r.n) n, the friction forces              */
  PetscReal dissipation;                         /* energy dissipated by friction along a load path      */
} SSStarContactResult;
PETSC_EXTERN PetscErrorCode SSStarSceneGetContactResult(SSStarScene, PetscInt, Vec, const SSStarState[], SSStarContactResult *);
PETSC_EXTERN PetscErrorCode SSStarSceneContactView(SSStarScene, Vec, const SSStarState[], PetscViewer);
PETSC_EXTERN PetscErrorCode SSStarSceneViewNoEquilibrium(SSStarScene, SNES, PetscViewer);
/* The held groups (-dirichlet, -displacement_<G>) and the force each prescription exerts on the body */
PETSC_EXTERN PetscErrorCode SSStarSceneGetHeldGroups(SSStarScene, PetscInt *, const char *const *[]);
PETSC_EXTERN PetscErrorCode SSStarSceneGetReactions(SSStarScene, SNES, Vec, PetscReal[]);
/* The P1 tetrahedron's strain (B u), Hooke's stress and the von Mises stress: xx, yy, zz, yz, xz, xy (tensor components) */
PETSC_EXTERN PetscReal SSStarTetStrain(const PetscReal[12], const PetscReal[12], PetscReal[6]);
PETSC_EXTERN void      SSStarHookeStress(PetscReal, PetscReal, const PetscReal[6], PetscReal[6]);
PETSC_EXTERN PetscReal SSStarVonMises(const PetscReal[6]);

/*
   Load paths (docs/load-paths.md): the loads as histories of a pseudo-time (-traction_<G>, -gravity), moving obstacles
   (-obstacle_<G>_motion), the steps solved with incremental friction (SNESSSStarSetContactOffsets()), and a file that
   holds every step.
*/
PETSC_EXTERN PetscErrorCode SSStarSceneGetKnots(SSStarScene, PetscInt *, PetscReal *[]);
PETSC_EXTERN PetscErrorCode SSStarSceneHasPath(SSStarScene, PetscBool *);
PETSC_EXTERN PetscErrorCode SSStarSceneAssembleLoad(SSStarScene, PetscReal, Vec);
PETSC_EXTERN PetscErrorCode SSStarSceneGetLoadResultant(SSStarScene, Vec, PetscReal[3]);
PETSC_EXTERN PetscErrorCode SSStarSceneCheckSteps(SSStarScene, PetscInt, const PetscReal[]);
PETSC_EXTERN PetscErrorCode SSStarSceneSetStep(SSStarScene, SNES, PetscReal);
PETSC_EXTERN PetscErrorCode SSStarSceneSetHistory(SSStarScene, const char[], const char[]);
PETSC_EXTERN PetscErrorCode SSStarSceneCheckStep(SSStarScene, SNES, Vec, PetscBool *, PetscBool *);
PETSC_EXTERN PetscErrorCode SSStarSceneAcceptStep(SSStarScene, Vec, Vec);
PETSC_EXTERN PetscErrorCode SSStarSceneGetContactGroupCount(SSStarScene, PetscInt *);
PETSC_EXTERN PetscErrorCode SSStarSceneGetMotion(SSStarScene, PetscInt, const char *[], PetscReal[3], PetscBool *);
PETSC_EXTERN PetscErrorCode SSStarSceneOutputBegin(SSStarScene, const char[]);
PETSC_EXTERN PetscErrorCode SSStarSceneOutputStep(SSStarScene, SNES, Vec, PetscInt);
PETSC_EXTERN PetscErrorCode SSStarSceneOutputEnd(SSStarScene, SNES, Vec, PetscErrorCode (*)(PetscViewer, void *), void *);
/* The table of the steps (/steps): its columns and the row of the step just solved */
PETSC_EXTERN PetscErrorCode SSStarSceneGetStepColumns(SSStarScene, PetscInt *, PetscInt *);
PETSC_EXTERN PetscErrorCode SSStarSceneGetStepColumn(SSStarScene, PetscInt, size_t, char[], PetscInt *, PetscBool *);
PETSC_EXTERN PetscErrorCode SSStarSceneGetStepRow(SSStarScene, SNES, Vec, PetscInt, PetscReal[]);

/*
   Output: HDF5 + XDMF, the same file on any number of ranks (the mesh file's node order), with what was solved and how
   the solve went; written to temporary names and renamed on success, so that a failed run leaves no file behind.
   extra, if not NULL, adds the caller's datasets to the open file.
*/
PETSC_EXTERN PetscErrorCode SSStarCheckOutputFile(MPI_Comm, const char[]);
PETSC_EXTERN PetscErrorCode SSStarSceneWriteSolution(SSStarScene, SNES, const char[], Vec, PetscErrorCode (*)(PetscViewer, void *), void *);
PETSC_EXTERN PetscErrorCode SSStarWriteTable(PetscViewer, const char[], PetscInt, const char *const[], PetscInt, const PetscReal *const[]);
/* A dataset of the output as the scene holds it at a state, every row in file order, on every rank */
PETSC_EXTERN PetscErrorCode SSStarSceneGetField(SSStarScene, SNES, Vec, const char[], Vec *);
/* The friction of each contact node of an ssstar SNES (group/friction_law, group/<parameter>), as the scenes write it */
PETSC_EXTERN PetscErrorCode SSStarWriteNodeFriction(SNES, PetscViewer, const char[]);

/* The pieces a scene is made of, for programs of their own */
PETSC_EXTERN PetscErrorCode SSStarMeshGenerate(MPI_Comm, const char[], PetscInt, const char[]);
PETSC_EXTERN PetscErrorCode SSStarMeshCacheFile(MPI_Comm, const char[], const char[], PetscInt, char[]);
PETSC_EXTERN PetscErrorCode SSStarMeshFileNodes(MPI_Comm, const char[], PetscInt *);
PETSC_EXTERN PetscErrorCode SSStarCheckMemory(MPI_Comm, PetscReal, const char[]);
PETSC_EXTERN PetscErrorCode SSStarEstimateMemory(MPI_Comm, PetscReal, PetscReal, PetscLogDouble *, PetscLogDouble *, PetscBool *);

#endif
