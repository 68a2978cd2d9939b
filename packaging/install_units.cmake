# Runs at install time (install(CODE) in CMakeLists.txt), with the prefix the
# files really go to: the systemd units and their environment file.
set(prefix "${CMAKE_INSTALL_PREFIX}")
if(prefix STREQUAL "/usr")
  set(sysconf "/etc")  # Debian policy: /etc, not /usr/etc
else()
  set(sysconf "${prefix}/etc")
endif()
set(STAIRS_BINDIR "${prefix}/bin")
set(STAIRS_ENVIRONMENT_FILE "${sysconf}/default/stairs")
set(STAIRS_DOC "${prefix}/share/doc/stairs/README.md")
foreach(unit stairs-perception stairs-tracker stairs-openni2)
  set(out "$ENV{DESTDIR}${prefix}/lib/systemd/system/${unit}.service")
  message(STATUS "Installing: ${out}")
  configure_file("${STAIRS_PACKAGING_DIR}/systemd/${unit}.service.in" "${out}" @ONLY)
endforeach()
set(out "$ENV{DESTDIR}${STAIRS_ENVIRONMENT_FILE}")
message(STATUS "Installing: ${out}")
configure_file("${STAIRS_PACKAGING_DIR}/systemd/stairs.default" "${out}" COPYONLY)
