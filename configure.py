#!/usr/bin/env python3
"""Configure ssstar: find PETSc (PETSC_DIR/PETSC_ARCH, else Debian's /usr/lib/petsc) with MUMPS, HDF5 and
ScaLAPACK, find gmsh and its C API, MUMPS's C API and METIS, and write config/ssstar.mk for the Makefile.
The direct reduction calls MUMPS itself: it links the MUMPS PETSc links (MUMPS_LIB of PETSc's petscvariables).

Run as root, it installs the missing Debian packages; otherwise it prints the apt-get line to run.
"""
import ctypes.util
import os
import shutil
import subprocess
import sys

PACKAGES = {
    # Debian package: test that it is there
    "petsc-dev": lambda: os.path.exists("/usr/lib/petsc/include/petscconf.h"),
    "gmsh": lambda: shutil.which("gmsh") is not None,
    "libgmsh-dev": lambda: os.path.exists("/usr/include/gmshc.h"),
    "libopenblas0-pthread": lambda: os.path.isdir("/usr/lib/x86_64-linux-gnu/openblas-pthread"),
    "python3-numpy": lambda: debian_python_has("numpy"),
    "python3-matplotlib": lambda: debian_python_has("matplotlib"),
    "python3-h5py": lambda: debian_python_has("h5py"),
    "pkg-config": lambda: shutil.which("pkg-config") is not None,
    "python3-petsc4py": lambda: debian_python_has("petsc4py"),
    "python3-mpi4py": lambda: debian_python_has("mpi4py"),  # examples/scene.py sweep --split: a scene per rank
    "python3-venv": lambda: debian_python_has("ensurepip"),  # pip install ./python into a venv (tests/suite_pyscene.py)
    "python3-setuptools": lambda: debian_python_has("setuptools"),  # ... without build isolation (no index needed)
    "python3-wheel": lambda: debian_python_has("wheel"),
    "libmumps-dev": lambda: os.path.exists("/usr/include/dmumps_c.h"),  # MUMPS's C API (the direct reduction)
    "libmetis-dev": lambda: os.path.exists("/usr/include/metis.h"),  # METIS_NodeND (its ordering)
    "valgrind": lambda: shutil.which("valgrind") is not None,  # the memory check of the tests (tests/suite_hard.py)
}
DEBIAN_PYTHON = "/usr/bin/python3"
REQUIRED_PETSC_PACKAGES = ["MUMPS", "HDF5", "SCALAPACK"]


def debian_python_has(module):
    return os.path.exists(DEBIAN_PYTHON) and subprocess.call(
        [DEBIAN_PYTHON, "-c", "import " + module], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL) == 0


def install_missing():
    missing = [pkg for pkg, present in PACKAGES.items() if not present()]
    if not missing:
        return
    cmd = ["apt-get", "install", "-y", "--no-install-recommends"] + missing
    if os.geteuid() != 0:
        sys.exit("configure: missing Debian packages; run as root:\n  apt-get update && " + " ".join(cmd))
    print("configure: installing " + " ".join(missing), flush=True)
    env = dict(os.environ, DEBIAN_FRONTEND="noninteractive")
    subprocess.check_call(["apt-get", "update", "-qq"], env=env)
    subprocess.check_call(cmd + ["-qq"], env=env)
    still = [pkg for pkg, present in PACKAGES.items() if not present()]
    if still:
        sys.exit("configure: still missing after apt-get: " + " ".join(still))


def has_xdmf_reader(python):
    return python and subprocess.call([python, "-c", "import vtk; vtk.vtkXdmfReader"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL) == 0


def install_vtk():
    """VTK with the XDMF reader ParaView uses, for the test that reads the XDMF of a load path (tests/xdmf_check.py):
    Debian's python3-vtk9 has none, PyPI's vtk has; pip installs it for the first python3 on the PATH"""
    candidates = [shutil.which("python3"), DEBIAN_PYTHON]
    if any(has_xdmf_reader(py) for py in candidates):
        return
    python = candidates[0] or DEBIAN_PYTHON
    cmd = [python, "-m", "pip", "install", "vtk"] + (["--break-system-packages"] if python == DEBIAN_PYTHON else [])
    if os.geteuid() != 0:
        print("configure: no Python with VTK's vtkXdmfReader (a test reads the XDMF files with it); run:\n  " + " ".join(cmd))
        return
    print("configure: installing VTK for %s (pip install vtk)" % python, flush=True)
    if subprocess.call(cmd + ["-q"]) != 0 or not has_xdmf_reader(python):
        print("configure: pip could not install vtk; the test of the XDMF files of load paths will fail")


def find_petsc():
    petsc_dir = os.environ.get("PETSC_DIR", "/usr/lib/petsc")
    petsc_arch = os.environ.get("PETSC_ARCH", "")
    conf = os.path.join(petsc_dir, petsc_arch, "include", "petscconf.h")
    if not os.path.exists(conf):
        conf = os.path.join(petsc_dir, "include", "petscconf.h")
    if not os.path.exists(conf):
        sys.exit("configure: no PETSc at PETSC_DIR=%s PETSC_ARCH=%s (petscconf.h not found)" % (petsc_dir, petsc_arch))
    text = open(conf).read()
    missing = [p for p in REQUIRED_PETSC_PACKAGES if "#define PETSC_HAVE_%s 1" % p not in text]
    if missing:
        sys.exit("configure: PETSc at %s lacks %s; ssstar needs MUMPS, HDF5 and ScaLAPACK" % (petsc_dir, ", ".join(missing)))
    version = {}
    verh = os.path.join(os.path.dirname(conf), "petscversion.h")
    if not os.path.exists(verh):
        verh = os.path.join(petsc_dir, "include", "petscversion.h")
    for line in open(verh):
        parts = line.split()
        if len(parts) == 3 and parts[0] == "#define" and parts[1] in ("PETSC_VERSION_MAJOR", "PETSC_VERSION_MINOR", "PETSC_VERSION_SUBMINOR"):
            version[parts[1]] = int(parts[2])
    variables = os.path.join(petsc_dir, petsc_arch, "lib", "petsc", "conf", "petscvariables")
    if not os.path.exists(variables):
        variables = os.path.join(petsc_dir, "lib", "petsc", "conf", "petscvariables")
    if not any(line.startswith("MUMPS_LIB =") for line in open(variables)):
        sys.exit("configure: %s names no MUMPS_LIB: the direct reduction links the MUMPS PETSc links" % variables)
    ver = (version["PETSC_VERSION_MAJOR"], version["PETSC_VERSION_MINOR"])
    if ver < (3, 18):
        sys.exit("configure: PETSc %d.%d is too old; ssstar needs 3.18 or newer" % ver)
    return petsc_dir, petsc_arch, "%d.%d.%d" % (ver + (version["PETSC_VERSION_SUBMINOR"],))


def main():
    install_missing()
    install_vtk()
    petsc_dir, petsc_arch, version = find_petsc()
    gmsh = shutil.which("gmsh")
    os.makedirs("config", exist_ok=True)
    with open("config/ssstar.mk", "w") as f:
        f.write("# written by configure.py\n")
        f.write("PETSC_DIR := %s\nPETSC_ARCH := %s\n" % (petsc_dir, petsc_arch))
        # libgmsh is opened when a run needs it (src/sys/gmshlib.c), by the name the dynamic linker knows it by
        f.write("GMSH := %s\nGMSH_SONAME := %s\n" % (gmsh, ctypes.util.find_library("gmsh") or "libgmsh.so"))
        f.write("METIS_LIB := -lmetis\n")
        f.write("PYTHON := %s\n" % DEBIAN_PYTHON)
    print("configure: PETSc %s at %s%s (MUMPS, HDF5, ScaLAPACK), gmsh %s; wrote config/ssstar.mk"
          % (version, petsc_dir, ("/" + petsc_arch) if petsc_arch else "", gmsh))


if __name__ == "__main__":
    main()
