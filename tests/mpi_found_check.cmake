# Fails where the Open MPI packages that scripts/setup.sh installs are
# installed but CMake did not find MPI: the build then leaves out the
# WAVEPATH_MPI component and the MPI tests (tests/cli/mpi_cli_test.cpp) skip,
# which would otherwise pass unnoticed. A build that leaves MPI out on purpose
# (-DWAVEPATH_MPI=OFF, as scripts/test.sh's sanitizer build) found it first,
# and passes. Usage: cmake -DSOURCE_DIR=... -DMPI_FOUND=... -P mpi_found_check.cmake
execute_process(COMMAND bash "${SOURCE_DIR}/scripts/setup.sh" --list-packages OUTPUT_VARIABLE packages
                RESULT_VARIABLE listed)
if(NOT listed EQUAL 0)
  message(FATAL_ERROR "scripts/setup.sh --list-packages failed (${listed})")
endif()
string(REGEX MATCHALL "[^\n]*mpi[^\n]*" mpi_packages "${packages}")
if(NOT mpi_packages)
  message(FATAL_ERROR "scripts/setup.sh installs no MPI package any more: update this check")
endif()
set(installed "")
foreach(package IN LISTS mpi_packages)
  execute_process(COMMAND dpkg-query -W -f=\${Status} "${package}" OUTPUT_VARIABLE status ERROR_QUIET)
  if(status STREQUAL "install ok installed")
    list(APPEND installed "${package}")
  endif()
endforeach()
string(REPLACE ";" ", " names "${mpi_packages}")
if(NOT installed STREQUAL mpi_packages)
  message(STATUS "${names}: not all installed, so MPI need not be found")
elseif(NOT MPI_FOUND)
  message(FATAL_ERROR "${names} installed, but CMake did not find MPI: the WAVEPATH_MPI component is not "
                      "built and the MPI tests skip (cmake --debug-find-pkg=MPI shows where it looked)")
else()
  message(STATUS "${names} installed and MPI found")
endif()
