#!/usr/bin/env bash
# cmake --install into a fresh prefix, then the installed luxtrace runs the installed
# example with a small photon budget from an unrelated directory, and the installed tree
# has the jobs, the documentation (with README links that resolve) and the Python package.
#   install_test.sh CMAKE BUILD_DIR WORKDIR
set -euo pipefail
cmake_cmd=$1
build=$2
work=$3
src=$(cd "$(dirname "$0")/.." && pwd)
prefix=$work/prefix
rm -rf "$work"
mkdir -p "$work/elsewhere"
"$cmake_cmd" --install "$build" --prefix "$prefix" > "$work/install.log"
fail() { echo "install_test: $*" >&2; exit 1; }

lux=$prefix/bin/luxtrace
[ -x "$lux" ] || fail "no executable $lux"
"$lux" --version | grep -q '^luxtrace [0-9]' || fail "--version"
for f in share/luxtrace/README.md share/luxtrace/docs/REFERENCE.md share/luxtrace/docs/SPEC.md \
         share/luxtrace/examples/office/office.toml share/luxtrace/examples/office/desk.obj \
         share/luxtrace/jobs/one_node.sbatch share/luxtrace/jobs/README.md; do
    [ -f "$prefix/$f" ] || fail "missing $f"
done
# The installed documentation stands alone: its relative links resolve inside the prefix,
# but for those to developer notes under tests/, which are not installed.
/usr/bin/python3 "$src/scripts/check_links.py" --missing-ok tests/ "$prefix/share/luxtrace" ||
    fail "broken links in the installed documentation"

# The example, run where nothing of the source tree is: paths inside it are relative to it.
cd "$work/elsewhere"
scene=$prefix/share/luxtrace/examples/office/office.toml
"$lux" check "$scene" > check.log || fail "check of the installed example: $(tail -3 check.log)"
"$lux" run "$scene" --photons 20k --threads 2 --quiet --output office.h5 > run.log 2>&1 ||
    fail "run of the installed example: $(tail -3 run.log)"
[ -f office.h5 ] && [ -f office.xdmf ] || fail "no result file"
"$lux" info office.h5 > info.log || fail "info"
grep -q 20000 info.log || fail "info does not report the 20000 photons: $(cat info.log)"

if [ -d "$src/python/luxtrace" ]; then
    PYTHONPATH=$prefix/share/luxtrace/python /usr/bin/python3 -c "import luxtrace" || fail "import luxtrace"
    # One version for both: the package's is the binary's, less the commit the binary names.
    py_version=$(PYTHONPATH=$prefix/share/luxtrace/python /usr/bin/python3 -c "import luxtrace; print(luxtrace.__version__)")
    bin_version=$("$lux" --version | awk '{print $2}')
    [ "$py_version" = "${bin_version%%+*}" ] ||
        fail "the installed Python package is version $py_version, luxtrace --version says $bin_version"
fi
cd /
rm -rf "$work"
echo "install_test: installed tree runs the example"
