/*
   The problem a scene declares to an SNES (docs/derivation.md section 18): a linear scene's affine F(u) = K u - b, the
   fast special case (SNESSSStarSetLinearProblem()), or a hyperelastic scene's residual F(u) = f(u) + k u - load and its
   tangent J(u) (elasticity.c), evaluated at every iterate, with the prescribed values g of the load put into the iterate
   before each solve with the linear response of the body to their change (a predictor; so that the symmetric identity
   rows of J give exact Newton steps from the first).
*/
#include "../sceneimpl.h"

/*@C
   SSStarSceneIsAffine - whether the scene's problem is affine, F(u) = K u - b: every volume group linear
   (-material_model linear, the default); a hyperelastic model (saint_venant_kirchhoff, neo_hookean) makes it nonlinear

   Not Collective

   Input Parameter:
.  scene - the scene, after SSStarSceneSetFromOptions()

   Output Parameter:
.  affine - PETSC_TRUE for a linear scene

   Level: intermediate

.seealso: `SSStarSceneSetProblem()`
@*/
PetscErrorCode SSStarSceneIsAffine(SSStarScene scene, PetscBool *affine)
{
  PetscFunctionBegin;
  *affine = scene->affine;
  PetscFunctionReturn(0);
}

static PetscErrorCode HyperelasticFunction(SNES snes, Vec u, Vec r, void *ctx)
{
  SSStarScene scene = (SSStarScene)ctx;
  PetscBool   ok;

  PetscFunctionBegin;
  PetscCall(SSStarAssembleResidual(scene, u, scene->problemLoad, r, &ok));
  if (!ok) PetscCall(SNESSetFunctionDomainError(snes)); /* a neo-Hookean cell turned inside out: the step is too long */
  PetscFunctionReturn(0);
}

static PetscErrorCode HyperelasticJacobian(SNES snes, Vec u, Mat J, Mat Jpre, void *ctx)
{
  SSStarScene scene = (SSStarScene)ctx;
  PetscBool   ok;

  PetscFunctionBegin;
  PetscCall(SSStarAssembleTangent(scene, u, Jpre, &ok));
  if (!ok) PetscCall(SNESSetJacobianDomainError(snes));
  if (scene->nFloating) PetscCall(SSStarSetRigidBodyModes(scene, u, Jpre)); /* the current configuration's motions (18b) */
  if (J != Jpre) { /* a matrix-free J (-snes_mf_operator) */
    PetscCall(MatAssemblyBegin(J, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(J, MAT_FINAL_ASSEMBLY));
  }
  PetscFunctionReturn(0);
}

/*
   The linear solver of the predictor: the reference K' (SSStarSceneAssemble()'s, identity rows, factored once by MUMPS'
   Cholesky); null pivots allowed, for the rigid motions of floating bodies (the right-hand side does not load them)
*/
static PetscErrorCode PredictorSetUp(SSStarScene scene)
{
  KSP          ksp;
  PC           pc;
  Mat          F;
  MatNullSpace ns;

  PetscFunctionBegin;
  if (scene->predictor) PetscFunctionReturn(0);
  PetscCall(KSPCreate(scene->comm, &ksp));
  PetscCall(KSPSetOperators(ksp, scene->Kref, scene->Kref));
  PetscCall(KSPSetType(ksp, KSPPREONLY));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCSetType(pc, PCCHOLESKY));
  PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  PetscCall(PCFactorSetUpMatSolverType(pc));
  PetscCall(PCFactorGetMatrix(pc, &F));
  PetscCall(MatGetNullSpace(scene->Kref, &ns));
  if (ns) PetscCall(MatMumpsSetIcntl(F, 24, 1)); /* null pivot detection: a particular solution */
  PetscCall(KSPSetUp(ksp));
  scene->predictor = ksp;
  PetscFunctionReturn(0);
}

/*
   Before each solve: the prescribed components of the iterate u moved to their values g = load / diag(K), the free
   ones by the linear response to that move, du = K'^-1 [-K_FD dg; diag(K) dg] (docs/derivation.md (18.5)): a predictor
   that spreads the motion of a moved support into the body, so that the cells next to it are not crushed or turned
   inside out by the jump, whatever the mesh size
*/
static PetscErrorCode PrescribeIterate(SNES snes, Vec u, void *ctx)
{
  SSStarScene  scene = (SSStarScene)ctx;
  Vec          dg, m, rhs, du, gloc, floc;
  PetscReal    norm;
  SSStarCells  cells;
  MatNullSpace ns;

  PetscFunctionBegin;
  if (!scene->nDisplacements) PetscFunctionReturn(0);
  PetscCall(VecDuplicate(u, &dg));
  PetscCall(VecDuplicate(u, &m));
  PetscCall(VecZeroEntries(dg));
  PetscCall(VecZeroEntries(m));
  PetscCall(SSStarHeldDiagonal(scene, scene->problemLoad, dg, PETSC_TRUE)); /* g at the prescribed components, 0 elsewhere */
  PetscCall(SSStarHeldDiagonal(scene, u, m, PETSC_FALSE));
  PetscCall(SSStarHeldDiagonal(scene, m, m, PETSC_TRUE)); /* u at the prescribed components, 0 elsewhere */
  PetscCall(VecAXPY(dg, -1.0, m));
  PetscCall(VecNorm(dg, NORM_INFINITY, &norm));
  PetscCall(VecDestroy(&m));
  if (norm == 0) {
    PetscCall(VecDestroy(&dg));
    PetscFunctionReturn(0);
  }
  PetscCall(PredictorSetUp(scene));
  PetscCall(DMGetLocalVector(scene->dm, &gloc));
  PetscCall(DMGetLocalVector(scene->dm, &floc));
  PetscCall(VecZeroEntries(gloc));
  PetscCall(DMGlobalToLocal(scene->dm, dg, INSERT_VALUES, gloc));
  PetscCall(VecZeroEntries(floc));
  PetscCall(SSStarCellsBegin(scene, &cells));
  PetscCall(SSStarHeldLift(scene, &cells, gloc, floc)); /* -K_FD dg */
  PetscCall(SSStarCellsEnd(&cells));
  PetscCall(VecDuplicate(u, &rhs));
  PetscCall(VecDuplicate(u, &du));
  PetscCall(VecZeroEntries(rhs));
  PetscCall(DMLocalToGlobal(scene->dm, floc, ADD_VALUES, rhs));
  PetscCall(DMRestoreLocalVector(scene->dm, &floc));
  PetscCall(DMRestoreLocalVector(scene->dm, &gloc));
  PetscCall(SSStarHeldDiagonal(scene, dg, rhs, PETSC_FALSE)); /* diag(K) dg */
  PetscCall(KSPSolve(scene->predictor, rhs, du));
  PetscCall(MatGetNullSpace(scene->Kref, &ns));
  if (ns) PetscCall(MatNullSpaceRemove(ns, du)); /* no rigid motion of a floating body */
  PetscCall(VecAXPY(u, 1.0, du));
  PetscCall(VecDestroy(&du));
  PetscCall(VecDestroy(&rhs));
  PetscCall(VecDestroy(&dg));
  PetscFunctionReturn(0);
}

/*@C
   SSStarSceneSetProblem - declares the scene's problem to an SNES: for a linear scene F(u) = K u - load with the
   Jacobian K (SNESSSStarSetLinearProblem(): affine, the Jacobian evaluated once); for a hyperelastic scene
   (-material_model, -material_model_<G>) the residual F(u) = f(u) + k u - load of its cells' internal forces and its
   springs, and the tangent J(u) assembled into K at every iterate (docs/derivation.md section 18)

   Collective

   Input Parameters:
+  scene - the scene, after SSStarSceneAssemble()
.  snes  - the SNES (ssstar with contact, any other without: newtonls for a hyperelastic scene)
.  K     - the stiffness of SSStarSceneAssemble(): the Jacobian's matrix (a hyperelastic scene overwrites it with J(u))
-  load  - the load (SSStarSceneAssemble()'s b, or SSStarSceneAssembleLoad()'s), referenced: a program that changes
           its values between solves (load steps, the steps of a load path) changes the problem

   Notes:
   The load is dead: tractions and gravity keep their direction and their magnitude per unit reference area or volume
   whatever the deformation (-traction_<G> is no follower load). A prescribed displacement's component has an identity
   row in both: F = diag(K) (u - g) there; for a hyperelastic scene the values g are put into the iterate before every
   solve (SNESSetComputeInitialGuess()) with the linear response of the body to their change (a predictor, one solve
   with the reference K' factored once), so that the Newton steps are exact from the first. After SNESSolve(),
   SNESGetFunction() holds F(u): at the contact dofs the contact forces, as for a linear scene.

   Level: intermediate

.seealso: `SSStarSceneIsAffine()`, `SSStarSceneAssemble()`, `SNESSSStarSetLinearProblem()`, `SSStarSceneSetContact()`
@*/
PetscErrorCode SSStarSceneSetProblem(SSStarScene scene, SNES snes, Mat K, Vec load)
{
  Vec r;

  PetscFunctionBegin;
  if (scene->affine) {
    PetscCall(SNESSSStarSetLinearProblem(snes, K, load));
    PetscFunctionReturn(0);
  }
  PetscCall(PetscObjectReference((PetscObject)load));
  PetscCall(VecDestroy(&scene->problemLoad));
  scene->problemLoad = load;
  PetscCall(VecDuplicate(load, &r));
  PetscCall(SNESSetFunction(snes, r, HyperelasticFunction, scene));
  PetscCall(VecDestroy(&r));
  PetscCall(SNESSetJacobian(snes, K, K, HyperelasticJacobian, scene));
  if (scene->nDisplacements && !scene->Kref) { /* the predictor's K' (K becomes J(u) at the first Jacobian) */
    MatNullSpace ns;

    PetscCall(MatDuplicate(K, MAT_COPY_VALUES, &scene->Kref));
    PetscCall(MatGetNullSpace(K, &ns));
    PetscCall(MatSetNullSpace(scene->Kref, ns));
  }
  PetscCall(SNESSetComputeInitialGuess(snes, PrescribeIterate, scene));
  PetscFunctionReturn(0);
}
