"""The package's version: luxtrace's own, whose number is written in one place only, the
project() line of the repository's CMakeLists.txt.

cmake --install fills it in below (configure_file); pip's build reads it from
CMakeLists.txt beside python/ (pyproject.toml); a package imported from the repository
reads it there too, and one installed by pip finds it in its installed metadata."""
import re
from importlib import metadata
from pathlib import Path

_CONFIGURED = "@PROJECT_VERSION@"


def _version():
    if not _CONFIGURED.startswith("@"):
        return _CONFIGURED
    cmake_lists = Path(__file__).resolve().parents[2] / "CMakeLists.txt"
    if cmake_lists.is_file():
        found = re.search(r"project\(\s*luxtrace\s+VERSION\s+([0-9.]+)", cmake_lists.read_text())
        if found:
            return found.group(1)
    try:
        return metadata.version("luxtrace")
    except metadata.PackageNotFoundError:
        return "unknown"


__version__ = _version()
