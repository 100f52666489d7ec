# A Huygens MPI equality test (ctest label mpi, tests/CMakeLists.txt): `huygens run SCENE` for STEPS
# steps with --fast-plans (FFTW_ESTIMATE) as
#   one:   the one-process solver (today's program),
#   slab1: the slab solver on one rank (HUYGENS_SLAB_SOLVER=1 HUYGENS_MPI_INIT=1, no mpirun),
#   ranks: under MPIEXEC on NP ranks,
# then tests/mpi/compare_npy.py: every dump of `ranks` within relative L2 LIMIT of `slab1` (0: the same
# bits) and within ALSO_LIMIT of `one` (docs/scale.md "Huygens on slabs": with --fast-plans the slab
# transforms give the one-process spectrum bit for bit, and the heights differ by their rounding).
# cmake -DHUYGENS=... -DPYTHON=... -DCHECK=compare_npy.py -DMPIEXEC=... -DNPFLAG=-np -DPREFLAGS="..." -DNP=2
#       -DSCENE=... -DSTEPS=.. -DEVERY=.. -DLIMIT=0 -DALSO_LIMIT=1e-6 -DWORK=dir -P near_dumps.cmake
foreach(v HUYGENS PYTHON CHECK MPIEXEC NPFLAG NP SCENE STEPS EVERY LIMIT ALSO_LIMIT WORK)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "near_dumps.cmake: ${v} not given")
  endif()
endforeach()
separate_arguments(preflags UNIX_COMMAND "${PREFLAGS}")
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
set(args run "${SCENE}" --steps ${STEPS} --dump-every ${EVERY} --fast-plans)
execute_process(COMMAND "${HUYGENS}" ${args} --dump "${WORK}/one" RESULT_VARIABLE rc OUTPUT_VARIABLE out
                ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "one process: exit ${rc}\n${out}\n${err}")
endif()
execute_process(COMMAND "${CMAKE_COMMAND}" -E env HUYGENS_SLAB_SOLVER=1 HUYGENS_MPI_INIT=1 "${HUYGENS}" ${args} --dump "${WORK}/slab1"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "slab solver on one rank: exit ${rc}\n${out}\n${err}")
endif()
execute_process(COMMAND "${MPIEXEC}" ${preflags} ${NPFLAG} ${NP} "${HUYGENS}" ${args} --dump "${WORK}/ranks"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${NP} ranks: exit ${rc}\n${out}\n${err}")
endif()
if(NOT out MATCHES "per rank on ${NP} ranks")
  message(FATAL_ERROR "the run under ${MPIEXEC} did not run on ${NP} ranks:\n${out}\n${err}")
endif()
execute_process(COMMAND "${PYTHON}" "${CHECK}" "${WORK}/ranks" "${WORK}/slab1" --limit ${LIMIT} --also "${WORK}/one"
                        --also-limit ${ALSO_LIMIT}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message(STATUS "${out}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${NP} ranks: dumps differ\n${out}\n${err}")
endif()
file(REMOVE_RECURSE "${WORK}")
