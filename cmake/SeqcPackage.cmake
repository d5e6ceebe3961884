# `cpack -G DEB` in the build folder: seqc_<version>_<arch>.deb. Depends comes from the shared
# libraries the binary links (dpkg-shlibdeps, from dpkg-dev); the maintainer scripts reload the
# udev rules so a plugged-in controller gets the new permissions without a reboot.
set(CPACK_PACKAGE_NAME seqc)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_VENDOR "the seqc authors")
set(CPACK_PACKAGE_CONTACT "seqc maintainers <seqc@users.noreply.github.com>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
    "motion sequence compiler and uploader for hobby servo robots")
set(CPACK_PACKAGE_DESCRIPTION
    "seqc compiles a robot's choreography, written in YAML, checks it with compiler-style\n"
    "diagnostics, stores it in a LewanSoul/Hiwonder servo controller's action groups, or\n"
    "streams it live to a Yahboom Raspblock car board. It ships emulators of both devices.")
set(CPACK_RESOURCE_FILE_LICENSE ${PROJECT_SOURCE_DIR}/LICENSE)
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_STRIP_FILES ON)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION electronics)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "udev")
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA
    ${PROJECT_SOURCE_DIR}/scripts/debian/postinst ${PROJECT_SOURCE_DIR}/scripts/debian/postrm)
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION TRUE)
set(CPACK_GENERATOR DEB)
include(CPack)
