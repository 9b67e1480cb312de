/*
   Held dofs: the -dirichlet groups (u = 0, their nodes have no dofs: the section's constraints, mesh.c) and the
   prescribed displacements of -displacement_<G> x,y,z (each component a number or free, constant or a history
   t:x,y,z;...). A prescribed component keeps its dof, with an identity row of K: its row and column of every cell's
   matrix are zero but the diagonal, and the load there is diag(K) g, so that K u = b gives u = g there; the other dofs
   get the lifting b - K_{:,D} g of the prescribed values (docs/derivation.md section 15). A node prescribed in every
   component is no contact node; a contact node with some components prescribed is held so only as on a plane of
   symmetry (SSStarSceneCheckPartlyHeld()).
*/
#include "../sceneimpl.h"
#include <ctype.h>

static const char *const Axes[3] = {"x", "y", "z"};

/* Whether the piece text[0..len) is the word free (any case), spaces around it allowed */
static PetscBool IsFree(const char *text, size_t len)
{
  while (len && isspace((unsigned char)text[0])) {
    text++;
    len--;
  }
  while (len && isspace((unsigned char)text[len - 1])) len--;
  return (PetscBool)(len == 4 && tolower((unsigned char)text[0]) == 'f' && tolower((unsigned char)text[1]) == 'r' && tolower((unsigned char)text[2]) == 'e' && tolower((unsigned char)text[3]) == 'e');
}

/*
   The value of -displacement_<G> with every component written free replaced by 0 (numbers, as the history parser reads
   them), and the components free in some knot (bit k); the knots are separated by ';', a knot's components follow its
   ':' and are separated by ','
*/
static PetscErrorCode ReplaceFree(const char text[], char **numbers, PetscInt *free)
{
  char  *s;
  size_t len, start = 0;

  PetscFunctionBegin;
  *free = 0;
  PetscCall(PetscStrallocpy(text, numbers));
  s = *numbers;
  PetscCall(PetscStrlen(s, &len));
  while (start <= len) { /* one knot: s[start .. end) */
    size_t end = start, from, k = 0;

    while (end < len && s[end] != ';') end++;
    from = start;
    for (size_t i = start; i < end; i++)
      if (s[i] == ':') from = i + 1;
    while (from <= end) { /* one component: s[from .. to) */
      size_t to = from;

      while (to < end && s[to] != ',') to++;
      if (IsFree(s + from, to - from)) {
        if (k < 3) *free |= 1 << k;
        for (size_t i = from; i < to; i++) s[i] = ' ';
        s[from] = '0';
      }
      k++;
      from = to + 1;
    }
    start = end + 1;
  }
  PetscFunctionReturn(0);
}

/* SSStarPrescribedRead - the prescription of group named by option with the value text (the option's value) */
PetscErrorCode SSStarPrescribedRead(SSStarScene scene, const char option[], const char group[], const char text[], SSStarPrescribed *p)
{
  char *numbers;

  PetscFunctionBegin;
  PetscCheck(text && text[0], scene->comm, PETSC_ERR_ARG_WRONG, "Option %s needs a value: x,y,z (each a number or free), or knots t:x,y,z separated by ';'", option);
  PetscCall(ReplaceFree(text, &numbers, &p->free));
  PetscCall(SSStarHistoryDestroy(&p->history));
  PetscCall(SSStarHistoryCreateFromString(scene->comm, option, numbers, 3, &p->history));
  PetscCall(PetscFree(numbers));
  PetscCheck(p->free != 7, scene->comm, PETSC_ERR_ARG_WRONG, "Option %s %s: every component is free, nothing is prescribed", option, text);
  PetscCall(PetscStrncpy(p->name, group, sizeof(p->name)));
  PetscFunctionReturn(0);
}

/* "free,free,-0.01" or "history t:free,free,-0.01;..." of a prescription */
PetscErrorCode SSStarPrescribedText(const SSStarPrescribed *p, char text[], size_t len)
{
  PetscInt         n;
  const PetscReal *times, *v;

  PetscFunctionBegin;
  PetscCall(SSStarHistoryGetKnots(p->history, &n, &times, &v));
  text[0] = 0;
  if (n) PetscCall(PetscStrlcat(text, "history ", len));
  for (PetscInt i = 0; i < PetscMax(n, 1); i++) {
    char knot[128] = "", comp[3][32];

    for (PetscInt k = 0; k < 3; k++) {
      if (p->free & (1 << k)) PetscCall(PetscStrncpy(comp[k], "free", sizeof(comp[k])));
      else PetscCall(PetscSNPrintf(comp[k], sizeof(comp[k]), "%g", (double)v[3 * i + k]));
    }
    if (n) PetscCall(PetscSNPrintf(knot, sizeof(knot), "%s%g:", i ? ";" : "", (double)times[i]));
    PetscCall(PetscStrlcat(text, knot, len));
    PetscCall(PetscSNPrintf(knot, sizeof(knot), "%s,%s,%s", comp[0], comp[1], comp[2]));
    PetscCall(PetscStrlcat(text, knot, len));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarPrescribedDestroy(SSStarScene scene)
{
  PetscFunctionBegin;
  for (PetscInt d = 0; d < scene->nDisplacements; d++) PetscCall(SSStarHistoryDestroy(&scene->displacements[d].history));
  PetscCall(PetscFree(scene->displacements));
  scene->nDisplacements = 0;
  PetscCall(PetscFree(scene->heldBy));
  PetscCall(PetscFree(scene->loadHeld));
  PetscCall(PetscFree(scene->heldNames));
  PetscCall(VecDestroy(&scene->diagK));
  PetscCall(VecDestroy(&scene->lastLoad));
  PetscFunctionReturn(0);
}

/* The option that holds by held group h: "-dirichlet G" or "-displacement_G" */
PetscErrorCode SSStarHeldName(SSStarScene scene, PetscInt h, char name[], size_t len)
{
  PetscFunctionBegin;
  if (h < scene->nDirichlet) PetscCall(PetscSNPrintf(name, len, "-dirichlet %s", scene->dirichlet[h]));
  else PetscCall(PetscSNPrintf(name, len, "-displacement_%s", scene->displacements[h - scene->nDirichlet].name));
  PetscFunctionReturn(0);
}

/* The value of component k of held group h at time t (a -dirichlet group's: 0) */
static PetscErrorCode HeldValue(SSStarScene scene, PetscInt h, PetscInt k, PetscReal t, PetscReal *value)
{
  PetscReal v[3];

  PetscFunctionBegin;
  *value = 0;
  if (h < scene->nDirichlet) PetscFunctionReturn(0);
  PetscCall(SSStarHistoryEvaluate(scene->displacements[h - scene->nDirichlet].history, t, v));
  *value = v[k];
  PetscFunctionReturn(0);
}

/* SSStarHeldValues - the values of the held groups at time t: 3 per held group (0 for -dirichlet and free components) */
PetscErrorCode SSStarHeldValues(SSStarScene scene, PetscReal t, PetscReal values[])
{
  PetscFunctionBegin;
  for (PetscInt h = 0; h < scene->nDirichlet + scene->nDisplacements; h++)
    for (PetscInt k = 0; k < 3; k++) PetscCall(HeldValue(scene, h, k, t, &values[3 * h + k]));
  PetscFunctionReturn(0);
}

/* Whether component k of held groups a and b is the same function of time (at every knot of both: both are linear between) */
static PetscErrorCode SameValues(SSStarScene scene, PetscInt a, PetscInt b, PetscInt k, PetscBool *same)
{
  PetscInt         n[2] = {0, 0};
  const PetscReal *times[2] = {NULL, NULL};

  PetscFunctionBegin;
  *same = PETSC_TRUE;
  for (PetscInt s = 0; s < 2; s++) {
    const PetscInt h = s ? b : a;

    if (h >= scene->nDirichlet) PetscCall(SSStarHistoryGetKnots(scene->displacements[h - scene->nDirichlet].history, &n[s], &times[s], NULL));
  }
  for (PetscInt s = 0; s < 2; s++)
    for (PetscInt i = -1; i < n[s] && *same; i++) { /* i = -1: any time of a constant */
      const PetscReal t = i < 0 ? 0 : times[s][i];
      PetscReal       va, vb;

      PetscCall(HeldValue(scene, a, k, t, &va));
      PetscCall(HeldValue(scene, b, k, t, &vb));
      *same = (PetscBool)(PetscAbsReal(va - vb) <= 1e-14 * PetscMax(PetscAbsReal(va), PetscAbsReal(vb)));
    }
  PetscFunctionReturn(0);
}

/*
   SSStarSceneFindHeld - the held group of every component of every local vertex (scene->heldBy): the first -dirichlet
   group of the node, else for each component the first -displacement_<G> group that prescribes it. A component two
   groups hold with different values is refused, naming the node and both groups.
*/
PetscErrorCode SSStarSceneFindHeld(SSStarScene scene)
{
  const PetscInt     nheld = scene->nDirichlet + scene->nDisplacements;
  DMLabel           *labels;
  PetscInt           vStart, vEnd;
  PetscBool         *same;
  SSStarBadNode      bad = {-1, -1, -1, {0, 0, 0}, 0};
  PetscInt           badComponent = -1;
  PetscBool          found;
  DM                 cdm;
  PetscSection       csec;
  Vec                coordinates;
  const PetscScalar *ta, *xa;

  PetscFunctionBegin;
  PetscCall(DMPlexGetDepthStratum(scene->dm, 0, &vStart, &vEnd));
  PetscCall(PetscFree(scene->heldBy));
  PetscCall(PetscMalloc1(3 * (vEnd - vStart) + 1, &scene->heldBy));
  PetscCall(PetscMalloc2(nheld + 1, &labels, 3 * nheld * nheld + 1, &same));
  for (PetscInt h = 0; h < nheld; h++) PetscCall(DMGetLabel(scene->dm, h < scene->nDirichlet ? scene->dirichlet[h] : scene->displacements[h - scene->nDirichlet].name, &labels[h]));
  for (PetscInt a = 0; a < nheld; a++)
    for (PetscInt b = 0; b < nheld; b++)
      for (PetscInt k = 0; k < 3; k++) PetscCall(SameValues(scene, a, b, k, &same[3 * (nheld * a + b) + k]));
  PetscCall(DMGetCoordinatesLocal(scene->dm, &coordinates));
  PetscCall(DMGetCoordinateDM(scene->dm, &cdm));
  PetscCall(DMGetLocalSection(cdm, &csec));
  PetscCall(VecGetArrayRead(coordinates, &xa));
  PetscCall(VecGetArrayRead(scene->tags, &ta));
  for (PetscInt v = vStart; v < vEnd; v++) {
    PetscInt *held = &scene->heldBy[3 * (v - vStart)];

    held[0] = held[1] = held[2] = -1;
    for (PetscInt h = 0; h < nheld; h++) {
      const PetscInt free = h < scene->nDirichlet ? 0 : scene->displacements[h - scene->nDirichlet].free;
      PetscInt       value;

      PetscCall(DMLabelGetValue(labels[h], v, &value));
      if (value < 0) continue;
      for (PetscInt k = 0; k < 3; k++) {
        if (free & (1 << k)) continue;
        if (held[k] < 0) held[k] = h;
        else if (!same[3 * (nheld * held[k] + h) + k] && bad.tag < 0) {
          PetscInt off;

          bad.tag   = (PetscInt)PetscRealPart(ta[v - vStart]);
          bad.group = held[k];
          bad.other = h;
          badComponent = k;
          PetscCall(PetscSectionGetOffset(csec, v, &off));
          for (PetscInt c = 0; c < 3; c++) bad.x[c] = PetscRealPart(xa[off + c]);
        }
      }
    }
  }
  PetscCall(VecRestoreArrayRead(scene->tags, &ta));
  PetscCall(VecRestoreArrayRead(coordinates, &xa));
  PetscCall(PetscFree2(labels, same));
  bad.gap = (PetscReal)badComponent; /* the component travels in the gap's place */
  PetscCall(SSStarSceneShareBadNode(scene->comm, &bad, &found));
  if (found) {
    char a[SSSTAR_GROUP_NAME_LEN + 16], b[SSSTAR_GROUP_NAME_LEN + 16];

    PetscCall(SSStarHeldName(scene, bad.group, a, sizeof(a)));
    PetscCall(SSStarHeldName(scene, bad.other, b, sizeof(b)));
    SETERRQ(scene->comm, PETSC_ERR_ARG_WRONG, "Mesh node %" PetscInt_FMT " (0-based, file order) at (%g, %g, %g) is prescribed twice with different values: its %s displacement by %s and by %s", bad.tag, (double)bad.x[0], (double)bad.x[1], (double)bad.x[2], Axes[(PetscInt)bad.gap], a, b);
  }
  PetscFunctionReturn(0);
}

/* SSStarHeldIdentityRow - whether component k of local vertex v (numbered from vStart) is prescribed with an identity row */
PetscBool SSStarHeldIdentityRow(SSStarScene scene, PetscInt v, PetscInt k)
{
  return (PetscBool)(scene->heldBy && scene->heldBy[3 * v + k] >= scene->nDirichlet);
}

/* SSStarHeldElement - a cell's matrix with the rows and columns of its prescribed components zero but the diagonal */
void SSStarHeldElement(SSStarScene scene, const PetscInt v[4], PetscScalar K[144])
{
  for (PetscInt a = 0; a < 4; a++)
    for (PetscInt k = 0; k < 3; k++) {
      const PetscInt r = 3 * a + k;

      if (!SSStarHeldIdentityRow(scene, v[a], k)) continue;
      for (PetscInt j = 0; j < 12; j++)
        if (j != r) K[12 * r + j] = K[12 * j + r] = 0;
    }
}

/*
   SSStarHeldLift - subtracts the lifting K_{:,D} g of the prescribed values (values: SSStarHeldValues()) from the local
   load Floc at the dofs that are not held (the held ones get diag(K) g: SSStarHeldPrescribe())
*/
PetscErrorCode SSStarHeldLift(SSStarScene scene, const SSStarCells *cells, const PetscReal values[], Vec Floc)
{
  PetscSection sec;
  PetscScalar *fa;

  PetscFunctionBegin;
  if (!scene->nDisplacements) PetscFunctionReturn(0);
  PetscCall(DMGetLocalSection(scene->dm, &sec));
  PetscCall(VecGetArray(Floc, &fa));
  for (PetscInt c = 0; c < cells->cEnd - cells->cStart; c++) {
    const PetscInt *v = &cells->vertices[4 * c];
    PetscReal       g[12], x[12];
    PetscScalar     Ke[144];
    PetscBool       any = PETSC_FALSE;

    for (PetscInt a = 0; a < 4; a++)
      for (PetscInt k = 0; k < 3; k++) {
        g[3 * a + k] = SSStarHeldIdentityRow(scene, v[a], k) ? values[3 * scene->heldBy[3 * v[a] + k] + k] : 0;
        any          = (PetscBool)(any || g[3 * a + k] != 0);
      }
    if (!any) continue;
    PetscCall(SSStarCellsGet(cells, c, x));
    SSStarTetStiffness(x, cells->lame[c][0], cells->lame[c][1], Ke);
    for (PetscInt a = 0; a < 4; a++) {
      PetscInt off;

      PetscCall(PetscSectionGetOffset(sec, cells->vStart + v[a], &off));
      for (PetscInt k = 0; k < 3; k++) {
        PetscReal f = 0;

        if (scene->heldBy[3 * v[a] + k] >= 0) continue;
        for (PetscInt j = 0; j < 12; j++) f += PetscRealPart(Ke[12 * (3 * a + k) + j]) * g[j];
        fa[off + k] -= f;
      }
    }
  }
  PetscCall(VecRestoreArray(Floc, &fa));
  PetscFunctionReturn(0);
}

/* SSStarHeldPrescribe - b = diag(K) g at the owned dofs of prescribed components (values: SSStarHeldValues()) */
PetscErrorCode SSStarHeldPrescribe(SSStarScene scene, const PetscReal values[], Vec b)
{
  PetscSection       gsec;
  PetscInt           vStart, vEnd, rstart;
  PetscScalar       *ba;
  const PetscScalar *da;

  PetscFunctionBegin;
  if (!scene->nDisplacements) PetscFunctionReturn(0);
  PetscCheck(scene->diagK, scene->comm, PETSC_ERR_ARG_WRONGSTATE, "The load of prescribed displacements needs K: SSStarSceneAssemble() first");
  PetscCall(DMGetGlobalSection(scene->dm, &gsec));
  PetscCall(DMPlexGetDepthStratum(scene->dm, 0, &vStart, &vEnd));
  PetscCall(VecGetOwnershipRange(b, &rstart, NULL));
  PetscCall(VecGetArray(b, &ba));
  PetscCall(VecGetArrayRead(scene->diagK, &da));
  for (PetscInt v = vStart; v < vEnd; v++) {
    PetscInt off;

    PetscCall(PetscSectionGetOffset(gsec, v, &off));
    if (off < 0) continue; /* a ghost */
    for (PetscInt k = 0; k < 3; k++)
      if (SSStarHeldIdentityRow(scene, v - vStart, k)) ba[off - rstart + k] = da[off - rstart + k] * values[3 * scene->heldBy[3 * (v - vStart) + k] + k];
  }
  PetscCall(VecRestoreArrayRead(scene->diagK, &da));
  PetscCall(VecRestoreArray(b, &ba));
  PetscFunctionReturn(0);
}

/* Whether component k of a history is 0 at every time (NULL: no history, 0) */
static PetscErrorCode ZeroComponent(SSStarHistory h, PetscInt k, PetscBool *zero)
{
  PetscInt         n;
  const PetscReal *v;

  PetscFunctionBegin;
  *zero = PETSC_TRUE;
  if (!h) PetscFunctionReturn(0);
  PetscCall(SSStarHistoryGetKnots(h, &n, NULL, &v));
  for (PetscInt i = 0; i < PetscMax(n, 1); i++) *zero = (PetscBool)(*zero && v[3 * i + k] == 0);
  PetscFunctionReturn(0);
}

/*
   SSStarSceneCheckPartlyHeld - a contact node with some components prescribed (a rim node of a face held in x only)
   stays a contact node with those components held by their identity rows. That is exact when the contact force has no
   component along them, which the law guarantees on a plane of symmetry (docs/derivation.md section 15): the
   prescribed value 0 at every time, the contact normal at the node perpendicular to it, a rigid obstacle that does not
   move along it, a friction law isotropic in the tangent plane (none, tresca, coulomb). Any other such node is
   refused, naming it, its contact group and its held group.
*/
PetscErrorCode SSStarSceneCheckPartlyHeld(SSStarScene scene)
{
  SSStarBadNode bad    = {-1, -1, -1, {0, 0, 0}, 0};
  const char   *why[5] = {"its prescribed value is not 0 at every time", "the contact normal at the node has a component along it", "its group's contact is a contact pair", "the obstacle moves along it", "the friction law is not isotropic in the tangent plane (none, tresca or coulomb)"};
  PetscBool     found;

  PetscFunctionBegin;
  for (PetscInt i = 0; i < scene->n && bad.tag < 0; i++)
    for (PetscInt k = 0; k < 3 && bad.tag < 0; k++) {
      const PetscInt            h  = scene->contactHeld[3 * i + k];
      const SSStarContactGroup *cg = &scene->contact[scene->group[i]];
      PetscBool                 zero, still, isotropic = PETSC_FALSE;
      const char               *law;
      PetscInt                  reason = -1;

      if (h < 0) continue;
      PetscCall(ZeroComponent(scene->displacements[h - scene->nDirichlet].history, k, &zero));
      PetscCall(ZeroComponent(cg->motion, k, &still));
      PetscCall(SSStarLawGetInfo(cg->law, &law, NULL, NULL, NULL));
      for (PetscInt l = 0; l < 3; l++) {
        PetscBool same;

        PetscCall(PetscStrcmp(law, l == 0 ? SSSTARLAWNONE : l == 1 ? SSSTARLAWTRESCA : SSSTARLAWCOULOMB, &same));
        isotropic = (PetscBool)(isotropic || same);
      }
      if (!zero) reason = 0;
      else if (cg->master[0]) reason = 2;
      else if (PetscAbsReal(scene->normal[3 * i + k]) > 1e-10) reason = 1;
      else if (!still) reason = 3;
      else if (!isotropic) reason = 4;
      if (reason < 0) continue;
      bad.tag   = scene->tag[i];
      bad.group = scene->group[i];
      bad.other = h;
      bad.gap   = 5 * k + reason; /* the component and the reason travel in the gap's place */
      PetscCall(PetscArraycpy(bad.x, &scene->coords[3 * i], 3));
    }
  PetscCall(SSStarSceneShareBadNode(scene->comm, &bad, &found));
  if (found) {
    const PetscInt code = (PetscInt)bad.gap;
    char           held[SSSTAR_GROUP_NAME_LEN + 16];

    PetscCall(SSStarHeldName(scene, bad.other, held, sizeof(held)));
    SETERRQ(scene->comm, PETSC_ERR_SUP, "Mesh node %" PetscInt_FMT " (0-based, file order) at (%g, %g, %g) of contact group \"%s\" has its %s displacement prescribed by %s: a contact node may have some components prescribed only as on a plane of symmetry (the value 0, perpendicular to the contact normal, against a rigid obstacle that does not move along it, with the law none, tresca or coulomb); here %s", bad.tag, (double)bad.x[0], (double)bad.x[1], (double)bad.x[2], scene->contact[bad.group].name, Axes[code / 5], held, why[code % 5]);
  }
  PetscFunctionReturn(0);
}
