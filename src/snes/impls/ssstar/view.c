/*
   What the SNES type "ssstar" reads from the options database and prints: SNESSetFromOptions() (the options of the
   friction laws and the reductions from their tables), -snes_view, the line of -snes_converged_reason and the state
   monitor.
*/
#include "ssstarimpl.h"
#include "laws/lawimpl.h"
#include "../../../sys/meminfo.h"

/*
   A value of a list option that is not in the list, refused here with PETSc's message: PETSc 3.18's
   PetscOptionsEList() writes one byte past its buffer when it refuses a value and the names fill the buffer exactly
   (as "none tresca coulomb orthotropic " and "direct mumps explicit none auto " do)
*/
static PetscErrorCode RefuseUnknownChoice(PetscOptionItems *PetscOptionsObject, const char opt[], const char *const list[], PetscInt n)
{
  char      given[256], names[512] = "";
  PetscBool set, found = PETSC_FALSE;

  PetscFunctionBegin;
  PetscCall(PetscOptionsGetString(PetscOptionsObject->options, PetscOptionsObject->prefix, opt, given, sizeof(given), &set));
  if (!set) PetscFunctionReturn(0);
  for (PetscInt k = 0; k < n && !found; k++) PetscCall(PetscStrcasecmp(given, list[k], &found));
  if (found) PetscFunctionReturn(0);
  for (PetscInt k = 0; k < n; k++) {
    PetscCall(PetscStrlcat(names, list[k], sizeof(names)));
    PetscCall(PetscStrlcat(names, " ", sizeof(names)));
  }
  SETERRQ(PETSC_COMM_SELF, PETSC_ERR_USER, "Unknown option %s for -%s%s. Available options: %s", given, PetscOptionsObject->prefix ? PetscOptionsObject->prefix : "", opt + 1, names);
}

/* -snes_ssstar_friction_law and -snes_ssstar_<parameter> for every parameter of the registered laws */
static PetscErrorCode SetLawsFromOptions(SNES snes, PetscOptionItems *PetscOptionsObject)
{
  SSStarContact     *ct = &((SNES_SSStar *)snes->data)->contact;
  PetscInt           nlaws, law = ct->law->index, nparams;
  const char *const *names, *const *params;
  PetscBool          set;

  PetscFunctionBegin;
  PetscCall(SSStarLawGetNames(&nlaws, &names));
  PetscCall(RefuseUnknownChoice(PetscOptionsObject, "-snes_ssstar_friction_law", names, nlaws));
  PetscCall(PetscOptionsEList("-snes_ssstar_friction_law", "Friction law of the contact nodes (the table of laws)", "SNESSSStarSetFrictionLaw", names, nlaws, names[law], &law, &set));
  if (set) PetscCall(SNESSSStarSetFrictionLaw(snes, names[law]));
  PetscCall(SSStarLawGetParameterNames(&nparams, &params));
  for (PetscInt p = 0; p < nparams; p++) {
    const SSStarLawParameter *par;
    const char               *owner = NULL;
    char                      option[128], text[256];
    PetscReal                 value[3];
    PetscInt                  n;
    PetscBool                 given;

    PetscCall(SSStarLawGetParameter(params[p], &par));
    for (PetscInt l = 0; l < nlaws && !owner; l++) { /* the first law that has it, for the help text */
      SSStarLaw lw;

      PetscCall(SSStarLawGet(l, &lw));
      if (SSStarLawFindParameter(lw, par->name) >= 0) owner = lw->name;
    }
    PetscCall(PetscSNPrintf(option, sizeof(option), "-snes_ssstar_%s", par->name));
    PetscCall(SSStarContactGetParameter(ct, par->name, &n, value, &given));
    PetscCall(PetscSNPrintf(text, sizeof(text), "The %s of every contact node without its own (law %s%s%s)", par->description, owner, par->kind == SSSTAR_LAW_DIRECTION ? "; x,y,z" : "", given ? "" : "; no default"));
    if (par->kind == SSSTAR_LAW_DIRECTION) PetscCall(PetscOptionsRealArray(option, text, "SNESSSStarSetLawParameter", value, &n, &set));
    else PetscCall(PetscOptionsReal(option, text, "SNESSSStarSetLawParameter", value[0], &value[0], &set));
    if (set) PetscCall(SNESSSStarSetLawParameter(snes, par->name, n, value));
  }
  PetscFunctionReturn(0);
}

/* -snes_ssstar_reduction: a registered reduction or auto */
static PetscErrorCode SetReductionFromOptions(SNES snes, PetscOptionItems *PetscOptionsObject)
{
  SSStarProblem     *pb = &((SNES_SSStar *)snes->data)->problem;
  const char *const *choices;
  PetscInt           n, chosen = 0;
  PetscBool          set;

  PetscFunctionBegin;
  PetscCall(SSStarReductionGetNames(&n, &choices));
  for (PetscInt k = 0; k < n; k++) {
    PetscBool same;

    PetscCall(PetscStrcmp(choices[k], pb->reductionType, &same));
    if (same) chosen = k;
  }
  PetscCall(RefuseUnknownChoice(PetscOptionsObject, "-snes_ssstar_reduction", choices, n));
  PetscCall(PetscOptionsEList("-snes_ssstar_reduction", "Whole-body use: K reduced to the contact dofs (direct, mumps, explicit), or none (the whole body, P never formed), or auto", "SNESSSStarSetReductionType", choices, n, pb->reductionType, &chosen, &set));
  if (set) PetscCall(SNESSSStarSetReductionType(snes, choices[chosen]));
  PetscFunctionReturn(0);
}

/*
   -snes_ssstar_affine: true or false (as a PETSc bool: 1, 0, yes, no; alone: true) declares F, auto (the default) leaves
   it to F (SNESSSStarSetLinearProblem()'s is affine, a program's own is not), which is not known when the options are
   read
*/
static PetscErrorCode SetAffineFromOptions(SNES snes, PetscOptionItems *PetscOptionsObject)
{
  SSStarProblem *pb = &((SNES_SSStar *)snes->data)->problem;
  char           value[16];
  PetscBool      set, isauto, affine = PETSC_TRUE;

  PetscFunctionBegin;
  PetscCall(PetscStrncpy(value, pb->affineSet ? (pb->affineDeclared ? "true" : "false") : "auto", sizeof(value)));
  PetscCall(PetscOptionsString("-snes_ssstar_affine", "Whether F is affine, K u - b: true (the Jacobian once per solve, the Schur reduction may run), false (F at the iterates, the Jacobian as -snes_lag_jacobian says, on the whole body) or auto: true for SNESSSStarSetLinearProblem()'s F, false for a program's own", "SNESSSStarSetAffine", value, value, sizeof(value), &set));
  if (!set) PetscFunctionReturn(0);
  PetscCall(PetscStrcasecmp(value, "auto", &isauto));
  if (isauto) {
    pb->affineSet = PETSC_FALSE;
    PetscFunctionReturn(0);
  }
  if (value[0]) PetscCall(PetscOptionsStringToBool(value, &affine));
  PetscCall(SNESSSStarSetAffine(snes, affine));
  PetscFunctionReturn(0);
}

/* -help: the options of the Newton step's GMRES (-snes_ssstar_newton_ksp_*), which the set-up creates */
static PetscErrorCode HelpNewtonKSP(SNES snes)
{
  KSP         ksp;
  const char *prefix;

  PetscFunctionBegin;
  PetscCall(KSPCreate(PetscObjectComm((PetscObject)snes), &ksp));
  PetscCall(SNESGetOptionsPrefix(snes, &prefix));
  PetscCall(KSPSetOptionsPrefix(ksp, prefix));
  PetscCall(KSPAppendOptionsPrefix(ksp, "snes_ssstar_newton_"));
  PetscCall(KSPSetType(ksp, KSPGMRES));
  PetscCall(KSPSetFromOptions(ksp));
  PetscCall(KSPDestroy(&ksp));
  PetscFunctionReturn(0);
}

PetscErrorCode SNESSetFromOptions_SSStar(SNES snes, PetscOptionItems *PetscOptionsObject)
{
  SNES_SSStar  *ss = (SNES_SSStar *)snes->data;
  PetscReal     value;
  SSStarMethod  method;
  PetscBool     set;
  PetscInt      threads;

  PetscFunctionBegin;
  PetscOptionsHeadBegin(PetscOptionsObject, "SNES ssstar options (semismooth* Newton for contact with friction)");
  PetscCall(SetLawsFromOptions(snes, PetscOptionsObject));
  PetscCall(SetReductionFromOptions(snes, PetscOptionsObject));
  PetscCall(SetAffineFromOptions(snes, PetscOptionsObject));
  PetscCall(PetscOptionsReal("-snes_ssstar_memory_limit", "Memory (GB per rank) the reduction of K may plan for (0: MemAvailable per rank)", "SNESSSStarSetMemoryLimit", ss->problem.memoryLimit, &value, &set));
  if (set) PetscCall(SNESSSStarSetMemoryLimit(snes, value));
  PetscCall(PetscOptionsReal("-snes_ssstar_scaling", "Scaling gamma of the approximation step (0: 1/mean diag P)", "SNESSSStarSetScaling", ss->scaling_user, &value, &set));
  if (set) PetscCall(SNESSSStarSetScaling(snes, value));
  PetscCall(PetscOptionsEnum("-snes_ssstar_method", "The iteration: newton (semismooth*) or fixedpoint (u <- u + z, a first-order baseline)", "SNESSSStarSetMethod", SSStarMethods, (PetscEnum)ss->method, (PetscEnum *)&method, &set));
  if (set) PetscCall(SNESSSStarSetMethod(snes, method));
  PetscCall(PetscOptionsReal("-snes_ssstar_state_tol", "Relative tolerance tau of the contact-state classification", "SNESSSStarSetStateTolerance", ss->state_tol, &value, &set));
  if (set) PetscCall(SNESSSStarSetStateTolerance(snes, value));
  PetscCall(SSStarNewtonGetReuse(ss->newton, &value));
  PetscCall(PetscOptionsReal("-snes_ssstar_lu_reuse", "Solve a Newton step by GMRES on the last LU while at most this fraction of the nodes changed their known rows since it (negative: a fresh LU at every step)", "SNESSSStarSetLUReuse", value, &value, &set));
  if (set) PetscCall(SNESSSStarSetLUReuse(snes, value));
  PetscCall(SSStarNewtonGetPCReuse(ss->newton, &value));
  PetscCall(PetscOptionsReal("-snes_ssstar_pc_reuse", "Whole body: keep the multigrid of an earlier Newton step while at most this fraction of the nodes changed their known rows since it (negative: a new one every step)", "SNESSSStarSetPCReuse", value, &value, &set));
  if (set) PetscCall(SNESSSStarSetPCReuse(snes, value));
  {
    PetscInt dofs;

    PetscCall(SSStarNewtonGetPlainAggregationDofs(ss->newton, &dofs));
    PetscCall(PetscOptionsInt("-snes_ssstar_plain_aggregation_dofs", "Whole body: the multigrid aggregates plainly (W-cycles, products all at once: the memory lever) from this many dofs of K (0: always; negative: only where smoothed does not fit)", "SNESSSStarSetPlainAggregationDofs", dofs, &dofs, &set));
    if (set) PetscCall(SNESSSStarSetPlainAggregationDofs(snes, dofs));
  }
  {
    PetscInt  wLevels;
    PetscBool setW;

    PetscCall(SSStarNewtonGetMGOverCorrection(ss->newton, &value, &wLevels));
    PetscCall(PetscOptionsReal("-snes_ssstar_mg_overcorrection", "Whole body: plain aggregation's W-cycled levels take their coarse corrections times this (1: the Galerkin ones; at most 2)", "SNESSSStarSetMGOverCorrection", value, &value, &set));
    PetscCall(PetscOptionsInt("-snes_ssstar_mg_w_levels", "Whole body: plain aggregation's finest levels that W-cycle, V below (unless -pc_mg_cycle_type)", "SNESSSStarSetMGOverCorrection", wLevels, &wLevels, &setW));
    if (set || setW) PetscCall(SNESSSStarSetMGOverCorrection(snes, value, wLevels));
  }
  PetscCall(PetscOptionsReal("-snes_ssstar_ksp_rtol_max", "Whole body: the loosest relative tolerance of a Newton step's linear solve (it tightens with ||z||/||z_0||)", "SNESSSStarSetKSPRtolMax", ss->etaMax, &value, &set));
  if (set) PetscCall(SNESSSStarSetKSPRtolMax(snes, value));
  PetscCall(PetscOptionsReal("-snes_ssstar_ksp_floor", "Whole body: the likely last step's linear solve goes to this fraction of the stopping rule (docs/derivation.md section 19a)", "SNESSSStarSetKSPFloor", ss->kspFloor, &value, &set));
  if (set) PetscCall(SNESSSStarSetKSPFloor(snes, value));
  PetscCall(PetscOptionsReal("-snes_ssstar_law_rtol", "The tolerance of the law residual of a converged iterate as written (docs/derivation.md section 12); 0: max(-snes_rtol, 1e-8)", "SNESSSStarSetLawTolerance", ss->lawRtol, &value, &set));
  if (set) PetscCall(SNESSSStarSetLawTolerance(snes, value));
  PetscCall(SSStarNewtonGetLUThreads(ss->newton, &threads));
  PetscCall(PetscOptionsInt("-snes_ssstar_lu_threads", "BLAS threads of rank 0 for the LU of the Newton matrix on several ranks (0: the cores it may run on; 1: leave the BLAS)", "SNESSSStarSetLUThreads", threads, &threads, &set));
  if (set) PetscCall(SNESSSStarSetLUThreads(snes, threads));
  {
    PetscBool on = ss->glob.on, setOn, setDamping, setStagnation;
    PetscInt  its;

    PetscCall(PetscOptionsBool("-snes_ssstar_globalization", "Damped steps on ||z|| and remedies (false: the plain iteration)", "SNESSSStarSetGlobalization", on, &on, &setOn));
    PetscCall(PetscOptionsReal("-snes_ssstar_damping_min", "Smallest damping factor of the line search on ||z||", "SNESSSStarSetGlobalization", ss->glob.dampingMin, &value, &setDamping));
    PetscCall(PetscOptionsInt("-snes_ssstar_stagnation_its", "Stop after this many iterations without a smaller ||z||", "SNESSSStarSetGlobalization", ss->glob.stagnationIts, &its, &setStagnation));
    if (setOn || setDamping || setStagnation) PetscCall(SNESSSStarSetGlobalization(snes, on, setDamping ? value : PETSC_DEFAULT, setStagnation ? its : PETSC_DEFAULT));
  }
  PetscCall(SNESMonitorSetFromOptions(snes, "-snes_ssstar_monitor_states", "Monitor the number of contact nodes in each state, and the remedies", "SNESSSStarMonitorStates", SNESSSStarMonitorStates, NULL));
  PetscCall(SNESMonitorSetFromOptions(snes, "-snes_ssstar_monitor_progress", "Monitor the set-up (reduction) and each Newton step: ||z||, nodes that changed state, Krylov iterations, seconds, memory", "SNESSSStarMonitorProgress", SNESSSStarMonitorProgress, NULL));
  PetscOptionsHeadEnd();
  if (PetscOptionsObject->printhelp) PetscCall(HelpNewtonKSP(snes));
  PetscFunctionReturn(0);
}

/* "L 14 M1 55 M2 0 M3+ 15 M3- 0 M4 0" (LS, a Tresca state, only when some node has it) */
PetscErrorCode SNESSSStarFormatStateCounts(const PetscInt counts[], char buf[], size_t len)
{
  size_t used = 0;

  PetscFunctionBegin;
  buf[0] = 0;
  for (PetscInt s = 0; s < SSSTAR_NUM_STATES; s++) {
    if (s == SSSTAR_STATE_LS && !counts[s]) continue;
    PetscCall(PetscSNPrintf(buf + used, len - used, "%s%s %" PetscInt_FMT, s ? " " : "", SSStarStateNames[s], counts[s]));
    PetscCall(PetscStrlen(buf, &used));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SNESView_SSStar(SNES snes, PetscViewer viewer)
{
  SNES_SSStar *ss = (SNES_SSStar *)snes->data;
  PetscBool    isascii;

  PetscFunctionBegin;
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &isascii));
  if (!isascii) PetscFunctionReturn(0);
  PetscCall(SSStarProblemView(&ss->contact, &ss->problem, viewer));
  PetscCall(SSStarNonlinearView(snes, viewer));
  PetscCall(SSStarContactView(&ss->contact, viewer));
  if (ss->method != SSSTAR_METHOD_NEWTON) PetscCall(PetscViewerASCIIPrintf(viewer, "  method: %s (u <- u + z, no Newton step)\n", SSStarMethods[ss->method]));
  if (ss->scaling_user > 0) PetscCall(PetscViewerASCIIPrintf(viewer, "  approximation-step scaling gamma = %g\n", (double)ss->scaling_user));
  else if (ss->method == SSSTAR_METHOD_FIXEDPOINT) PetscCall(PetscViewerASCIIPrintf(viewer, "  approximation-step scaling gamma = 1/(largest contact row sum of K)%s%g\n", ss->scaling > 0 ? " = " : "", ss->scaling > 0 ? (double)ss->scaling : 0.0));
  else PetscCall(PetscViewerASCIIPrintf(viewer, "  approximation-step scaling gamma = 1/mean(diag K_CC)%s%g\n", ss->scaling > 0 ? " = " : "", ss->scaling > 0 ? (double)ss->scaling : 0.0));
  if (snes->ops->converged == SNESConvergedSSStar) {
    PetscCall(PetscViewerASCIIPrintf(viewer, "  stopping rule ||z|| <= max(atol, rtol max(||u||, ||gamma f||)), atol = %g, rtol = %g\n", (double)snes->abstol, (double)snes->rtol));
    PetscCall(PetscViewerASCIIPrintf(viewer, "    and the law residual of the iterate as written <= %g (%s; docs/derivation.md section 12)\n", (double)SNESSSStarLawTolerance(snes), ss->lawRtol > 0 ? "-snes_ssstar_law_rtol" : "max(rtol, 1e-8)"));
  }
  PetscCall(PetscViewerASCIIPrintf(viewer, "  state tolerance tau = %g\n", (double)ss->state_tol));
  PetscCall(SSStarNewtonView(ss->newton, viewer));
  PetscCall(SSStarGlobalizationView(&ss->glob, viewer));
  if (ss->reason != SSSTAR_REASON_ITERATING) {
    char counts[256];

    PetscCall(SNESSSStarFormatStateCounts(ss->counts, counts, sizeof(counts)));
    PetscCall(PetscViewerASCIIPrintf(viewer, "  last solve: %s after %" PetscInt_FMT " iterations, ||z|| = %g, law residual %g; contact states %s\n", SSStarReasons[ss->reason], snes->iter, (double)snes->norm, (double)ss->lawResidual, counts));
    PetscCall(SSStarGlobalizationViewCounts(&ss->glob, viewer));
  }
  PetscFunctionReturn(0);
}

/* With -snes_converged_reason, a line after PETSc's with the finer reason of ssstar */
PetscErrorCode SNESSSStarConvergedReasonView(SNES snes, void *ctx)
{
  SNES_SSStar      *ss = (SNES_SSStar *)snes->data;
  PetscViewer       viewer;
  PetscViewerFormat format;
  PetscBool         flg, isssstar;

  PetscFunctionBegin;
  PetscCall(PetscObjectTypeCompare((PetscObject)snes, SNESSSSTAR, &isssstar));
  if (!isssstar) PetscFunctionReturn(0);
  PetscCall(PetscOptionsGetViewer(PetscObjectComm((PetscObject)snes), ((PetscObject)snes)->options, ((PetscObject)snes)->prefix, "-snes_converged_reason", &viewer, &format, &flg));
  if (!flg) PetscFunctionReturn(0);
  PetscCall(PetscViewerASCIIAddTab(viewer, ((PetscObject)snes)->tablevel));
  PetscCall(PetscViewerASCIIPrintf(viewer, "  ssstar: %s, ||z|| = %g, law residual %g (tolerance %g)\n", SSStarReasons[ss->reason], (double)snes->norm, (double)ss->lawResidual, (double)SNESSSStarLawTolerance(snes)));
  {
    char counts[256];

    PetscCall(SSStarNonlinearFormatCounts(snes, counts, sizeof(counts)));
    PetscCall(PetscViewerASCIIPrintf(viewer, "  ssstar: %s\n", counts));
  }
  if (ss->reason == SSSTAR_REASON_NO_EQUILIBRIUM) {
    const SSStarFloating *fb = &ss->problem.floating;

    PetscCall(PetscViewerASCIIPrintf(viewer, "  ssstar: floating body %" PetscInt_FMT " of %" PetscInt_FMT " slides away along (%.4g, %.4g, %.4g) (its translation (%.4g, %.4g, %.4g)): the friction laws cannot balance %.3g of the load on its rigid-body motions\n", fb->movingBody, fb->nbodies, (double)fb->direction[0], (double)fb->direction[1], (double)fb->direction[2], (double)fb->translation[0], (double)fb->translation[1], (double)fb->translation[2], (double)fb->unbalanced));
  }
  PetscCall(PetscViewerASCIISubtractTab(viewer, ((PetscObject)snes)->tablevel));
  PetscCall(PetscViewerDestroy(&viewer));
  PetscFunctionReturn(0);
}

/*@C
   SNESSSStarMonitorStates - prints, at every iteration, how many contact nodes are in each state of Table 1, with
   the remedies that led to the iterate

   Collective

   Input Parameters:
+  snes  - the SNES
.  its   - the iteration
.  znorm - ||z||
-  vf    - the viewer and its format

   Options Database Key:
.  -snes_ssstar_monitor_states - activates it

   Level: intermediate

.seealso: `SNESMonitorSet()`, `SNESSSStarGetStates()`
@*/
PetscErrorCode SNESSSStarMonitorStates(SNES snes, PetscInt its, PetscReal znorm, PetscViewerAndFormat *vf)
{
  SNES_SSStar *ss     = (SNES_SSStar *)snes->data;
  PetscViewer  viewer = vf->viewer;
  char         counts[256], events[512];
  PetscInt     nlu, nreused, nkrylov;

  PetscFunctionBegin;
  PetscCall(PetscViewerPushFormat(viewer, vf->format));
  PetscCall(PetscViewerASCIIAddTab(viewer, ((PetscObject)snes)->tablevel));
  PetscCall(SNESSSStarFormatStateCounts(ss->counts, counts, sizeof(counts)));
  PetscCall(SSStarNewtonGetCounts(ss->newton, &nlu, &nreused, &nkrylov));
  PetscCall(SSStarGlobalizationFormatEvents(&ss->glob, events, sizeof(events)));
  if (ss->problem.nonlinear) PetscCall(PetscViewerASCIIPrintf(viewer, "%3" PetscInt_FMT " SSStar states %s; Newton steps so far: %" PetscInt_FMT " LU, %" PetscInt_FMT " on an old LU (%" PetscInt_FMT " Krylov its), %" PetscInt_FMT " Jacobians%s\n", its, counts, nlu, nreused, nkrylov, ss->problem.jacobians, events));
  else PetscCall(PetscViewerASCIIPrintf(viewer, "%3" PetscInt_FMT " SSStar states %s; Newton steps so far: %" PetscInt_FMT " LU, %" PetscInt_FMT " on an old LU (%" PetscInt_FMT " Krylov its)%s\n", its, counts, nlu, nreused, nkrylov, events));
  PetscCall(PetscViewerASCIISubtractTab(viewer, ((PetscObject)snes)->tablevel));
  PetscCall(PetscViewerPopFormat(viewer));
  PetscFunctionReturn(0);
}


/*
   What the set-up of this solve did: "K reduced to 3168 contact dofs by the direct Schur complement (chosen by auto)"
   or "the whole body, 12675 dofs, P never formed (reduction none, chosen by auto)" when it built the problem; when it
   kept the last solve's (a load path's next step: only the load changed), "K's reduction to 3168 contact dofs kept, the
   load reduced" or "the whole body's K kept, the free dofs in equilibrium with the new load"
*/
static PetscErrorCode FormatProblem(SNES snes, PetscBool built, char buf[], size_t len)
{
  SNES_SSStar *ss = (SNES_SSStar *)snes->data;
  PetscInt     n;
  const char  *type;
  PetscBool    isauto;

  PetscFunctionBegin;
  PetscCall(MatGetSize(ss->problem.A, &n, NULL));
  PetscCall(SSStarProblemGetReductionType(&ss->problem, &type));
  PetscCall(PetscStrcmp(ss->problem.reductionType, SSSTARREDUCTIONAUTO, &isauto));
  if (!ss->contact.dofs) PetscCall(PetscSNPrintf(buf, len, "the reduced problem, %" PetscInt_FMT " contact dofs", n));
  else if (!built && ss->problem.wholeBody) PetscCall(PetscSNPrintf(buf, len, "the whole body's K (%" PetscInt_FMT " dofs) kept from the last solve, the free dofs in equilibrium with the new load", n));
  else if (!built) PetscCall(PetscSNPrintf(buf, len, "K's reduction to %" PetscInt_FMT " contact dofs (%s) kept from the last solve, the new load reduced", n, type));
  else if (ss->problem.wholeBody) PetscCall(PetscSNPrintf(buf, len, "the whole body, %" PetscInt_FMT " dofs, P never formed (reduction %s%s)", n, type, isauto ? ", chosen by auto" : ""));
  else PetscCall(PetscSNPrintf(buf, len, "K reduced to %" PetscInt_FMT " contact dofs by the %s Schur complement%s", n, type, isauto ? " (chosen by auto)" : ""));
  PetscFunctionReturn(0);
}

/*@C
   SNESSSStarMonitorProgress - a line as each phase of a solve ends: the set-up (the reduction of K, or the whole
   body's), then one per iterate with ||z||, the contact nodes whose state changed since the previous iterate, the
   Krylov iterations and the seconds of the Newton step that led to it, and the memory of the largest rank

   Collective

   Input Parameters:
+  snes  - the SNES
.  its   - the iteration
.  znorm - ||z|| (the value -snes_monitor prints)
-  vf    - the viewer and its format

   Options Database Keys:
+  -snes_ssstar_monitor_progress - activates it
-  -ssstar_progress              - the programs' progress lines (on by default in examples/), this monitor among them

   Notes:
   The lines are flushed as they are printed. The memory is the resident set of the rank with the most
   (SSStarMemoryGetUsage()).

   Level: intermediate

.seealso: `SNESSSStarMonitorProgressAdd()`, `SNESSSStarMonitorStates()`, `SSStarMemoryGetUsage()`
@*/
PetscErrorCode SNESSSStarMonitorProgress(SNES snes, PetscInt its, PetscReal znorm, PetscViewerAndFormat *vf)
{
  SNES_SSStar   *ss     = (SNES_SSStar *)snes->data;
  PetscViewer    viewer = vf->viewer;
  PetscLogDouble now, factorSeconds;
  PetscInt       krylov, factorizations;
  char           problem[256], memory[128], fresh[64] = "";

  PetscFunctionBegin;
  PetscCall(PetscTime(&now));
  PetscCall(SSStarMemoryText(PetscObjectComm((PetscObject)snes), memory, sizeof(memory)));
  PetscCall(SSStarNewtonGetCounts(ss->newton, &factorizations, NULL, &krylov));
  PetscCall(SSStarNewtonGetFactorTime(ss->newton, &factorSeconds));
  if (factorizations > ss->factorizationsLast) PetscCall(PetscSNPrintf(fresh, sizeof(fresh), ", new %s (%.3f s)", ss->problem.wholeBody ? "multigrid" : "LU", factorSeconds - ss->factorSecondsLast));
  PetscCall(PetscViewerPushFormat(viewer, vf->format));
  PetscCall(PetscViewerASCIIAddTab(viewer, ((PetscObject)snes)->tablevel));
  if (its == 0) {
    PetscCall(FormatProblem(snes, (PetscBool)(ss->problem.builds != ss->buildsShown), problem, sizeof(problem)));
    ss->buildsShown = ss->problem.builds;
    PetscCall(PetscViewerASCIIPrintf(viewer, "  set-up: %s%s, %.3f s, %s\n", problem, ss->problem.nonlinear ? (ss->problem.affine ? ", the contact measured at the iterates" : ", a nonlinear residual") : "", now - ss->tStart, memory));
    PetscCall(PetscViewerASCIIPrintf(viewer, "%3" PetscInt_FMT " SSStar ||z|| %14.12e\n", its, (double)znorm));
  } else {
    PetscInt changed = PetscMax(ss->glob.changed, 0);

    PetscCall(PetscViewerASCIIPrintf(viewer, "%3" PetscInt_FMT " SSStar ||z|| %14.12e, %" PetscInt_FMT " node%s changed state; step %.3f s, %" PetscInt_FMT " Krylov its%s%s, %s\n", its, (double)znorm, changed, changed == 1 ? "" : "s", now - ss->tLast, krylov - ss->krylovLast,
                                     ss->problem.jacobians > ss->jacobiansLast ? ", new Jacobian" : "", fresh, memory));
  }
  PetscCall(PetscViewerASCIISubtractTab(viewer, ((PetscObject)snes)->tablevel));
  PetscCall(PetscViewerPopFormat(viewer));
  PetscCall(PetscViewerFlush(viewer));
  ss->tLast              = now;
  ss->krylovLast         = krylov;
  ss->factorizationsLast = factorizations;
  ss->factorSecondsLast  = factorSeconds;
  ss->jacobiansLast      = ss->problem.jacobians;
  PetscFunctionReturn(0);
}

/*@C
   SNESSSStarMonitorProgressAdd - adds SNESSSStarMonitorProgress() on standard output, as -snes_ssstar_monitor_progress
   does (once: a second call, or the option, adds nothing); nothing for a SNES of another type

   Logically Collective

   Input Parameter:
.  snes - the SNES

   Level: intermediate

.seealso: `SNESSSStarMonitorProgress()`, `SSStarSceneSetProgress()`
@*/
PetscErrorCode SNESSSStarMonitorProgressAdd(SNES snes)
{
  PetscViewerAndFormat *vf;
  PetscBool             isssstar;

  PetscFunctionBegin;
  PetscCall(PetscObjectTypeCompare((PetscObject)snes, SNESSSSTAR, &isssstar));
  if (!isssstar) PetscFunctionReturn(0);
  PetscCall(PetscViewerAndFormatCreate(PETSC_VIEWER_STDOUT_(PetscObjectComm((PetscObject)snes)), PETSC_VIEWER_DEFAULT, &vf));
  for (PetscInt i = 0; i < snes->numbermonitors; i++) { /* SNESMonitorSet() keeps neither of two identical monitors' contexts */
    PetscBool identical;

    /* identical: PetscMonitorCompare() has destroyed vf itself (destroying it again crashed -snes_ssstar_monitor_progress) */
    PetscCall(PetscMonitorCompare((PetscErrorCode(*)(void))(void (*)(void))SNESSSStarMonitorProgress, vf, (PetscErrorCode(*)(void **))PetscViewerAndFormatDestroy, (PetscErrorCode(*)(void))(void (*)(void))snes->monitor[i], snes->monitorcontext[i], snes->monitordestroy[i], &identical));
    if (identical) PetscFunctionReturn(0);
  }
  PetscCall(SNESMonitorSet(snes, (PetscErrorCode(*)(SNES, PetscInt, PetscReal, void *))SNESSSStarMonitorProgress, vf, (PetscErrorCode(*)(void **))PetscViewerAndFormatDestroy));
  PetscFunctionReturn(0);
}
