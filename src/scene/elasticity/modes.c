/*
   The rigid-body modes in the layout of K (the coordinates of its free dofs, block size 3): as K's near-null space, the
   six of the whole mesh, from which algebraic multigrid (PCGAMG) builds its coarse spaces (it halves its iterations on
   elasticity; the whole-body Newton step of ssstar uses it); as K's null space, those of each body no -dirichlet or
   -spring_<G> group holds (bodies.c): the six rigid motions of a body held by contact alone, fewer when prescribed
   displacements hold some of them (a lid moved down with x, y free keeps the two translations in its plane and the
   turn about its normal: the motions whose prescribed components vanish, docs/derivation.md section 15), orthonormal:
   K does not resist them, and the solver needs to know it (section 14)
*/
#include "../sceneimpl.h"
#include <petscblaslapack.h>

/* Rigid motion m of a body at x: m < 3 the translation along axis m, else the rotation about axis m - 3 through c,
   its lever arm divided by s (the body's size: the six motions of one scale) */
static void RigidMotion(PetscInt m, const PetscReal x[3], const PetscReal c[3], PetscReal s, PetscReal rho[3])
{
  rho[0] = rho[1] = rho[2] = 0;
  if (m < 3) rho[m] = 1;
  else { /* e_a x (x - c) */
    const PetscInt a = m - 3, b = (a + 1) % 3, d = (a + 2) % 3;

    rho[b] = -(x[d] - c[d]) / s;
    rho[d] = (x[b] - c[b]) / s;
  }
}

/* The floating body of local vertex v (its index in scene->floating), or -1 */
static PetscInt FloatingOf(SSStarScene scene, PetscInt v)
{
  for (PetscInt f = 0; f < scene->nFloating; f++)
    if (scene->body[v] == scene->floating[f]) return f;
  return -1;
}

/*
   The rigid motions each floating body keeps (coefficients of RigidMotion(), 6 per motion, body by body; count[f]
   per body) and each body's centre and size: the null space of the Gram matrix of the six motions at its prescribed
   components (LAPACK's syev, eigenvalues below 1e-10 of the largest)
*/
static PetscErrorCode KeptMotions(SSStarScene scene, Vec coordinates, PetscReal centre[], PetscReal size[], PetscInt count[], PetscReal **coef)
{
  const PetscInt     nf = scene->nFloating;
  PetscSection       gsec, csec;
  PetscInt           vStart, vEnd, total = 0;
  PetscReal         *sums, *bounds, *gram;
  const PetscScalar *xa;
  DM                 cdm;

  PetscFunctionBegin;
  /* per body: its owned vertices' count and sum of coordinates (4); -min x and max x (6) */
  PetscCall(PetscCalloc3(4 * nf + 1, &sums, 6 * nf + 1, &bounds, 36 * nf + 1, &gram));
  for (PetscInt k = 0; k < 6 * nf; k++) bounds[k] = -PETSC_MAX_REAL;
  PetscCall(DMGetGlobalSection(scene->dm, &gsec));
  PetscCall(DMGetCoordinateDM(scene->dm, &cdm));
  PetscCall(DMGetLocalSection(cdm, &csec));
  PetscCall(DMPlexGetDepthStratum(scene->dm, 0, &vStart, &vEnd));
  PetscCall(VecGetArrayRead(coordinates, &xa));
  for (PetscInt pass = 0; pass < 2; pass++) { /* the bodies' centres and sizes, then their Gram matrices */
    for (PetscInt v = vStart; v < vEnd; v++) {
      const PetscInt f = FloatingOf(scene, v - vStart);
      PetscInt       off, coff;
      PetscReal      x[3], rho[6][3];

      PetscCall(PetscSectionGetOffset(gsec, v, &off));
      if (f < 0 || off < 0) continue; /* owned vertices of floating bodies */
      PetscCall(PetscSectionGetOffset(csec, v, &coff));
      for (PetscInt k = 0; k < 3; k++) x[k] = PetscRealPart(xa[coff + k]);
      if (!pass) {
        sums[4 * f]++;
        for (PetscInt k = 0; k < 3; k++) {
          sums[4 * f + 1 + k] += x[k];
          bounds[6 * f + k]     = PetscMax(bounds[6 * f + k], -x[k]);
          bounds[6 * f + 3 + k] = PetscMax(bounds[6 * f + 3 + k], x[k]);
        }
        continue;
      }
      for (PetscInt m = 0; m < 6; m++) RigidMotion(m, x, &centre[3 * f], size[f], rho[m]);
      for (PetscInt k = 0; k < 3; k++) {
        if (!SSStarHeldIdentityRow(scene, v - vStart, k)) continue;
        for (PetscInt i = 0; i < 6; i++)
          for (PetscInt j = 0; j < 6; j++) gram[36 * f + 6 * i + j] += rho[i][k] * rho[j][k];
      }
    }
    if (!pass) {
      PetscCall(MPIU_Allreduce(MPI_IN_PLACE, sums, 4 * nf, MPIU_REAL, MPIU_SUM, scene->comm));
      PetscCall(MPIU_Allreduce(MPI_IN_PLACE, bounds, 6 * nf, MPIU_REAL, MPIU_MAX, scene->comm));
      for (PetscInt f = 0; f < nf; f++) {
        PetscReal extent = 0;

        for (PetscInt k = 0; k < 3; k++) {
          centre[3 * f + k] = sums[4 * f + 1 + k] / PetscMax(sums[4 * f], 1);
          extent            = PetscMax(extent, bounds[6 * f + 3 + k] + bounds[6 * f + k]); /* max x - min x */
        }
        size[f] = extent > 0 ? extent : 1;
      }
    }
  }
  PetscCall(VecRestoreArrayRead(coordinates, &xa));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, gram, 36 * nf, MPIU_REAL, MPIU_SUM, scene->comm));
  PetscCall(PetscMalloc1(36 * nf + 1, coef));
  for (PetscInt f = 0; f < nf; f++) {
    PetscBLASInt n = 6, lwork = 64, info;
    PetscReal    w[6], work[64], *G = &gram[36 * f];

    PetscCallBLAS("LAPACKsyev", LAPACKsyev_("V", "U", &n, G, &n, w, work, &lwork, &info));
    PetscCheck(!info, PETSC_COMM_SELF, PETSC_ERR_LIB, "LAPACK syev failed: %d", (int)info);
    count[f] = 0;
    for (PetscInt i = 0; i < 6; i++) /* ascending: the kernel first */
      if (w[i] <= 1e-10 * w[5]) PetscCall(PetscArraycpy(&(*coef)[6 * (total + count[f]++)], &G[6 * i], 6));
    total += count[f];
  }
  PetscCall(PetscFree3(sums, bounds, gram));
  PetscFunctionReturn(0);
}

/* The local coordinates of the configuration X + u (u a global vector; NULL: the reference X), a new vector */
static PetscErrorCode CurrentCoordinates(SSStarScene scene, Vec u, Vec *x)
{
  DM                 dm = scene->dm, cdm;
  PetscSection       sec, csec;
  Vec                uloc, X;
  PetscInt           vStart, vEnd;
  const PetscScalar *ua;
  PetscScalar       *xa;

  PetscFunctionBegin;
  PetscCall(DMGetCoordinatesLocal(dm, &X));
  PetscCall(VecDuplicate(X, x));
  PetscCall(VecCopy(X, *x));
  if (!u) PetscFunctionReturn(0);
  PetscCall(DMGetCoordinateDM(dm, &cdm));
  PetscCall(DMGetLocalSection(cdm, &csec));
  PetscCall(DMGetLocalSection(dm, &sec));
  PetscCall(DMGetLocalVector(dm, &uloc));
  PetscCall(VecZeroEntries(uloc));
  PetscCall(DMGlobalToLocal(dm, u, INSERT_VALUES, uloc));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(VecGetArrayRead(uloc, &ua));
  PetscCall(VecGetArray(*x, &xa));
  for (PetscInt v = vStart; v < vEnd; v++) {
    PetscInt off, coff, dof;

    PetscCall(PetscSectionGetDof(sec, v, &dof));
    if (dof != 3) continue;
    PetscCall(PetscSectionGetOffset(sec, v, &off));
    PetscCall(PetscSectionGetOffset(csec, v, &coff));
    for (PetscInt k = 0; k < 3; k++) xa[coff + k] += ua[off + k];
  }
  PetscCall(VecRestoreArray(*x, &xa));
  PetscCall(VecRestoreArrayRead(uloc, &ua));
  PetscCall(DMRestoreLocalVector(dm, &uloc));
  PetscFunctionReturn(0);
}

/* SSStarSetRigidBodyModes - K's near-null space (the six rigid motions of the mesh) and null space (the motions the
   floating bodies keep) at the configuration X + u (u NULL: the reference; a hyperelastic body's tangent J(u) gets its
   current configuration's, docs/derivation.md section 18b); a scene without contact whose bodies keep some is refused,
   naming the body */
PetscErrorCode SSStarSetRigidBodyModes(SSStarScene scene, Vec u, Mat K)
{
  DM                 dm = scene->dm, cdm;
  PetscSection       sec, csec;
  Vec                cloc, xloc, x, *modes;
  PetscInt           vStart, vEnd, nmodes = 0, *count, *first;
  PetscReal         *centre, *size, *coef;
  const PetscScalar *ca;
  PetscScalar       *xa;
  MatNullSpace       nsp;

  PetscFunctionBegin;
  PetscCall(PetscMalloc4(3 * scene->nFloating + 1, &centre, scene->nFloating + 1, &size, scene->nFloating + 1, &count, scene->nFloating + 1, &first));
  PetscCall(CurrentCoordinates(scene, u, &cloc));
  PetscCall(KeptMotions(scene, cloc, centre, size, count, &coef));
  for (PetscInt f = 0; f < scene->nFloating; f++) {
    first[f] = nmodes;
    nmodes += count[f];
    PetscCheck(!count[f] || scene->nContact || count[f] == 6, scene->comm, PETSC_ERR_ARG_WRONG, "The body of %s is held in some directions only: its prescribed displacements (-displacement_<G> with free components) leave %" PetscInt_FMT " of its rigid-body motions free, and there is no contact to hold them", scene->floatingName[f], count[f]);
  }
  /* floating: semidefinite. A tangent J(u) is symmetric (dead loads) but not always definite (Saint Venant-Kirchhoff
     past its limit point): declared SPD, GAMG estimates its smoother's eigenvalues by CG, which stops on it with
     DIVERGED_INDEFINITE_MAT and fails the whole multigrid (PC_SUBPC_ERROR) */
  PetscCall(MatSetOption(K, nmodes || u ? MAT_SYMMETRIC : MAT_SPD, PETSC_TRUE));
  PetscCall(PetscMalloc1(nmodes + 1, &modes));
  PetscCall(DMGetCoordinateDM(dm, &cdm));
  PetscCall(DMGetLocalSection(cdm, &csec));
  PetscCall(DMGetLocalSection(dm, &sec));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(DMGetLocalVector(dm, &xloc));
  PetscCall(VecGetArrayRead(cloc, &ca));
  /* mode -1: the coordinates (the near-null space); mode j: the j-th kept motion, zero at the prescribed components */
  for (PetscInt mode = -1; mode < nmodes; mode++) {
    PetscCall(VecGetArrayWrite(xloc, &xa));
    for (PetscInt v = vStart; v < vEnd; v++) {
      const PetscInt f = FloatingOf(scene, v - vStart);
      PetscInt       off, coff, dof;
      PetscReal      y[3], rho[3];

      PetscCall(PetscSectionGetDof(sec, v, &dof));
      if (dof != 3) continue;
      PetscCall(PetscSectionGetOffset(sec, v, &off));
      PetscCall(PetscSectionGetOffset(csec, v, &coff));
      for (PetscInt k = 0; k < 3; k++) {
        y[k]        = PetscRealPart(ca[coff + k]);
        xa[off + k] = mode < 0 ? ca[coff + k] : 0.0;
      }
      if (mode < 0 || f < 0 || mode < first[f] || mode >= first[f] + count[f]) continue;
      for (PetscInt m = 0; m < 6; m++) {
        RigidMotion(m, y, &centre[3 * f], size[f], rho);
        for (PetscInt k = 0; k < 3; k++) xa[off + k] += coef[6 * mode + m] * rho[k];
      }
      for (PetscInt k = 0; k < 3; k++)
        if (SSStarHeldIdentityRow(scene, v - vStart, k)) xa[off + k] = 0;
    }
    PetscCall(VecRestoreArrayWrite(xloc, &xa));
    PetscCall(DMCreateGlobalVector(dm, &x)); /* the held dofs are not in it */
    PetscCall(DMLocalToGlobal(dm, xloc, INSERT_VALUES, x));
    PetscCall(VecSetBlockSize(x, 3));
    if (mode < 0) {
      PetscCall(MatNullSpaceCreateRigidBody(x, &nsp));
      PetscCall(MatSetNearNullSpace(K, nsp));
      PetscCall(MatNullSpaceDestroy(&nsp));
      PetscCall(VecDestroy(&x));
    } else modes[mode] = x;
  }
  PetscCall(VecRestoreArrayRead(cloc, &ca));
  PetscCall(VecDestroy(&cloc));
  PetscCall(DMRestoreLocalVector(dm, &xloc));
  if (nmodes) {
    for (PetscInt f = 0; f < scene->nFloating; f++) /* Gram-Schmidt, twice, body by body */
      for (PetscInt k = first[f]; k < first[f] + count[f]; k++)
        for (PetscInt pass = 0; pass < 2; pass++) {
          for (PetscInt j = first[f]; j < k; j++) {
            PetscScalar dot;

            PetscCall(VecDot(modes[k], modes[j], &dot));
            PetscCall(VecAXPY(modes[k], -dot, modes[j]));
          }
          PetscCall(VecNormalize(modes[k], NULL));
        }
    PetscCall(MatNullSpaceCreate(scene->comm, PETSC_FALSE, nmodes, modes, &nsp));
    PetscCall(MatSetNullSpace(K, nsp));
    PetscCall(MatNullSpaceDestroy(&nsp));
  }
  for (PetscInt k = 0; k < nmodes; k++) PetscCall(VecDestroy(&modes[k]));
  PetscCall(PetscFree(modes));
  PetscCall(PetscFree(coef));
  PetscCall(PetscFree4(centre, size, count, first));
  PetscFunctionReturn(0);
}
