# Runs COMMAND (a string, split like a shell line) and requires exit code EXPECT_RC and, when given,
# output (stdout and stderr) matching EXPECT_REGEX. Used by the --dry-run and MPI exit-code tests
# (tests/CMakeLists.txt).  cmake -DCOMMAND="..." -DEXPECT_RC=N [-DEXPECT_REGEX=...] -P expect_run.cmake
separate_arguments(cmd UNIX_COMMAND "${COMMAND}")
execute_process(COMMAND ${cmd} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL EXPECT_RC)
  message(FATAL_ERROR "exit ${rc}, expected ${EXPECT_RC}: ${COMMAND}\n${out}\n${err}")
endif()
if(DEFINED EXPECT_REGEX AND NOT "${out}${err}" MATCHES "${EXPECT_REGEX}")
  message(FATAL_ERROR "output does not match '${EXPECT_REGEX}': ${COMMAND}\n${out}\n${err}")
endif()
