"""pip install ./python: the module ssstar and, beside it, the libssstar.so of this source tree (run make first), so
that the installed module loads the library it was built with; _config.py records both and the version, which the
module checks at import (pyproject.toml has the rest)."""
import os
import re
import shutil

from setuptools import setup
from setuptools.command.build_py import build_py
from setuptools.dist import Distribution

HERE = os.path.dirname(os.path.abspath(__file__))
TOP = os.path.dirname(HERE)
LIBRARY = os.path.join(TOP, "lib", "libssstar.so")


def version():
    """SSSTAR_VERSION_MAJOR/MINOR/SUBMINOR of include/ssstar.h"""
    text = open(os.path.join(TOP, "include", "ssstar.h")).read()
    return ".".join(re.search(r"#define SSSTAR_VERSION_%s (\d+)" % part, text).group(1) for part in ("MAJOR", "MINOR", "SUBMINOR"))


class BuildWithLibrary(build_py):
    def run(self):
        super().run()
        if not os.path.exists(LIBRARY):
            raise SystemExit("ssstar: %s is missing: build the library first (make, at the top of the source tree)" % LIBRARY)
        target = os.path.join(self.build_lib, "ssstar")
        shutil.copy2(LIBRARY, os.path.join(target, "libssstar.so"))
        with open(os.path.join(target, "_config.py"), "w") as f:
            f.write("# written by pip install (python/setup.py): the library installed with the module\n"
                    "import os\n\nLIBRARY = os.path.join(os.path.dirname(os.path.abspath(__file__)), \"libssstar.so\")\n"
                    "VERSION = \"%s\"\n" % version())


class WithLibrary(Distribution):
    def has_ext_modules(self):  # a wheel for this platform: it holds a shared library
        return True


setup(version=version(), cmdclass={"build_py": BuildWithLibrary}, distclass=WithLibrary)
