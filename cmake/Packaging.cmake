# The Debian package of the cell PC (`bash scripts/package.sh`, or `cpack` in the build tree):
# binpick_<version>_<arch>.deb with /usr/bin/binpick and binpickd, their image codecs in
# /usr/lib/binpick, the unit in /usr/lib/systemd/system, /etc/binpick/binpickd.yaml as a conffile,
# the docs and example settings in /usr/share/doc/binpick, the example recipe's model in
# /usr/share/binpick/models. Depends come from dpkg-shlibdeps; the maintainer scripts are in
# packaging/debian/ (docs/install.md).
set(BINPICK_PACKAGE_MAINTAINER "binpick developers" CACHE STRING "The Debian package's Maintainer field")

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME binpick)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "${PROJECT_DESCRIPTION}")
set(CPACK_PACKAGE_DESCRIPTION
    "binpick looks into a bin of randomly piled parts with a structured-light camera (GigE Vision camera, \
projector triggered over GPIO), finds every part's 6-DoF pose and sends pick poses to the robot controller \
over TCP. binpickd is the cell service (systemd); binpick is the command line for capture, reconstruction, \
detection, calibration and the virtual cell.")
set(CPACK_RESOURCE_FILE_LICENSE ${PROJECT_SOURCE_DIR}/LICENSE)
set(CPACK_STRIP_FILES ON)
# The package installs to /usr whatever this build's prefix: staged with DESTDIR so that the
# install scripts see /usr as their prefix, and /etc stays /etc.
set(CPACK_SET_DESTDIR ON)
set(CPACK_INSTALL_PREFIX /usr)
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)

set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)  # binpick_0.1.0_amd64.deb
set(CPACK_DEBIAN_PACKAGE_MAINTAINER "${BINPICK_PACKAGE_MAINTAINER}")
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# adduser for the gpio group, udev for the rule that gives it /dev/gpiochip*.
set(CPACK_DEBIAN_PACKAGE_DEPENDS "adduser, udev")
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "systemd")
set(packaging_dir ${PROJECT_SOURCE_DIR}/packaging/debian)
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA
    ${packaging_dir}/postinst ${packaging_dir}/prerm ${packaging_dir}/postrm ${packaging_dir}/conffiles)
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)
set(CPACK_OUTPUT_FILE_PREFIX dist)  # below the directory cpack runs in
# cpack installs what is built: it does not build the tests first (scripts/package.sh builds the
# installed targets).
set(CMAKE_SKIP_INSTALL_ALL_DEPENDENCY ON)

include(CPack)
