"""ssstar.Scene: the scenes of examples/contact from Python, over the C scene library (src/scene, include/ssstarscene.h):
the same mesh, groups, obstacles, pairs, load paths and output file, solved by the same calls in the same order, with
the steps of a load path handed to the Python program one at a time. help(ssstar.Scene) says how."""
import atexit
import ctypes
import math
import os
import weakref

import numpy as np
from petsc4py import PETSc

from . import _Enum, _Handle, _Int, _Real, _call, _declare, _h, _lib, _petsc4py, release_work, STATE_NAMES

_P = ctypes.POINTER
_C = {name: _declare(name, *args) for name, args in {
    "PetscObjectGetComm": (_Handle, _P(_Handle)),
    "PetscObjectCompose": (_Handle, ctypes.c_char_p, _Handle),
    "PetscObjectDereference": (_Handle,),
    "PetscOptionsCreate": (_P(_Handle),),
    "PetscOptionsUsed": (_Handle, ctypes.c_char_p, _P(_Enum)),
    "PetscOptionsDestroy": (_P(_Handle),),
    "PetscOptionsInsertFile": (_Handle, _Handle, ctypes.c_char_p, _Enum),
    "PetscOptionsLeftGet": (_Handle, _P(_Int), _P(_P(ctypes.c_char_p)), _P(_P(ctypes.c_char_p))),
    "PetscOptionsLeftRestore": (_Handle, _P(_Int), _P(_P(ctypes.c_char_p)), _P(_P(ctypes.c_char_p))),
    "SSStarCheckAllRanks": (_Handle, ctypes.c_int, ctypes.c_char_p),
    "VecGetLocalSize": (_Handle, _P(_Int)),
    "VecGetBlockSize": (_Handle, _P(_Int)),
    "VecGetArrayRead": (_Handle, _P(_P(_Real))),
    "VecRestoreArrayRead": (_Handle, _P(_P(_Real))),
    "VecDestroy": (_P(_Handle),),
    "SSStarCheckOutputFile": (_Handle, ctypes.c_char_p),
    "SSStarSceneCreate": (_Handle, _P(_Handle)),
    "SSStarSceneSetFromOptions": (_Handle,),
    "SSStarSceneHasContact": (_Handle, _P(_Enum)),
    "SSStarSceneHasPath": (_Handle, _P(_Enum)),
    "SSStarSceneCheckOptionsUsedOf": (_Handle, _Int, _P(ctypes.c_char_p), ctypes.c_char_p, _Handle),
    "SSStarSceneSetUp": (_Handle,),
    "SSStarSceneAssemble": (_Handle, _P(_Handle), _P(_Handle)),
    "SSStarSceneGetDM": (_Handle, _P(_Handle)),
    "SSStarSceneGetSizes": (_Handle, _P(_Int), _P(_Int)),
    "SSStarSceneSetSolver": (_Handle, _Handle, _Handle, _Handle),
    "SSStarSceneIsAffine": (_Handle, _P(_Enum)),
    "SNESGetLineSearch": (_Handle, _P(_Handle)),
    "SNESLineSearchSetType": (_Handle, ctypes.c_char_p),
    "SSStarSceneSolveNested": (_Handle, _Handle, _Handle),
    "SSStarSceneView": (_Handle, _Handle),
    "SSStarSceneDestroy": (_P(_Handle),),
    "SSStarSceneGetKnots": (_Handle, _P(_Int), _P(_P(_Real))),
    "SSStarSceneAssembleLoad": (_Handle, _Real, _Handle),
    "SSStarSceneCheckSteps": (_Handle, _Int, _P(_Real)),
    "SSStarSceneGetPathTimes": (_Handle, ctypes.c_char_p, _P(_Int), _P(_P(_Real))),
    "SSStarSceneSolveStep": (_Handle, _Handle, _Handle, _Real, ctypes.c_void_p),
    "SSStarSceneAdvance": (_Handle, _Handle, _Handle, _Real, _Int, ctypes.c_void_p),
    "SSStarSceneAcceptStep": (_Handle, _Handle, _Handle),
    "SSStarSceneSetHistory": (_Handle, ctypes.c_char_p, ctypes.c_char_p),
    "SSStarSceneGetContactGroupCount": (_Handle, _P(_Int)),
    "SSStarSceneGetMotion": (_Handle, _Int, _P(ctypes.c_char_p), _P(_Real), _P(_Real), _P(_Enum)),
    "SSStarSceneOutputBegin": (_Handle, ctypes.c_char_p),
    "SSStarSceneOutputStep": (_Handle, _Handle, _Handle, _Int),
    "SSStarSceneOutputEnd": (_Handle, _Handle, _Handle, _Handle, _Handle),
    "SSStarSceneWriteSolution": (_Handle, _Handle, ctypes.c_char_p, _Handle, _Handle, _Handle),
    "SSStarWriteTable": (_Handle, ctypes.c_char_p, _Int, _P(ctypes.c_char_p), _Int, _P(_P(_Real))),
    "SSStarSceneGetStepColumns": (_Handle, _P(_Int), _P(_Int)),
    "SSStarSceneGetStepColumn": (_Handle, _Int, ctypes.c_size_t, ctypes.c_char_p, _P(_Int), _P(_Enum)),
    "SSStarSceneGetStepRow": (_Handle, _Handle, _Handle, _Int, _P(_Real)),
    "SSStarSceneGetField": (_Handle, _Handle, _Handle, ctypes.c_char_p, _P(_Handle)),
    "SSStarSceneGetEnergies": (_Handle, _P(_Real), _P(_Enum)),
}.items()}
_PETSC_ERR_FILE_OPEN = 65
# PetscFree() is a macro over the function pointer PetscTrFree
_free = ctypes.CFUNCTYPE(ctypes.c_int, ctypes.c_void_p, ctypes.c_int, ctypes.c_char_p, ctypes.c_char_p)


def _petsc_free(pointer):
    free = _free(ctypes.c_void_p.in_dll(_lib, "PetscTrFree").value)
    _call(free, ctypes.cast(pointer, ctypes.c_void_p), 0, b"ssstar.scene", b"scene.py")




class _Step(ctypes.Structure):
    """SSStarStep of include/ssstarscene.h: what the library's stepper did"""
    _fields_ = [("time", _Real), ("cuts", _Int), ("linearizations", _Int), ("iterations", _Int), ("reason", _Enum),
                ("accepted", _Enum), ("reached", _Enum), ("stopped", _Enum), ("no_equilibrium", _Enum), ("retry", _Real),
                ("why", ctypes.c_char_p)]


_REASONS = _P(ctypes.c_char_p).in_dll(_lib, "SNESConvergedReasons")  # indexed by SNESConvergedReason (< 0 too)
_EXTRA = ctypes.CFUNCTYPE(ctypes.c_int, ctypes.c_void_p, ctypes.c_void_p)  # SSStarSceneWriteSolution()'s extra
# examples/contact's own options, which the scene reads as examples/contact does
_DRIVER_OPTIONS = ("steps", "steps_max_cuts", "load_steps", "o")
_DRIVER_HELP = b"-steps -steps_max_cuts -load_steps -o"
# the histories set() changes (SSStarSceneSetHistory())
_HISTORIES = ("traction", "gravity", "obstacle_motion", "obstacle_rotation", "displacement")
# the kinds of contact states, as SSStarSceneGetContactResult() counts them
_KINDS = {"separated": ("L", "LS"), "sliding": ("M1", "M2"), "sticking": ("M3+", "M3-", "M4")}
# the datasets of /steps/<k>/contact: at a state (normal: of the frames the state was linearized at), then of a load
# path after a step was accepted
_STATE_FIELDS = ("displacement", "reaction", "normal", "state", "final_gap", "pressure", "traction", "slip")
_PATH_FIELDS = ("slip_increment", "slip_path", "dissipation")
_SCENE_FIELDS = ("coordinates", "normal", "gap", "area", "group")


def _number(x):
    """A component of a value: a number, or None (a free component of a prescribed displacement) as free"""
    if x is None:
        return "free"
    return repr(float(x)) if isinstance(x, (float, np.floating)) else str(x)


def _text(value):
    """A keyword's value as its option's text: True a flag, False "false", a number, a string, a sequence "a,b,c", a
    history of (t, vector) pairs "t:x,y,z;t:x,y,z" (or an array with rows t, x, y, z)"""
    if value is None or value is True:
        return None
    if value is False:
        return "false"
    if isinstance(value, (str, bytes)):
        return value.decode() if isinstance(value, bytes) else value
    if isinstance(value, (int, float, np.integer, np.floating)):
        return _number(value)
    rows = list(value)
    if rows and all(isinstance(r, (tuple, list, np.ndarray)) for r in rows):  # a history
        knots = []
        for r in rows:
            r = list(r)
            t, v = (r[0], r[1]) if len(r) == 2 else (r[0], r[1:])
            v = [v] if v is None or isinstance(v, (int, float, np.integer, np.floating)) else list(v)
            knots.append("%s:%s" % (_number(t), ",".join(_number(x) for x in v)))
        return ";".join(knots)
    return ",".join(_number(x) for x in rows)


def _time(t):
    """The time of a step, a finite number"""
    t = float(t)
    if not math.isfinite(t):
        raise ValueError("ssstar.Scene: the time %r of a step is not a finite number" % t)
    return t


def _group_option(keyword, group):
    if keyword in ("obstacle_motion", "obstacle_rotation"):
        return "obstacle_%s_%s" % (group, keyword[9:])
    return "%s_%s" % (keyword, group)


def _keyword_options(keywords):
    """(option, text) for each keyword: name=value is -name value; name={G: value} is -name_G value for each group G
    (obstacle_motion={G: ...} is -obstacle_G_motion, obstacle_rotation={G: ...} -obstacle_G_rotation)"""
    for key, value in keywords.items():
        if isinstance(value, dict):
            for group, v in value.items():
                yield _group_option(key, group), _text(v)
        else:
            yield key, _text(value)


def _file_options(comm, path):
    """The options of a PETSc options file (comments and all, as -options_file reads it), in a database of their own"""
    opts, n = _Handle(), _Int()
    names, values = _P(ctypes.c_char_p)(), _P(ctypes.c_char_p)()
    missing = "" if os.access(str(path), os.R_OK) and os.path.isfile(str(path)) else "Unable to open options file %s" % path
    _call(_C["SSStarCheckAllRanks"], comm, _PETSC_ERR_FILE_OPEN, missing.encode())  # rank 0 alone reads it below
    _call(_C["PetscOptionsCreate"], ctypes.byref(opts))
    try:
        _call(_C["PetscOptionsInsertFile"], comm, opts, str(path).encode(), 1)
        _call(_C["PetscOptionsLeftGet"], opts, ctypes.byref(n), ctypes.byref(names), ctypes.byref(values))
        pairs = [(names[i].decode(), None if values[i] is None else values[i].decode()) for i in range(n.value)]
        _call(_C["PetscOptionsLeftRestore"], opts, ctypes.byref(n), ctypes.byref(names), ctypes.byref(values))
    finally:
        _call(_C["PetscOptionsDestroy"], ctypes.byref(opts))
    return pairs


class _Options:
    """A scene's options (its file's, then its keywords'): in petsc4py's database while the scene works, the values
    there before restored after, so that scenes with other options can live side by side"""

    def __init__(self, pairs):
        merged = {}
        for name, value in pairs:  # the last value of a name counts, as in PETSc (names are case-insensitive)
            merged.pop(name.lower(), None)
            merged[name.lower()] = (name, value)
        self.pairs = list(merged.values())
        self._saved = []

    def __enter__(self):
        db, saved = PETSc.Options(), []
        for name, value in self.pairs:
            was_read = _read(name)  # before hasName() reads it
            had = db.hasName(name)
            saved.append((name, had, db.getString(name, None) if had else None, was_read))
            db.delValue(name)  # a new entry, unread until the scene reads it (the check of its options)
            db.setValue(name, value)
        self._saved.append(saved)
        return self

    def __exit__(self, *exc):
        db = PETSc.Options()
        for name, had, old, was_read in reversed(self._saved.pop()):
            db.delValue(name)
            if had:
                db.setValue(name, old if old != "" else None)
                if was_read:
                    db.hasName(name)  # read, as it was
        return False


def _read(name):
    """Whether an option of the database was read (PetscOptionsUsed(): it does not read it)"""
    used = _Enum()
    _call(_C["PetscOptionsUsed"], None, name.encode(), ctypes.byref(used))
    return bool(used.value)


_live = weakref.WeakSet()  # scenes to close before petsc4py finalizes PETSc


@atexit.register
def _close_all():
    for scene in list(_live):
        scene.close()


class Step:
    """A solved step of a scene, as numpy arrays, the same on every rank (rows in the order of the mesh file, as the
    output file has them):

      time, converged, reason (SNESConvergedReason's name), iterations, residual_norm, cuts   what the step was
                     (iterations: of its last linearization, as the file's /steps has them)
      linearizations, total_iterations   with large sliding the solves of the step, each linearized at the solution
                     of the one before until the contact measured there settles, and their iterations in all (a static
                     solve: 1 and iterations); a step whose contact does not settle in sliding_max_it of them is
                     DIVERGED_MAX_IT (and cut, as examples/contact cuts it)
      row            {column: value} of the table of the steps (/steps of the file): time, iterations, reason,
                     residual_norm, cuts, load (3), normal_force, tangential_force (3), area, sliding, sticking,
                     separated, dissipation, with dynamics kinetic_energy, strain_energy, external_work,
                     impact_dissipation, damping_dissipation, energy_error, motion/<G> (3), rotation/<G> (3),
                     groups/<G>/displacement (3), groups/<G>/reaction (3) of every held group (-dirichlet,
                     displacement=: the force its prescription exerts on the body)
      displacement   the displacement of every mesh node, n x 3 (/fields/displacement)
      velocity       with dynamics the velocity of every mesh node, n x 3 (/fields/velocity), else None
      contact        {name: array} per contact node (/contact/<name>): displacement, reaction (the force on the body),
                     normal (of the frames the step was solved in: with large sliding the current configuration's),
                     state (codes into ssstar.STATE_NAMES), final_gap, pressure, traction, slip; on a load path once a
                     step was accepted slip_increment, slip_path, dissipation
      factor         the load factor of a static continuation (-load_steps), else None

    sliding(), sticking(), separated(): boolean masks of the contact nodes by state (as the row counts them)."""

    def __init__(self, row, displacement, contact, factor=None, linearizations=1, total_iterations=None, velocity=None):
        self.row, self.displacement, self.contact, self.factor = row, displacement, contact, factor
        self.velocity = velocity
        self.linearizations = linearizations
        self.total_iterations = row["iterations"] if total_iterations is None else total_iterations
        self.time = row["time"]
        self.iterations = row["iterations"]
        self.reason_code = row["reason"]
        self.reason = _REASONS[row["reason"]].decode()  # SNESConvergedReasons[], as examples/contact prints them
        self.converged = row["reason"] > 0
        self.residual_norm = row["residual_norm"]
        self.cuts = row["cuts"]

    def _mask(self, kind):
        codes = [STATE_NAMES.index(s) for s in _KINDS[kind]]
        return np.isin(self.contact["state"], codes) if "state" in self.contact else np.zeros(0, dtype=bool)

    def sliding(self):
        """The contact nodes that slide (states M1, M2)"""
        return self._mask("sliding")

    def sticking(self):
        """The contact nodes that stick (states M3+, M3-, M4)"""
        return self._mask("sticking")

    def separated(self):
        """The contact nodes out of contact (states L, LS)"""
        return self._mask("separated")

    def __repr__(self):
        return "<ssstar.Step t=%g %s, %d iterations, sliding %d sticking %d separated %d>" % (
            self.time, self.reason, self.iterations, self.row["sliding"], self.row["sticking"], self.row["separated"])


class Scene:
    """A scene of examples/contact (docs/guide/scenes.md, docs/guide/load-paths.md): a body meshed by gmsh, its material, supports,
    loads, contact groups against rigid obstacles or other bodies with a friction law each, solved by the solver ssstar,
    through the same C scene library and calls as examples/contact, so with its answers.

        scene = ssstar.Scene("scenes/shear.opts")                    # an options file of examples/contact
        scene = ssstar.Scene(geo="meshes/block.geo", level=2, E=2e8, nu=0.3, spring={"top": 1000},
                             contact=["bottom"], friction={"bottom": 0.5},
                             traction={"top": [(0, (0, 0, 0)), (1, (0, 0, -10)), (2, (7.5, 0, -10))]})

    Options. The keywords are examples/contact's options, one name per parameter as in C: name=value gives -name value,
    name={G: value} gives -name_G value for each group G (obstacle_motion={G: ...} gives -obstacle_G_motion,
    obstacle_rotation={G: ...} -obstacle_G_rotation), keywords after the file's options. Values: a number, a string, a
    sequence (x, y, z) or ["bottom", "top"] joined by commas (None in it: free), True a flag, False "false", a history a
    sequence of (t, (x, y, z)) pairs (or "t:x,y,z;..."). So geo, mesh, level, mesh_scale, E, nu, material={G: (E, nu)},
    dirichlet=[...], displacement={G: (None, None, -0.01)} (a prescribed displacement, None or "free" a free
    component; a constant or a history), traction={G: ...}, spring={G: k}, gravity, density,
    contact=[...], obstacle={G: "sphere:0,0,10,10" or (px, py, pz, nx, ny, nz)}, obstacle_motion={G: history},
    obstacle_rotation={G: history of (t, (ax, ay, az, angle))}, friction_law={G: "tresca"}, friction={G: phi},
    slip_bound, friction_1, friction_2, friction_direction ({G: ...}),
    contact_pair={G: H}, pair_discretization, steps (times, or N), steps_max_cuts, load_steps, o (the file solve()
    writes), ssstar_progress, dynamics=True with initial_velocity, dynamics_scheme, dynamics_mass, damping, end_time;
    and the solver's: snes_rtol=1e-10, snes_ssstar_reduction="none", snes_monitor=True, ...
    The options live in petsc4py's database while the scene works (the values there before are put back after):
    command-line options (petsc4py.init(sys.argv)) apply to every scene unless its own override them. An option of
    the scene (keyword or file) that nothing reads is refused, naming the nearest known option, as examples/contact
    refuses it; bad values raise ssstar.Error with the library's message.

    Solving.
      solve()               what examples/contact does: the static problem (-load_steps N: at the loads k/N; one
                            solve started by nested iteration, nested_levels, SSStarSceneSolveNested()), or the
                            load path at its steps (steps=..., default the knots of the histories) with its step
                            cutting (steps_max_cuts); returns the last Step; with o=file, writes it
      steps(times=None)     the load path, a step at a time: a generator of the Step of every time of times (any
                            iterable, read lazily; default as solve()), each solved from the step before with
                            incremental friction, halved steps_max_cuts times at most if it does not converge (every
                            accepted sub-step is yielded; a step that fails is yielded last, converged False). Between
                            two steps the loop may change the loads (set()) or stop
      step(t, accept=True)  one step at t from the last accepted one, without cutting; accept=False leaves it tentative:
                            accept() takes it, another step(t) replaces it
      set(traction={G: v}, gravity=v, obstacle_motion={G: v}, displacement={G: v})   new values of the scene's
                            histories (constants or histories, as the keywords; also obstacle_rotation={G: v}; a
                            displacement keeps its free components), for the steps to come
      write(file)           the file examples/contact -o writes (o=file in the options does the same): given before
                            the solve, solve() of a static scene writes its solution there, and the steps of a load
                            path (solve(), steps(), step()) go into it as they are solved, completed by close() or the
                            end of solve(); given after a static solve, that solution
      close()               frees the scene (collective); a with block does it
    Each step of a path is solved as examples/contact solves it: with large sliding (sliding="large", the default)
    solved again from its solution, linearized there, while the contact measured there moves (SSStarSceneCheckStep()),
    at most sliding_max_it times, else DIVERGED_MAX_IT (and cut); with small sliding the motions of a list of times are
    checked before the first solve (SSStarSceneCheckSteps()).

    What it holds: snes (the petsc4py SNES, ssstar or a Cholesky solve without contact), dm, K, b (the load at the
    last knot), u (the displacement of the last solve), iterations (of every solve so far, as examples/contact's summary
    counts them), nodes, contact_size, has_contact, has_path, dynamics (whether the steps are time steps, dynamics=True:
    docs/guide/dynamics.md), knots, vertices (n x 3, file order), contact_nodes
    ({coordinates, normal, gap, area, group} per contact node, file order), group_names, columns (the table of the
    steps: (name, width, integer)), view().

    MPI: every rank makes the same scene (comm=PETSc.COMM_WORLD by default; a petsc4py or mpi4py communicator) and
    gets the same numpy arrays; the scene's calls are collective.
    """

    def __init__(self, options_file=None, comm=None, **options):
        self._scene = _Handle()
        self._closed = True
        comm = PETSc.COMM_WORLD if comm is None else PETSc.Comm(comm)
        self.snes = PETSc.SNES().create(comm)
        self._comm = _Handle()
        _call(_C["PetscObjectGetComm"], _h(self.snes), ctypes.byref(self._comm))
        pairs = _file_options(self._comm, options_file) if options_file is not None else []
        self._options = _Options(pairs + list(_keyword_options(options)))
        self._target = None      # the file of write() before anything was solved (or of o=...)
        self._output = None      # the file a load path is being written to
        self._steps_done = 0     # steps solved (static solves and steps of a path)
        self._accepted = None    # the time of the last accepted step of a load path, None before
        self._pending = None     # a converged step not accepted yet: (time, cuts)
        self._load_steps = None  # the rows of a static continuation, for /load_steps
        self._failed = False
        self._solves = (1, 0)    # the linearizations of the step solved last and their iterations
        self.iterations = 0      # of every solve, as examples/contact's summary counts them
        try:
            with self._options:
                self._make()
        except BaseException:
            self.close()  # every rank raises the library's collective errors: every rank closes
            raise

    def _make(self):
        """examples/contact's set-up: the scene, its solver, the check of the options, the mesh, K, b, the contact"""
        _call(_C["SSStarSceneCreate"], self._comm, ctypes.byref(self._scene))
        self._closed = False
        _live.add(self)
        _call(_C["SSStarSceneSetFromOptions"], self._scene)
        self.has_contact = self._flag("SSStarSceneHasContact")
        self._read_driver_options()
        self.has_path = self._flag("SSStarSceneHasPath") or self._steps_text is not None
        energies, dynamics = (_Real * 8)(), _Enum()  # SSStarEnergies: is the scene one of -dynamics
        _call(_C["SSStarSceneGetEnergies"], self._scene, energies, ctypes.byref(dynamics))
        self.dynamics = bool(dynamics.value)
        if self.has_path and self._load_steps_n is not None:
            raise ValueError("Option -load_steps scales the constant loads of a static problem; a load path is -steps with histories (-traction_<G> t:x,y,z;..., -gravity, -obstacle_<G>_motion): give one of them")
        if self.has_path:
            self._default_times()  # a malformed steps=... refused before the mesh, as examples/contact refuses it
        if self._o is not None:
            _call(_C["SSStarCheckOutputFile"], self._comm, self._o.encode())
            self._target = self._o
        self.affine = self._flag("SSStarSceneIsAffine")  # every body linear (-material_model linear, the default)
        if self.has_contact:
            self.snes.setType("ssstar")
        else:  # as examples/contact: one linear solve, or Newton's method for a hyperelastic body (docs/guide/large-deformation.md)
            self.snes.setType("ksponly" if self.affine else "newtonls")
            ksp = self.snes.getKSP()
            ksp.setType("preonly")
            ksp.getPC().setType("cholesky" if self.affine else "lu")
            ksp.getPC().setFactorSolverType("mumps")
            if not self.affine:
                linesearch = _Handle()  # cp: F is the energy's gradient (petsc4py 3.18 has no SNES.getLineSearch)
                _call(_C["SNESGetLineSearch"], _h(self.snes), ctypes.byref(linesearch))
                _call(_C["SNESLineSearchSetType"], linesearch, b"cp")
        _petsc4py(self.snes.setFromOptions)
        names = [n for n, _ in self._options.pairs if n.lower() not in _DRIVER_OPTIONS]
        _call(_C["SSStarSceneCheckOptionsUsedOf"], self._scene, len(names), (ctypes.c_char_p * max(1, len(names)))(*[n.encode() for n in names]), _DRIVER_HELP, _h(self.snes))
        _call(_C["SSStarSceneSetUp"], self._scene)
        K, b, dm = _Handle(), _Handle(), _Handle()
        _call(_C["SSStarSceneAssemble"], self._scene, ctypes.byref(K), ctypes.byref(b))
        self.K, self.b = self._wrap(K, owned=True), self._wrap(b, owned=True)
        _call(_C["SSStarSceneGetDM"], self._scene, ctypes.byref(dm))
        self.dm = self._wrap(dm)
        self._load = self.b.duplicate()
        # F(u) = K u - load (a hyperelastic scene's f(u) + k u - load, its tangent into K), the load set at each step; the
        # contact (SSStarSceneSetSolver(): SSStarSceneSetProblem(), SSStarSceneSetContact())
        _call(_C["SSStarSceneSetSolver"], self._scene, _h(self.snes), _h(self.K), _h(self._load))
        self.u = self.dm.createGlobalVec()
        self.u.zeroEntries()
        n, p = _Int(), _Int()
        _call(_C["SSStarSceneGetSizes"], self._scene, ctypes.byref(n), ctypes.byref(p))
        self.nodes, self.contact_size = n.value, p.value
        self.columns = self._columns()

    # ---------------------------------------------------------------------------------------------------- plumbing
    def _flag(self, function):
        v = _Enum()
        _call(_C[function], self._scene, ctypes.byref(v))
        return bool(v.value)

    def _read_driver_options(self):
        """examples/contact's own options, from the scene's own options (not the command line's: a script's -o is its
        own): -steps, -steps_max_cuts, -load_steps, -o"""
        given = {name.lower(): value for name, value in self._options.pairs}

        def integer(name, default):
            try:
                return int(given[name]) if name in given else default
            except (TypeError, ValueError):
                raise ValueError("Option -%s %s: expected an integer" % (name, given[name])) from None
        self._steps_text = given.get("steps")
        self._max_cuts = integer("steps_max_cuts", 4)
        self._load_steps_n = integer("load_steps", None)
        self._o = given.get("o")
        if self._max_cuts < 0:
            raise ValueError("-steps_max_cuts %d: must be >= 0" % self._max_cuts)
        if self._load_steps_n is not None and self._load_steps_n < 1:
            raise ValueError("-load_steps %d: needs at least one step" % self._load_steps_n)
        if "steps" in given and not given["steps"] or "o" in given and not given["o"]:
            raise ValueError("Options -steps and -o need a value")

    def _wrap(self, handle, owned=False):
        """A petsc4py object for a C object (composed on the SNES and queried back); owned: drop the C reference"""
        _call(_C["PetscObjectCompose"], _h(self.snes), b"ssstar_scene_object", handle)
        obj = self.snes.query("ssstar_scene_object")
        _call(_C["PetscObjectCompose"], _h(self.snes), b"ssstar_scene_object", None)
        if owned:
            _call(_C["PetscObjectDereference"], handle)
        return obj

    def _check_open(self):
        if self._closed:
            raise RuntimeError("ssstar.Scene: the scene is closed")

    def _columns(self):
        n, size = _Int(), _Int()
        _call(_C["SSStarSceneGetStepColumns"], self._scene, ctypes.byref(n), ctypes.byref(size))
        self._row_size = size.value
        columns = []
        for c in range(n.value):
            name, width, integer = ctypes.create_string_buffer(1024), _Int(), _Enum()
            _call(_C["SSStarSceneGetStepColumn"], self._scene, c, 1024, name, ctypes.byref(width), ctypes.byref(integer))
            columns.append((name.value.decode(), width.value, bool(integer.value)))
        return columns

    def _field(self, name, state=True):
        """A dataset of the output (SSStarSceneGetField()): rows in file order, on every rank"""
        v, n, bs, a = _Handle(), _Int(), _Int(), _P(_Real)()
        _call(_C["SSStarSceneGetField"], self._scene, _h(self.snes) if state else None, _h(self.u) if state else None, name.encode(), ctypes.byref(v))
        try:
            _call(_C["VecGetLocalSize"], v, ctypes.byref(n))
            _call(_C["VecGetBlockSize"], v, ctypes.byref(bs))
            _call(_C["VecGetArrayRead"], v, ctypes.byref(a))
            values = np.array(np.ctypeslib.as_array(a, shape=(n.value,)) if n.value else [], dtype=float)
            _call(_C["VecRestoreArrayRead"], v, ctypes.byref(a))
        finally:
            _call(_C["VecDestroy"], ctypes.byref(v))
        return values.reshape(-1, bs.value) if bs.value > 1 else values

    def _record(self, cuts, factor=None):
        """The Step of the solve just done (the scene's options in effect)"""
        row = (_Real * self._row_size)()
        _call(_C["SSStarSceneGetStepRow"], self._scene, _h(self.snes), _h(self.u), cuts, row)
        values, at = {}, 0
        for name, width, integer in self.columns:
            v = np.array(row[at:at + width])
            values[name] = int(v[0]) if integer else (float(v[0]) if width == 1 else v)
            at += width
        contact = {}
        if self.has_contact:
            for name in _STATE_FIELDS + (_PATH_FIELDS if self._accepted is not None else ()):
                contact[name] = self._field("/contact/" + name)
            contact["state"] = contact["state"].astype(np.int32)
        self._steps_done += 1
        velocity = self._field("/fields/velocity") if self.dynamics else None
        return Step(values, self._field("/fields/displacement"), contact, factor, *self._solves, velocity=velocity)

    def _knots(self):
        n, times = _Int(), _P(_Real)()
        _call(_C["SSStarSceneGetKnots"], self._scene, ctypes.byref(n), ctypes.byref(times))
        knots = [times[i] for i in range(n.value)]
        _petsc_free(times)
        return knots

    @property
    def knots(self):
        """The times of the knots of every history (tractions, gravity, motions), sorted: the default steps"""
        self._check_open()
        return self._knots()

    # ------------------------------------------------------------------------------------------------- static data
    @property
    def vertices(self):
        """The mesh vertices, n x 3, in the mesh file's order (/geometry/vertices)"""
        self._check_open()
        with self._options:
            return self._field("/geometry/vertices", state=False)

    @property
    def contact_nodes(self):
        """{coordinates, normal, gap, area, group} of the contact nodes in the mesh file's order (/contact/...); group
        indexes group_names"""
        self._check_open()
        if not self.has_contact:
            return {}
        with self._options:
            nodes = {name: self._field("/contact/" + name, state=False) for name in _SCENE_FIELDS}
        nodes["group"] = nodes["group"].astype(np.int32)
        return nodes

    @property
    def group_names(self):
        """The contact groups, in the order of -contact"""
        self._check_open()
        n, names = _Int(), []
        _call(_C["SSStarSceneGetContactGroupCount"], self._scene, ctypes.byref(n))
        for g in range(n.value):
            name = ctypes.c_char_p()
            _call(_C["SSStarSceneGetMotion"], self._scene, g, ctypes.byref(name), None, None, None)
            names.append(name.value.decode())
        return names

    def view(self):
        """Prints what the scene simulates (SSStarSceneView(): the body, material, supports, loads, contact groups)"""
        self._check_open()
        _call(_C["SSStarSceneView"], self._scene, _h(PETSc.Viewer.STDOUT(self.snes.getComm())))

    # ------------------------------------------------------------------------------------------------------ solving
    def _solve_static(self, factor, nested=False):
        self.b.copy(self._load)
        self._load.scale(factor)
        if nested:  # -nested_levels: the start from the coarser meshes, as examples/contact's single static solve
            _call(_C["SSStarSceneSolveNested"], self._scene, _h(self.snes), _h(self.u))
        self.snes.solve(None, self.u)  # from the previous solution
        self._count(1, self.snes.getIterationNumber())
        return self._record(0, factor)

    def _count(self, solves, its):
        self._solves = (solves, its)
        self.iterations += its if self.has_contact or not self.affine else 0  # examples/contact counts no iteration of a linear solve

    def _default_times(self):
        """The times of the path (SSStarSceneGetPathTimes(): steps=..., else the knots, else one step at 0)"""
        n, times = _Int(), _P(_Real)()
        text = None if self._steps_text is None else self._steps_text.encode()
        _call(_C["SSStarSceneGetPathTimes"], self._scene, text, ctypes.byref(n), ctypes.byref(times))
        result = [times[i] for i in range(n.value)]
        _petsc_free(times)
        return result

    def _solve_at(self, t):
        """Solves the step at t from the last accepted step (SSStarSceneSolveStep(), examples/contact's stepper): with
        large sliding solved again from its solution, linearized there, while the contact measured there moves; a
        contact that does not settle in sliding_max_it linearizations is DIVERGED_MAX_IT"""
        t = _time(t)
        step = _Step()
        _call(_C["SSStarSceneSolveStep"], self._scene, _h(self.snes), _h(self.u), t, ctypes.byref(step))
        self._count(step.linearizations, step.iterations)
        self._pending = (t, 0) if step.reason > 0 else None

    def _output_step(self, cuts):
        """A step of the path into the file of write() (opened at the first step); cuts None: only opened"""
        if self._target and not self._output:
            _call(_C["SSStarSceneOutputBegin"], self._scene, self._target.encode())
            self._output, self._target = self._target, None
        if self._output and cuts is not None:
            _call(_C["SSStarSceneOutputStep"], self._scene, _h(self.snes), _h(self.u), cuts)

    def _accept(self):
        t, cuts = self._pending
        _call(_C["SSStarSceneAcceptStep"], self._scene, _h(self.u), _h(self.snes.getFunction()[0]))
        self._output_step(cuts)
        self._accepted = t
        self._pending = None
        return self._record(cuts)

    def step(self, t, accept=True):
        """Solves the load path's step at time t from the last accepted step (the loads at t, the obstacles where their
        motions put them at t, incremental friction from there), without step cutting; returns its Step. A converged
        step is accepted (the next starts from it; an open file gets it) unless accept=False: then accept() takes it,
        or another step() replaces it"""
        self._check_open()
        with self._options:
            self._solve_at(t)
            if self._pending and accept:
                return self._accept()
            return self._record(0)

    def accept(self):
        """Accepts the converged step solved last by step(t, accept=False); returns its Step (with the path's fields)"""
        self._check_open()
        if self._pending is None:
            raise RuntimeError("ssstar.Scene.accept(): no converged step waits (step(t, accept=False) first)")
        with self._options:
            return self._accept()

    def _advance(self, target):
        """The accepted (sub-)steps to the time target, halving a step that does not converge (SSStarSceneAdvance(), as
        examples/contact); the step that fails after steps_max_cuts halvings comes last"""
        while True:
            with self._options:
                if self._target and not self._output:  # the file of write(): the library writes each step into it
                    self._output_step(None)
                st = _Step()
                _call(_C["SSStarSceneAdvance"], self._scene, _h(self.snes), _h(self.u), _time(target), self._max_cuts, ctypes.byref(st))
                self._count(st.linearizations, st.iterations)
                if not st.accepted and not st.stopped:
                    continue  # retried at the midpoint
                if st.accepted:
                    self._accepted = st.time
                else:
                    self._failed = True
                step = self._record(st.cuts)
            yield step
            if not step.converged or st.reached:
                return

    def steps(self, times=None):
        """The load path a step at a time: yields the Step of each time of times (default: steps=..., else the knots of
        the histories), every accepted sub-step of a halved step included; stops after a step that fails (yielded with
        converged False). The loop may change the loads between two steps (set()), or stop."""
        self._check_open()
        times = self._default_times() if times is None else times
        if isinstance(times, (list, tuple, np.ndarray)) and self._accepted is None and not self._failed:
            # the motions of every step, before any solve and file (examples/contact's SolvePath()); a lazy iterable
            # has each step checked as it is set (SSStarSceneSetStep())
            ts = [_time(t) for t in times]
            with self._options:
                _call(_C["SSStarSceneCheckSteps"], self._scene, len(ts), (_Real * max(1, len(ts)))(*ts))
        for t in times:
            for step in self._advance(_time(t)):
                yield step
                if not step.converged:
                    return

    def solve(self):
        """What examples/contact does with the scene's options: the static problem (at the loads k/N of -load_steps N,
        each from the one before), or the load path at its steps; the file of write() (or o=...) is written. Returns
        the last Step (converged False if a solve did not converge)"""
        self._check_open()
        last = None
        if self.has_path:
            for last in self.steps():
                pass
            if self._output:
                self._end_output()
            return last
        n = self._load_steps_n or 1
        rows = []
        with self._options:
            for k in range(1, n + 1):
                last = self._solve_static(k / n, nested=n == 1 and self.has_contact)
                rows.append((last.factor, last.row["area"], last.row["normal_force"], last.iterations if self.has_contact else 0))
                if not last.converged:
                    break  # the next steps would start from a point that is no solution
        self._load_steps = rows if n > 1 else None
        if self._target:
            target, self._target = self._target, None
            self.write(target)
        return last

    def set(self, **histories):
        """New values of the scene's histories for the steps to come: traction={G: value}, gravity=value,
        obstacle_motion={G: value}, obstacle_rotation={G: value}, displacement={G: value}, each a constant ((x, y, z);
        (ax, ay, az, angle) for a rotation) or a history as the keywords of Scene() (SSStarSceneSetHistory(): only
        loads, motions and prescribed displacements the scene was made with, a displacement with the same free
        components)"""
        self._check_open()
        for key in histories:
            if key not in _HISTORIES:
                raise ValueError("Scene.set(%s=...): set() changes the histories %s" % (key, ", ".join(_HISTORIES)))
        with self._options:
            for option, text in _keyword_options(histories):
                _call(_C["SSStarSceneSetHistory"], self._scene, ("-" + option).encode(), (text or "").encode())

    # ------------------------------------------------------------------------------------------------------ output
    def write(self, file):
        """Writes the file examples/contact -o writes (HDF5 + XDMF, docs/guide/output.md). Before anything is solved: the file
        of what comes (o=file does the same): solve() of a static scene writes its solution there; the steps of a load
        path (solve(), steps(), step()) go into it as they are solved, and close() (or the end of solve()) completes it.
        After a static solve: its solution (with /load_steps after -load_steps N)"""
        self._check_open()
        file = str(file)
        if self._output or self._accepted is not None or self._failed:
            raise RuntimeError("Scene.write(%s): a load path's file is written as its steps are solved: call write() before its first step" % file)
        with self._options:
            _call(_C["SSStarCheckOutputFile"], self._comm, file.encode())
            if not self._steps_done:
                self._target = file
                return
            extra = None
            if self._load_steps:
                rows = self._load_steps
                columns = [(_Real * len(rows))(*[r[k] for r in rows]) for k in range(4)]
                names = (ctypes.c_char_p * 4)(b"factor", b"area", b"normal_force", b"iterations")
                table = (_P(_Real) * 4)(*[ctypes.cast(c, _P(_Real)) for c in columns])
                extra = _EXTRA(lambda viewer, ctx: _C["SSStarWriteTable"](viewer, b"/load_steps", 4, names, len(rows), table))
            release_work(self.snes)  # the file's memory out of the Newton steps' work, as examples/contact
            _call(_C["SSStarSceneWriteSolution"], self._scene, _h(self.snes), file.encode(), _h(self.u), ctypes.cast(extra, _Handle) if extra else None, None)

    def _end_output(self):
        with self._options:
            release_work(self.snes)
            _call(_C["SSStarSceneOutputEnd"], self._scene, _h(self.snes), _h(self.u), None, None)
        self._output = None

    def close(self):
        """Completes a file being written and frees the scene; collective (every rank closes its scene)"""
        if self._closed:
            return
        try:
            if self._output:
                self._end_output()
        finally:
            self._closed = True
            _live.discard(self)
            _call(_C["SSStarSceneDestroy"], ctypes.byref(self._scene))
            for name in ("u", "_load", "K", "b", "dm"):
                obj = getattr(self, name, None)
                if obj is not None:
                    obj.destroy()
            self.snes.destroy()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False

    def __del__(self):
        if not getattr(self, "_closed", True):
            self.close()

    def __repr__(self):
        if self._closed:
            return "<ssstar.Scene (closed)>"
        return "<ssstar.Scene: %d nodes, %d contact nodes%s>" % (self.nodes, self.contact_size, ", a load path" if self.has_path else "")
