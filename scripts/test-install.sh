#!/usr/bin/env bash
# The CMake package as another project sees it: installs the build tree (HUYGENS_BUILD_DIR,
# default build/) into a temporary prefix, checks that no installed text file names the source
# tree, then configures, builds and runs tests/install (find_package(huygens REQUIRED), a few
# steps of a scene, the height checked) against that prefix alone. Exit 1 on any failure.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${HUYGENS_BUILD_DIR:-$root/build}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() {
  echo "test-install: FAILED: $*" >&2
  exit 1
}

echo "== install test: cmake --install $build --prefix <tmp>/prefix"
cmake --install "$build" --prefix "$tmp/prefix" >"$tmp/install.log" 2>&1 || {
  cat "$tmp/install.log" >&2
  fail "cmake --install"
}
[ -f "$tmp/prefix/lib/cmake/huygens/huygensConfig.cmake" ] || fail "no huygensConfig.cmake installed"
if leaks=$(grep -rlF "$root" "$tmp/prefix/include" "$tmp/prefix/lib/cmake"); then
  fail "installed files name the source tree ($root): $leaks"
fi

echo "== install test: the outside project tests/install against the installed package"
cmake -S "$root/tests/install" -B "$tmp/build" -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$tmp/prefix" \
  >"$tmp/configure.log" 2>&1 || {
  cat "$tmp/configure.log" >&2
  fail "configuring tests/install with find_package(huygens)"
}
cmake --build "$tmp/build" -j "$(nproc)" >"$tmp/build.log" 2>&1 || {
  cat "$tmp/build.log" >&2
  fail "building tests/install"
}
"$tmp/build/huygens-install-test" || fail "tests/install's program"
# the Python package (HUYGENS_PYTHON): installed under the prefix where the interpreter it was built
# for looks (lib/python3.X/dist-packages or site-packages), importable from there alone
python=$(sed -n 's/^Python3_EXECUTABLE:FILEPATH=//p' "$build/CMakeCache.txt")
if grep -q '^HUYGENS_PYTHON:BOOL=ON' "$build/CMakeCache.txt"; then
  echo "== install test: import huygens from the installed package ($python)"
  init=$(find "$tmp/prefix" -path '*/huygens/__init__.py' | head -n 1)
  [ -n "$init" ] || fail "no huygens/__init__.py installed"
  (cd "$tmp" && PYTHONPATH=$(dirname "$(dirname "$init")") "$python" -c "
import huygens
assert huygens.__file__.startswith('$tmp/prefix'), huygens.__file__
s = huygens.Simulation('ring', fast_plans=True)
s.run(until_s=0.1)
print('installed huygens:', huygens.__file__, s.field('eta').shape)
") || fail "importing the installed Python package"
fi
echo "== install test: passed"
