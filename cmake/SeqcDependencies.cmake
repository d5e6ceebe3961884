# Every dependency comes from a Debian 12 package (scripts/install-deps.sh installs them).
find_package(yaml-cpp REQUIRED)   # libyaml-cpp-dev
find_package(CLI11 REQUIRED)      # libcli11-dev
find_package(fmt REQUIRED)        # libfmt-dev
find_package(GTest REQUIRED)      # libgtest-dev
include(GoogleTest)
find_package(Threads REQUIRED)
find_package(PkgConfig REQUIRED)  # pkg-config
pkg_check_modules(HIDAPI REQUIRED IMPORTED_TARGET hidapi-hidraw)  # libhidapi-dev
