# Fails when a file of src/, kernels/shared or kernels/interface includes a
# path that climbs out of its directory ("../"): such an include passes over
# the include roots that keep the layering (src/CMakeLists.txt).
file(GLOB_RECURSE files "${SOURCE_DIR}/src/*.h" "${SOURCE_DIR}/src/*.cpp" "${SOURCE_DIR}/kernels/shared/*.h"
     "${SOURCE_DIR}/kernels/interface/*.h")
set(found "")
foreach(file ${files})
  file(STRINGS "${file}" lines REGEX "^[ \t]*#[ \t]*include[ \t]*[\"<][^\">]*\\.\\./")
  foreach(line ${lines})
    file(RELATIVE_PATH name "${SOURCE_DIR}" "${file}")
    string(APPEND found "\n  ${name}: ${line}")
  endforeach()
endforeach()
if(found)
  message(FATAL_ERROR "includes by a relative path, not by room:${found}")
endif()
