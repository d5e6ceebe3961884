#!/usr/bin/env bash
# -DBUILD_TESTING=OFF needs no GoogleTest: configure with find_package(GTest) forbidden and
# check that the tool's target is there and no test target is.
# A missing dependency is named with its Debian package.
# Usage: no_gtest_test.sh SOURCE_DIR
set -euo pipefail
build=$(mktemp -d)
trap 'rm -rf "$build"' EXIT
cmake -S "$1" -B "$build" -G Ninja -DBUILD_TESTING=OFF \
  -DCMAKE_DISABLE_FIND_PACKAGE_GTest=ON >"$build/configure.log" 2>&1 ||
  { cat "$build/configure.log" >&2; exit 1; }
targets=$(ninja -C "$build" -t targets all)
grep -q '^seqc:' <<<"$targets" || { echo "FAIL: no seqc target" >&2; exit 1; }
if grep -q 'seqc_cli_golden_tests' <<<"$targets"; then
  echo "FAIL: tests configured with BUILD_TESTING=OFF" >&2
  exit 1
fi
grep -q 'Release' "$build/CMakeCache.txt" || { echo "FAIL: default build type is not Release" >&2; exit 1; }
echo "configured without GoogleTest; default build type Release"

# A missing library stops the configure step with the Debian package to install.
for pair in yaml-cpp:libyaml-cpp-dev fmt:libfmt-dev CLI11:libcli11-dev; do
  name=${pair%%:*}
  package=${pair#*:}
  missing=$(mktemp -d)
  if cmake -S "$1" -B "$missing" -G Ninja -DBUILD_TESTING=OFF \
    "-DCMAKE_DISABLE_FIND_PACKAGE_$name=ON" >"$missing/log" 2>&1; then
    echo "FAIL: configure succeeded without $name" >&2
    exit 1
  fi
  grep -q "sudo apt-get install $package" "$missing/log" ||
    { echo "FAIL: no hint to install $package:" >&2; cat "$missing/log" >&2; exit 1; }
  rm -rf "$missing"
done
echo "a missing yaml-cpp, fmt or CLI11 names its Debian package"
