/*
   Bodies held by contact alone (docs/derivation.md section 14). A body without a Dirichlet condition or a spring has
   rigid-body motions that K does not resist: K is semidefinite, and the program declares those motions as K's null
   space (MatSetNullSpace(); the scenes give six per floating body). What the iteration does with them:

     the balance (14.3): the load's work on them must be taken by contact forces the friction laws allow; where no
       such forces exist there is no equilibrium, and the solve stops before its first iteration with the motion along
       which the body goes (SNESSSStarCheckEquilibrium);
     the free motions of a Newton step (14.5): where the step's states hold no force along some of them (separated or
       sliding nodes), its matrix would be singular; they get a proximal term of the approximation step's stiffness,
       A + (1/gamma) U U^T on them alone, which changes the step, not the solutions (SSStarFloatingFreeMotions);
     the least-norm solution (14.6): motions no contact point can resist at all (a frictionless body on a plane: its
       sliding along the plane) leave a family of solutions; the one of smallest ||u|| is returned.
*/
#include "../ssstarimpl.h"
#include "../laws/lawimpl.h"
#include <petscblaslapack.h>

/* a motion the contact points move by less than this (the eigenvalue of Rc^T Rc relative to the largest) is not held */
#define SSSTAR_FLOATING_HELD_TOL 1e-12
/* a motion is free in a Newton step when its known rows hold less than this fraction of |Rc y|^2 */
#define SSSTAR_FLOATING_FREE_TOL 1e-8
PetscErrorCode SSStarFloatingReset(SSStarFloating *fb)
{
  PetscFunctionBegin;
  for (PetscInt k = 0; k < fb->m; k++) PetscCall(VecDestroy(&fb->modes[k]));
  for (PetscInt k = 0; k < fb->m && fb->pmodes; k++) PetscCall(VecDestroy(&fb->pmodes[k]));
  PetscCall(PetscFree(fb->pmodes));
  PetscCall(PetscFree(fb->Y));
  for (PetscInt k = 0; k < fb->nfixed; k++) PetscCall(VecDestroy(&fb->fixed[k]));
  PetscCall(PetscFree(fb->modes));
  PetscCall(PetscFree(fb->fixed));
  PetscCall(PetscFree3(fb->Rc, fb->G, fb->body));
  PetscCall(PetscFree2(fb->free, fb->freeGlobal));
  PetscCall(VecDestroy(&fb->motion));
  PetscCall(PetscMemzero(fb, sizeof(*fb)));
  PetscFunctionReturn(0);
}

/* Orthonormal copies of v[0..n) (modified Gram-Schmidt, twice) */
static PetscErrorCode Orthonormalize(PetscInt n, Vec v[])
{
  PetscFunctionBegin;
  for (PetscInt k = 0; k < n; k++) {
    PetscReal norm;

    for (PetscInt pass = 0; pass < 2; pass++)
      for (PetscInt j = 0; j < k; j++) {
        PetscScalar dot;

        PetscCall(VecDot(v[k], v[j], &dot));
        PetscCall(VecAXPY(v[k], -dot, v[j]));
      }
    PetscCall(VecNormalize(v[k], &norm));
    PetscCheck(norm > 0, PetscObjectComm((PetscObject)v[k]), PETSC_ERR_ARG_WRONG, "ssstar: K's null space (MatSetNullSpace) has linearly dependent vectors (vector %" PetscInt_FMT ")", k);
  }
  PetscFunctionReturn(0);
}

/*
   The generalized eigenproblem A y = lambda B y of m x m symmetric matrices (B positive definite; column-major,
   overwritten): eigenvalues ascending into w, eigenvectors (B-orthonormal) into A's columns
*/
static PetscErrorCode Eigen(PetscInt m, PetscReal A[], PetscReal B[], PetscReal w[])
{
  PetscBLASInt n, one = 1, lwork, info;
  PetscReal   *work;

  PetscFunctionBegin;
  PetscCall(PetscBLASIntCast(m, &n));
  lwork = 3 * n + 16;
  PetscCall(PetscMalloc1(lwork, &work));
  PetscCall(PetscFPTrapPush(PETSC_FP_TRAP_OFF));
  PetscCallBLAS("LAPACKsygv", LAPACKsygv_(&one, "V", "U", &n, A, &n, B, &n, w, work, &lwork, &info));
  PetscCall(PetscFPTrapPop());
  PetscCall(PetscFree(work));
  PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "LAPACK sygv failed: info %d", (int)info);
  PetscFunctionReturn(0);
}

/* sum over every node of Rc_ir^T Rc_ir (m x m) over its rows r with bit r of rows[i] set (rows NULL: every row) */
static PetscErrorCode RowGram(MPI_Comm comm, const SSStarFloating *fb, const unsigned char *rows, PetscReal G[])
{
  const PetscInt m = fb->m;

  PetscFunctionBegin;
  PetscCall(PetscArrayzero(G, m * m));
  for (PetscInt i = 0; i < fb->nnodes; i++)
    for (PetscInt r = 0; r < 3; r++) {
      const PetscReal *a = &fb->Rc[(3 * i + r) * m];

      if (rows && !(rows[i] & (1 << r))) continue;
      for (PetscInt k = 0; k < m; k++)
        for (PetscInt l = 0; l < m; l++) G[k * m + l] += a[k] * a[l];
    }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, G, m * m, MPIU_REAL, MPIU_SUM, comm));
  PetscFunctionReturn(0);
}

/* sum over every node of Rc_i^T sym(T_i) Rc_i (m x m) */
static PetscErrorCode HeldGram(MPI_Comm comm, const SSStarFloating *fb, const PetscReal T[], PetscReal G[])
{
  const PetscInt m = fb->m;

  PetscFunctionBegin;
  PetscCall(PetscArrayzero(G, m * m));
  for (PetscInt i = 0; i < fb->nnodes; i++)
    for (PetscInt r = 0; r < 3; r++)
      for (PetscInt c = 0; c < 3; c++) {
        const PetscReal  t = 0.5 * (T[9 * i + 3 * r + c] + T[9 * i + 3 * c + r]);
        const PetscReal *a = &fb->Rc[(3 * i + r) * m], *b = &fb->Rc[(3 * i + c) * m];

        if (t == 0) continue;
        for (PetscInt k = 0; k < m; k++)
          for (PetscInt l = 0; l < m; l++) G[k * m + l] += t * a[k] * b[l];
      }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, G, m * m, MPIU_REAL, MPIU_SUM, comm));
  PetscFunctionReturn(0);
}

/* The motions' values at the contact points in their frames: (B rho_k)_i = R_i (T^-1 rho_k) at the point's own dofs */
static PetscErrorCode ContactValues(SSStarContact *ct, SSStarFloating *fb)
{
  const PetscInt m = fb->m;
  Vec            w, wC;

  PetscFunctionBegin;
  PetscCall(PetscMalloc1(m, &fb->pmodes));
  for (PetscInt k = 0; k < m; k++) {
    const PetscScalar *a;

    PetscCall(VecDuplicate(fb->modes[k], &fb->pmodes[k]));
    w = fb->pmodes[k];
    PetscCall(SSStarContactToPointVariables(ct, fb->modes[k], w));
    if (ct->isC) PetscCall(VecGetSubVector(w, ct->isC, &wC));
    else wC = w;
    PetscCall(VecGetArrayRead(wC, &a));
    for (PetscInt i = 0; i < fb->nnodes; i++) {
      const PetscReal *R = ct->frames ? &ct->frames[9 * i] : NULL;

      for (PetscInt r = 0; r < 3; r++) fb->Rc[(3 * i + r) * m + k] = R ? R[3 * r] * PetscRealPart(a[3 * i]) + R[3 * r + 1] * PetscRealPart(a[3 * i + 1]) + R[3 * r + 2] * PetscRealPart(a[3 * i + 2]) : PetscRealPart(a[3 * i + r]);
    }
    PetscCall(VecRestoreArrayRead(wC, &a));
    if (ct->isC) PetscCall(VecRestoreSubVector(w, ct->isC, &wC));
  }
  PetscFunctionReturn(0);
}

/* The floating bodies: motions that move a common dof belong to one body (union-find over the motions) */
static PetscErrorCode GroupBodies(SSStarFloating *fb)
{
  const PetscInt     m = fb->m;
  PetscReal         *overlap;
  const PetscScalar *a, *b;
  PetscInt           n, *root;

  PetscFunctionBegin;
  PetscCall(PetscCalloc2(m * m, &overlap, m, &root));
  PetscCall(VecGetLocalSize(fb->modes[0], &n));
  for (PetscInt k = 0; k < m; k++) {
    PetscCall(VecGetArrayRead(fb->modes[k], &a));
    for (PetscInt l = 0; l < k; l++) {
      PetscCall(VecGetArrayRead(fb->modes[l], &b));
      for (PetscInt j = 0; j < n; j++) overlap[k * m + l] += PetscAbsScalar(a[j]) * PetscAbsScalar(b[j]);
      PetscCall(VecRestoreArrayRead(fb->modes[l], &b));
    }
    PetscCall(VecRestoreArrayRead(fb->modes[k], &a));
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, overlap, m * m, MPIU_REAL, MPIU_SUM, PetscObjectComm((PetscObject)fb->modes[0])));
  for (PetscInt k = 0; k < m; k++) root[k] = k;
  for (PetscInt k = 0; k < m; k++)
    for (PetscInt l = 0; l < k; l++)
      if (overlap[k * m + l] > 0) {
        PetscInt rk = k, rl = l;

        while (root[rk] != rk) rk = root[rk];
        while (root[rl] != rl) rl = root[rl];
        root[PetscMax(rk, rl)] = PetscMin(rk, rl);
      }
  fb->nbodies = 0;
  for (PetscInt k = 0; k < m; k++) {
    PetscInt r = k;

    while (root[r] != r) r = root[r];
    if (r == k) fb->body[k] = fb->nbodies++;
    else fb->body[k] = fb->body[r];
  }
  PetscCall(PetscFree2(overlap, root));
  PetscFunctionReturn(0);
}

/*
   The motions no contact point can resist (14.6): zero normal component at every point and zero tangential component
   at every point with friction. Orthonormal combinations of the motions, for the least-norm solution.
*/
static PetscErrorCode FixedMotions(SSStarContact *ct, SSStarFloating *fb)
{
  const PetscInt m = fb->m;
  MPI_Comm       comm = PetscObjectComm((PetscObject)fb->modes[0]);
  unsigned char *rows;
  PetscReal     *G0, *G, *w, *Y;
  PetscInt       nfixed = 0;

  PetscFunctionBegin;
  PetscCall(PetscMalloc5(fb->nnodes + 1, &rows, m * m, &G0, m * m, &G, m, &w, m * m, &Y));
  for (PetscInt i = 0; i < fb->nnodes; i++) {
    const SSStarFriction *fr = &ct->nodeFriction[i];

    rows[i] = (unsigned char)(fr->law->ops.frictionless(fr) ? 4 : 7);
  }
  PetscCall(RowGram(comm, fb, rows, G0));
  PetscCall(PetscArraycpy(G, fb->G, m * m));
  PetscCall(Eigen(m, G0, G, w));
  for (PetscInt k = 0; k < m && w[k] <= SSSTAR_FLOATING_FREE_TOL; k++) PetscCall(PetscArraycpy(&Y[m * nfixed++], &G0[m * k], m));
  if (nfixed) {
    PetscCall(PetscMalloc1(nfixed, &fb->fixed));
    for (PetscInt j = 0; j < nfixed; j++) {
      PetscCall(VecDuplicate(fb->modes[0], &fb->fixed[j]));
      PetscCall(VecZeroEntries(fb->fixed[j]));
      for (PetscInt k = 0; k < m; k++) PetscCall(VecAXPY(fb->fixed[j], Y[m * j + k], fb->modes[k]));
    }
    PetscCall(Orthonormalize(nfixed, fb->fixed));
  }
  fb->nfixed = nfixed;
  PetscCall(PetscFree5(rows, G0, G, w, Y));
  PetscFunctionReturn(0);
}

/*
   K's null space as declared (MatSetNullSpace(K, ...)), for the contact of ct (set up): the motions orthonormalized,
   checked (K rho = 0 to round-off for an affine residual; every motion moved by some contact point: a body nothing
   holds is refused before any factorization), their values at the contact points, the bodies, the motions no contact
   resists. Nothing when K has no null space. A nonlinear residual's J(u) at a stressed state does not annul the
   rotations of the current configuration (J(u) (Omega x) = Omega f(u), docs/derivation.md (18.10)): there the motions
   only regularize the Newton step (18b) and are not checked against J.
*/
PetscErrorCode SSStarFloatingSetUp(SSStarContact *ct, Mat K, PetscBool nonlinear, SSStarFloating *fb)
{
  MPI_Comm     comm = PetscObjectComm((PetscObject)K);
  MatNullSpace nsp;
  PetscBool    hasConstant;
  PetscInt     m;
  const Vec   *vecs;
  PetscReal    Knorm, *G, *Id, *w;
  Vec          Kr;

  PetscFunctionBegin;
  PetscCall(SSStarFloatingReset(fb));
  PetscCall(MatGetNullSpace(K, &nsp));
  if (!nsp) PetscFunctionReturn(0);
  PetscCall(MatNullSpaceGetVecs(nsp, &hasConstant, &m, &vecs));
  PetscCheck(!hasConstant, comm, PETSC_ERR_ARG_WRONG, "ssstar: K's null space (MatSetNullSpace) holds the constant vector; give the rigid-body motions of the floating bodies as vectors");
  if (!m) PetscFunctionReturn(0);
  fb->m = m;
  PetscCall(PetscMalloc1(m, &fb->modes));
  for (PetscInt k = 0; k < m; k++) {
    PetscCall(VecDuplicate(vecs[k], &fb->modes[k]));
    PetscCall(VecCopy(vecs[k], fb->modes[k]));
  }
  PetscCall(Orthonormalize(m, fb->modes));
  /* K rho = 0: a null space that is not K's would make every answer below wrong (the reduction's P, the least-norm
     solution); a nonlinear residual uses neither */
  PetscCall(MatNorm(K, NORM_INFINITY, &Knorm));
  PetscCall(VecDuplicate(fb->modes[0], &Kr));
  for (PetscInt k = 0; k < m && !nonlinear; k++) {
    PetscReal rnorm, vnorm;

    PetscCall(MatMult(K, fb->modes[k], Kr));
    PetscCall(VecNorm(Kr, NORM_INFINITY, &rnorm));
    PetscCall(VecNorm(fb->modes[k], NORM_INFINITY, &vnorm));
    PetscCheck(rnorm <= 1e-8 * Knorm * vnorm, comm, PETSC_ERR_ARG_WRONG, "ssstar: vector %" PetscInt_FMT " of K's null space (MatSetNullSpace) is not one: |K v| = %g |K| |v| (max norms); give the rigid-body motions of the bodies that nothing but contact holds", k, (double)(rnorm / (Knorm * vnorm)));
  }
  PetscCall(VecDestroy(&Kr));

  fb->nnodes = ct->nnodes;
  fb->frames = ct->frames;
  PetscCall(PetscMalloc3(3 * ct->nnodes * m + 1, &fb->Rc, m * m, &fb->G, m, &fb->body));
  PetscCall(ContactValues(ct, fb));
  PetscCall(RowGram(comm, fb, NULL, fb->G));
  PetscCall(GroupBodies(fb));
  /* a motion that no contact point moves: nothing holds that body (and K without the contact dofs is singular) */
  PetscCall(PetscMalloc3(m * m, &G, m * m, &Id, m, &w));
  PetscCall(PetscArraycpy(G, fb->G, m * m));
  PetscCall(PetscArrayzero(Id, m * m));
  for (PetscInt k = 0; k < m; k++) Id[k * m + k] = 1;
  PetscCall(Eigen(m, G, Id, w));
  if (!(w[0] > SSSTAR_FLOATING_HELD_TOL * w[m - 1])) {
    PetscInt  worst = 0;
    PetscReal big   = 0;

    for (PetscInt k = 0; k < m; k++)
      if (PetscAbsReal(G[k]) > big) {
        big   = PetscAbsReal(G[k]);
        worst = k;
      }
    PetscCall(PetscFree3(G, Id, w));
    SETERRQ(comm, PETSC_ERR_ARG_WRONG, "ssstar: K is singular and no contact point holds some of its rigid-body motions (mostly motion %" PetscInt_FMT " of its null space, floating body %" PetscInt_FMT "): a body held neither by Dirichlet conditions, springs nor contact", worst, fb->body[worst]);
  }
  PetscCall(PetscFree3(G, Id, w));
  PetscCall(FixedMotions(ct, fb));
  PetscCall(PetscInfo(NULL, "K's null space: %" PetscInt_FMT " rigid-body motions of %" PetscInt_FMT " floating bodies, %" PetscInt_FMT " of them resisted by no contact point (least-norm)\n", m, fb->nbodies, fb->nfixed));
  PetscFunctionReturn(0);
}

/*
   The motions the current Newton step leaves free (14.5): those the step's T blocks do not hold, i.e. the eigenvectors
   of G_T y = lambda G y with lambda ~ 0, G_T = sum_i Rc_i^T sym(T_i) Rc_i (a known row, T row r = e_r: sticking nodes
   and the normal of nodes in contact; a sliding node's W, which resists a motion across its slip); U = Rc y with the
   known rows (bit r of known[i]: row r of node i) set to zero, orthonormal over the contact dofs (y^T G y = 1), in the
   nodes' frames and in global axes.
*/
PetscErrorCode SSStarFloatingFreeMotions(SSStarFloating *fb, const unsigned char known[], const PetscReal T[])
{
  const PetscInt m = fb->m, n3 = 3 * fb->nnodes;
  MPI_Comm       comm = PetscObjectComm((PetscObject)fb->modes[0]);
  PetscReal     *Gk, *G, *w;

  PetscFunctionBegin;
  fb->nfree = 0;
  if (!m) PetscFunctionReturn(0);
  PetscCall(PetscMalloc3(m * m, &Gk, m * m, &G, m, &w));
  PetscCall(HeldGram(comm, fb, T, Gk));
  PetscCall(PetscArraycpy(G, fb->G, m * m));
  PetscCall(Eigen(m, Gk, G, w));
  while (fb->nfree < m && w[fb->nfree] <= SSSTAR_FLOATING_FREE_TOL) fb->nfree++;
  if (fb->nfree) {
    PetscCall(PetscFree2(fb->free, fb->freeGlobal));
    PetscCall(PetscFree(fb->Y));
    PetscCall(PetscMalloc2(n3 * fb->nfree + 1, &fb->free, n3 * fb->nfree + 1, &fb->freeGlobal));
    PetscCall(PetscMalloc1(m * fb->nfree, &fb->Y));
    PetscCall(PetscArraycpy(fb->Y, Gk, m * fb->nfree));
    for (PetscInt f = 0; f < fb->nfree; f++) {
      const PetscReal *y = &Gk[m * f];
      PetscReal       *u = &fb->free[n3 * f], *ug = &fb->freeGlobal[n3 * f];

      for (PetscInt d = 0; d < n3; d++) {
        u[d] = 0;
        if (known[d / 3] & (1 << (d % 3))) continue;
        for (PetscInt k = 0; k < m; k++) u[d] += fb->Rc[d * m + k] * y[k];
      }
      for (PetscInt i = 0; i < fb->nnodes; i++) {
        const PetscReal *R = fb->frames ? &fb->frames[9 * i] : NULL;

        for (PetscInt k = 0; k < 3; k++) ug[3 * i + k] = R ? R[k] * u[3 * i] + R[3 + k] * u[3 * i + 1] + R[6 + k] * u[3 * i + 2] : u[3 * i + k];
      }
    }
  }
  PetscCall(PetscFree3(Gk, G, w));
  PetscFunctionReturn(0);
}

/* x minus its part along the motions no contact point resists: the least-norm solution (14.6) */
PetscErrorCode SSStarFloatingLeastNorm(SSStarFloating *fb, Vec x)
{
  PetscFunctionBegin;
  for (PetscInt j = 0; j < fb->nfixed; j++) {
    PetscScalar dot;

    PetscCall(VecDot(x, fb->fixed[j], &dot));
    PetscCall(VecAXPY(x, -dot, fb->fixed[j]));
  }
  PetscFunctionReturn(0);
}


/* -snes_view: the floating bodies, if any */
PetscErrorCode SSStarFloatingView(SSStarFloating *fb, PetscViewer viewer)
{
  PetscFunctionBegin;
  if (!fb->m) PetscFunctionReturn(0);
  PetscCall(PetscViewerASCIIPrintf(viewer, "  floating bodies (held by contact alone): %" PetscInt_FMT ", K's null space of %" PetscInt_FMT " rigid-body motions; %" PetscInt_FMT " of them resisted by no contact point (the least-norm solution)\n", fb->nbodies, fb->m, fb->nfixed));
  PetscFunctionReturn(0);
}
