static const char help[] = "The reductions of a scene checked against other solvers (tests/suite_scenes.py):\n\
  -check vi      the frictionless solution equals PETSc's SNESVINEWTONRSLS on the same reduced problem P, f\n\
                 (bounds u_n >= -gap, every contact normal (0, 0, 1))\n\
  -check tresca  Tresca with the slip bounds phi r_n of the Coulomb solution reproduces the Coulomb solution\n\
  -phi <phi>     the scene's Coulomb coefficient (default: the solver's, -snes_ssstar_friction)\n\
  -tol <1e-10>   the largest relative difference accepted (max norm)\n\
The scene comes from the options, as for examples/contact.\n";

#include <ssstar.h>
#include <ssstarscene.h>

typedef struct {
  Mat K;
  Vec b;
} Body;

/* The scene's contact problem solved by ssstar (options with prefix), from u = 0 */
static PetscErrorCode SolveContact(SSStarScene scene, Body *body, const char prefix[], const char *law, Vec bounds, SNES *snes, Vec *u)
{
  DM                  dm;
  SNESConvergedReason reason;

  PetscFunctionBeginUser;
  PetscCall(SNESCreate(PETSC_COMM_WORLD, snes));
  PetscCall(SNESSetOptionsPrefix(*snes, prefix));
  PetscCall(SNESSetType(*snes, SNESSSSTAR));
  PetscCall(SSStarSceneSetContact(scene, *snes));
  if (law) PetscCall(SNESSSStarSetFrictionLaw(*snes, law));
  if (bounds) PetscCall(SNESSSStarSetNodeLawParameter(*snes, "slip_bound", bounds));
  PetscCall(SNESSSStarSetLinearProblem(*snes, body->K, body->b));
  PetscCall(SNESSetTolerances(*snes, PETSC_DEFAULT, 1e-13, PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT));
  PetscCall(SNESSetFromOptions(*snes));
  PetscCall(SSStarSceneGetDM(scene, &dm));
  PetscCall(DMCreateGlobalVector(dm, u));
  PetscCall(VecZeroEntries(*u));
  PetscCall(SNESSolve(*snes, NULL, *u));
  PetscCall(SNESGetConvergedReason(*snes, &reason));
  PetscCheck(reason > 0, PETSC_COMM_WORLD, PETSC_ERR_NOT_CONVERGED, "ssstar (prefix %s) did not converge: %s", prefix, SNESConvergedReasons[reason]);
  PetscFunctionReturn(0);
}

/* max |x - y| / max |y| */
static PetscErrorCode RelativeDifference(Vec x, Vec y, PetscReal *d)
{
  Vec       w;
  PetscReal ny;

  PetscFunctionBeginUser;
  PetscCall(VecDuplicate(x, &w));
  PetscCall(VecWAXPY(w, -1.0, y, x));
  PetscCall(VecNorm(w, NORM_INFINITY, d));
  PetscCall(VecNorm(y, NORM_INFINITY, &ny));
  *d /= ny;
  PetscCall(VecDestroy(&w));
  PetscFunctionReturn(0);
}

/* The reduced problem of an ssstar solve */
typedef struct {
  Mat P;
  Vec f;
} Reduced;

/* Frictionless contact = the bound-constrained problem min 1/2 v'Pv - f'v, v_z >= -gap, solved by SNESVINEWTONRSLS */
static PetscErrorCode CheckVI(SSStarScene scene, Body *body, PetscReal tol)
{
  SNES             snes, vi;
  Vec              u, uC, v, lower, upper;
  Reduced          red;
  IS               isC;
  PetscInt         n;
  const PetscReal *normals, *gaps;
  PetscScalar     *lo, *up;
  PetscReal        d, fnorm;
  KSP              ksp;
  PC               pc;
  SNESConvergedReason reason;

  PetscFunctionBeginUser;
  PetscCall(SolveContact(scene, body, "", NULL, NULL, &snes, &u));
  PetscCall(SNESSSStarGetReducedProblem(snes, &red.P, &red.f));
  PetscCall(SSStarSceneGetContactNodes(scene, &n, NULL, &normals, &gaps, NULL));
  PetscCall(VecDuplicate(red.f, &v));
  PetscCall(VecDuplicate(red.f, &lower));
  PetscCall(VecDuplicate(red.f, &upper));
  PetscCall(VecGetArrayWrite(lower, &lo));
  PetscCall(VecGetArrayWrite(upper, &up));
  for (PetscInt i = 0; i < n; i++) {
    PetscCheck(normals[3 * i] == 0 && normals[3 * i + 1] == 0 && normals[3 * i + 2] == 1, PETSC_COMM_SELF, PETSC_ERR_SUP, "-check vi needs every contact normal to be (0, 0, 1)");
    for (PetscInt k = 0; k < 3; k++) {
      lo[3 * i + k] = k == 2 ? -gaps[i] : PETSC_NINFINITY;
      up[3 * i + k] = PETSC_INFINITY;
    }
  }
  PetscCall(VecRestoreArrayWrite(upper, &up));
  PetscCall(VecRestoreArrayWrite(lower, &lo));

  PetscCall(SNESCreate(PETSC_COMM_WORLD, &vi));
  PetscCall(SNESSetOptionsPrefix(vi, "vi_"));
  PetscCall(SNESSetType(vi, SNESVINEWTONRSLS));
  PetscCall(SNESSSStarSetLinearProblem(vi, red.P, red.f)); /* P v - f, with any SNES type */
  PetscCall(SNESVISetVariableBounds(vi, lower, upper));
  PetscCall(VecNorm(red.f, NORM_2, &fnorm));
  PetscCall(SNESSetTolerances(vi, 1e-12 * fnorm, 1e-14, 0.0, 100, PETSC_DEFAULT)); /* the round-off floor of |P v - f| is ~1e-14 |f| */
  PetscCall(SNESGetKSP(vi, &ksp));
  PetscCall(KSPSetType(ksp, KSPPREONLY));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCSetType(pc, PCLU));
  PetscCall(SNESSetFromOptions(vi));
  PetscCall(VecZeroEntries(v));
  PetscCall(SNESSolve(vi, NULL, v));
  PetscCall(SNESGetConvergedReason(vi, &reason));
  PetscCheck(reason > 0, PETSC_COMM_WORLD, PETSC_ERR_NOT_CONVERGED, "SNESVINEWTONRSLS did not converge: %s", SNESConvergedReasons[reason]);

  PetscCall(SSStarSceneGetContactDofs(scene, &isC));
  PetscCall(VecGetSubVector(u, isC, &uC));
  PetscCall(RelativeDifference(uC, v, &d));
  PetscCall(VecRestoreSubVector(u, isC, &uC));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "frictionless ssstar vs SNESVINEWTONRSLS: contact displacement differs by %.3e relative (tolerance %.1e)\n", (double)d, (double)tol));
  PetscCheck(d <= tol, PETSC_COMM_WORLD, PETSC_ERR_NOT_CONVERGED, "frictionless ssstar and SNESVINEWTONRSLS differ by %g > %g", (double)d, (double)tol);
  PetscCall(VecDestroy(&lower));
  PetscCall(VecDestroy(&upper));
  PetscCall(VecDestroy(&v));
  PetscCall(SNESDestroy(&vi));
  PetscCall(VecDestroy(&u));
  PetscCall(SNESDestroy(&snes));
  PetscFunctionReturn(0);
}

/* Tresca with s_i = phi r_n,i of the Coulomb solution has the Coulomb solution as its (unique) solution */
static PetscErrorCode CheckTresca(SSStarScene scene, Body *body, PetscReal phi, PetscReal tol)
{
  SNES               coulomb, tresca;
  Vec                uc, ut, r, rC, bounds;
  IS                 isC;
  PetscInt           n;
  const PetscReal   *normals;
  const PetscScalar *ra;
  PetscScalar       *sa;
  PetscReal          d;

  PetscFunctionBeginUser;
  PetscCall(SolveContact(scene, body, "coulomb_", NULL, NULL, &coulomb, &uc));
  if (phi < 0) PetscCall(SNESSSStarGetFriction(coulomb, &phi));
  PetscCall(SNESGetFunction(coulomb, &r, NULL, NULL));
  PetscCall(SSStarSceneGetContactDofs(scene, &isC));
  PetscCall(SSStarSceneGetContactNodes(scene, &n, NULL, &normals, NULL, NULL));
  PetscCall(VecCreateMPI(PETSC_COMM_WORLD, n, PETSC_DETERMINE, &bounds));
  PetscCall(VecGetSubVector(r, isC, &rC));
  PetscCall(VecGetArrayRead(rC, &ra));
  PetscCall(VecGetArrayWrite(bounds, &sa));
  for (PetscInt i = 0; i < n; i++) {
    PetscReal rn = 0;

    for (PetscInt k = 0; k < 3; k++) rn += PetscRealPart(ra[3 * i + k]) * normals[3 * i + k];
    sa[i] = phi * PetscMax(rn, 0.0);
  }
  PetscCall(VecRestoreArrayWrite(bounds, &sa));
  PetscCall(VecRestoreArrayRead(rC, &ra));
  PetscCall(VecRestoreSubVector(r, isC, &rC));
  PetscCall(SolveContact(scene, body, "tresca_", SSSTARLAWTRESCA, bounds, &tresca, &ut));
  PetscCall(RelativeDifference(ut, uc, &d));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "Tresca with bounds phi r_n (phi = %g) vs Coulomb: displacement differs by %.3e relative (tolerance %.1e)\n", (double)phi, (double)d, (double)tol));
  PetscCheck(d <= tol, PETSC_COMM_WORLD, PETSC_ERR_NOT_CONVERGED, "Tresca and Coulomb differ by %g > %g", (double)d, (double)tol);
  PetscCall(VecDestroy(&bounds));
  PetscCall(VecDestroy(&ut));
  PetscCall(VecDestroy(&uc));
  PetscCall(SNESDestroy(&tresca));
  PetscCall(SNESDestroy(&coulomb));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  const char *const checks[] = {"vi", "tresca", "Check", "CHECK_", NULL};
  PetscEnum         check    = 0;
  PetscReal         tol = 1e-10, phi = -1;
  SSStarScene       scene;
  Body              body;

  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(SSStarInitializePackage());
  PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "Scene reductions", NULL);
  PetscCall(PetscOptionsEnum("-check", "What to check", NULL, checks, check, &check, NULL));
  PetscCall(PetscOptionsReal("-tol", "Largest relative difference accepted", NULL, tol, &tol, NULL));
  PetscCall(PetscOptionsReal("-phi", "The scene's Coulomb coefficient (default: the solver's)", NULL, phi, &phi, NULL));
  PetscOptionsEnd();
  PetscCall(SSStarSceneCreate(PETSC_COMM_WORLD, &scene));
  PetscCall(SSStarSceneSetFromOptions(scene));
  PetscCall(SSStarSceneSetUp(scene));
  PetscCall(SSStarSceneAssemble(scene, &body.K, &body.b));
  if (check == 0) PetscCall(CheckVI(scene, &body, tol));
  else PetscCall(CheckTresca(scene, &body, phi, tol));
  PetscCall(MatDestroy(&body.K));
  PetscCall(VecDestroy(&body.b));
  PetscCall(SSStarSceneDestroy(&scene));
  PetscCall(PetscFinalize());
  return 0;
}
