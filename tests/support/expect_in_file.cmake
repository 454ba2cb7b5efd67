# cmake -DFILE=path -DPATTERN=regex -P expect_in_file.cmake: fails unless FILE exists and
# matches PATTERN.
if(NOT EXISTS "${FILE}")
  message(FATAL_ERROR "missing: ${FILE}")
endif()
file(READ "${FILE}" content)
if(NOT content MATCHES "${PATTERN}")
  message(FATAL_ERROR "${FILE} does not match ${PATTERN}")
endif()
