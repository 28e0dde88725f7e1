# Runs squeal on bad input and checks that it fails with a clear message.
#   cmake -DSQUEAL=exe -DINPUT=file.prm -DEXPECT="text" [-DEXISTING=dir]
#         [-DMPIEXEC=mpirun] -P check_error.cmake
# With VALIDATE, squeal --validate must already refuse it.
# With MPIEXEC, squeal runs on 2 ranks: rank 0 alone prints the error, the
# launcher adds its own report, and the test's TIMEOUT catches a rank left
# waiting.
# With EXISTING, the output directory EXISTING is created first with a marker
# file, the run must refuse to replace it, and the marker must survive.
# With SELF_INCLUDE, the input is a file at that path that includes itself;
# with PIPE, a named pipe at that path (opening it would block).
# With INSIDE, the input is INSIDE/case.prm writing into INSIDE with
# Overwrite = true, and it must survive.
if(SELF_INCLUDE)
  file(WRITE "${SELF_INCLUDE}" "include ${SELF_INCLUDE}\n")
  set(INPUT "${SELF_INCLUDE}")
endif()
if(PIPE)
  file(REMOVE "${PIPE}")
  execute_process(COMMAND mkfifo "${PIPE}")
  set(INPUT "${PIPE}")
endif()
if(INSIDE)
  file(REMOVE_RECURSE "${INSIDE}")
  set(INPUT "${INSIDE}/case.prm")
  file(WRITE "${INPUT}" "subsection Output\n  set Directory = ${INSIDE}\n"
    "  set Overwrite = true\nend\n")
endif()
if(EXISTING)
  file(REMOVE_RECURSE "${EXISTING}")
  file(WRITE "${EXISTING}/earlier_result.txt" "keep me\n")
  file(WRITE "${EXISTING}.prm"
    "subsection Output\n  set Directory = ${EXISTING}\nend\n")
  set(INPUT "${EXISTING}.prm")
endif()
if(MPIEXEC)
  execute_process(COMMAND "${MPIEXEC}" -np 2 "${SQUEAL}" "${INPUT}"
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  # keep squeal's own lines, not the launcher's report
  string(REGEX MATCHALL "squeal: [^\n]*" own "${err}")
  string(REPLACE ";" "\n" err "${own}")
elseif(VALIDATE)
  execute_process(COMMAND "${SQUEAL}" --validate "${INPUT}"
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
else()
  execute_process(COMMAND "${SQUEAL}" "${INPUT}"
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
endif()
message("exit code ${rc}; stderr:\n${err}")
if(rc EQUAL 0)
  message(FATAL_ERROR "squeal accepted bad input ${INPUT}")
endif()
string(FIND "${err}" "${EXPECT}" where)
if(where EQUAL -1)
  message(FATAL_ERROR "the error message does not contain '${EXPECT}'")
endif()
string(REGEX MATCHALL "\n" lines "${err}")
list(LENGTH lines n_lines)
if(n_lines GREATER 6 OR err MATCHES "Stacktrace|PETSC ERROR")
  message(FATAL_ERROR "the error is not one clear message")
endif()
if(INSIDE AND NOT EXISTS "${INPUT}")
  message(FATAL_ERROR "the run deleted its own input")
endif()
if(EXISTING AND NOT EXISTS "${EXISTING}/earlier_result.txt")
  message(FATAL_ERROR "an earlier result was destroyed")
endif()
