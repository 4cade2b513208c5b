# Fills keyturn's OpenNI2 folder (cmake -DDIR=FOLDER -DOPENNI2=REAL_LIBOPENNI2 -P link_drivers.cmake,
# or included by the install step with both set): FOLDER/libOpenNI2.so.0 links to the system's
# libOpenNI2, and FOLDER/OpenNI2/Drivers/ links to every driver of the system's drivers folder
# (OpenNI2/Drivers beside the real libOpenNI2: PrimeSense's libPS1080, libPSLink, libOniFile, …)
# beside the simulated camera's driver, so a program loading this libOpenNI2 sees both kinds.
# The links point at the system's absolute paths (the folder stays movable); a link whose driver
# has gone from the system is removed. GUARDED names the system drivers the folder holds keyturn's
# guard of instead of a link (libOniFile.so.0: libKeyturnOniFile.so.0, oni_file_guard.cpp); a link
# to one of them, left by an earlier build, is removed.
if(NOT DIR OR NOT OPENNI2)
  message(FATAL_ERROR "link_drivers.cmake: set DIR (keyturn's OpenNI2 folder) and OPENNI2 (the real libOpenNI2)")
endif()
set(_drivers "${DIR}/OpenNI2/Drivers")
file(MAKE_DIRECTORY "${_drivers}")
file(CREATE_LINK "${OPENNI2}" "${DIR}/libOpenNI2.so.0" SYMBOLIC)
get_filename_component(_system_dir "${OPENNI2}" DIRECTORY)
file(GLOB _system_drivers "${_system_dir}/OpenNI2/Drivers/lib*.so.0")
foreach(_driver IN LISTS _system_drivers)
  get_filename_component(_name "${_driver}" NAME)
  list(FIND GUARDED "${_name}" _guarded)  # (no IN_LIST: this runs with -P, where policies are old)
  if(_guarded GREATER -1)
    file(REMOVE "${_drivers}/${_name}")
  elseif(NOT _name MATCHES "^libKeyturn(SimOpenNI2|OniFile)\\.so\\.0$")  # copies in the system's folder (docs/camera.md)
    file(CREATE_LINK "${_driver}" "${_drivers}/${_name}" SYMBOLIC)
  endif()
endforeach()
file(GLOB _present "${_drivers}/*")
foreach(_file IN LISTS _present)
  if(IS_SYMLINK "${_file}" AND NOT EXISTS "${_file}")
    file(REMOVE "${_file}")
  endif()
endforeach()
