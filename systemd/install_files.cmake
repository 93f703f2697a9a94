# Run by `cmake --install` and by cpack (install(SCRIPT) in systemd/CMakeLists.txt), with
# CMAKE_INSTALL_PREFIX the prefix being installed to (/usr for the Debian package), so that the
# unit starts the binpickd that this install puts in place, and the example settings name the model
# it puts in place, whatever the prefix:
#   PREFIX/lib/systemd/system/binpickd.service  ExecStart=PREFIX/bin/binpickd --config /etc/binpick/binpickd.yaml
#   /etc/binpick/binpickd.yaml                   the example settings; an existing file is kept
# The settings live in /etc/binpick for every prefix: it is the unit's ConfigurationDirectory.
# Inputs (set by install(CODE)): BINPICK_SOURCE_DIR, BINPICK_STAGING_DIR, BINPICK_GPIO_GROUP,
# BINPICK_SYSTEMD_UNIT_DIR (relative: below the prefix).
set(BINPICKD_PATH "${CMAKE_INSTALL_PREFIX}/bin/binpickd")
set(BINPICKD_CONFIG "/etc/binpick/binpickd.yaml")
set(unit_dir "${BINPICK_SYSTEMD_UNIT_DIR}")
if(NOT IS_ABSOLUTE "${unit_dir}")
  set(unit_dir "${CMAKE_INSTALL_PREFIX}/${unit_dir}")
endif()
configure_file("${BINPICK_SOURCE_DIR}/systemd/binpickd.service.in" "${BINPICK_STAGING_DIR}/binpickd.service" @ONLY)
file(INSTALL "${BINPICK_STAGING_DIR}/binpickd.service" DESTINATION "${unit_dir}")

# The example names the model this install ships (PREFIX/share/binpick/models).
file(READ "${BINPICK_SOURCE_DIR}/config/binpickd.yaml" settings)
string(REPLACE "/usr/share/binpick/" "${CMAKE_INSTALL_PREFIX}/share/binpick/" settings "${settings}")
file(WRITE "${BINPICK_STAGING_DIR}/binpickd.yaml" "${settings}")
# A settings file already installed is the cell's own: never overwritten (the package marks it a
# conffile, so dpkg asks instead).
if(EXISTS "$ENV{DESTDIR}${BINPICKD_CONFIG}")
  message(STATUS "Keeping: $ENV{DESTDIR}${BINPICKD_CONFIG}")
else()
  file(INSTALL "${BINPICK_STAGING_DIR}/binpickd.yaml" DESTINATION "/etc/binpick")
endif()
