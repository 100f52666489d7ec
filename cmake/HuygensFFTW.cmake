# FFTW in single precision as imported targets: PkgConfig::FFTW3F (fftw3f, by pkg-config) and
# FFTW3::fftw3f_omp (its OpenMP threads; Debian ships no pkg-config file for it, so it is found
# as a library). Included by the build (CMakeLists.txt) and by the installed huygensConfig.cmake:
# huygens_core is a static library linking them PRIVATE, so its consumers link them too.
# Sets HUYGENS_FFTW_FOUND; the caller decides whether a missing FFTW is fatal.
find_package(PkgConfig QUIET)
if(PkgConfig_FOUND)
  pkg_check_modules(FFTW3F QUIET IMPORTED_TARGET fftw3f)
endif()
find_library(HUYGENS_FFTW3F_OMP_LIBRARY NAMES fftw3f_omp HINTS ${FFTW3F_LIBRARY_DIRS})
if(TARGET PkgConfig::FFTW3F AND HUYGENS_FFTW3F_OMP_LIBRARY AND NOT TARGET FFTW3::fftw3f_omp)
  add_library(FFTW3::fftw3f_omp UNKNOWN IMPORTED)
  set_target_properties(FFTW3::fftw3f_omp PROPERTIES IMPORTED_LOCATION "${HUYGENS_FFTW3F_OMP_LIBRARY}"
                                                     INTERFACE_LINK_LIBRARIES PkgConfig::FFTW3F)
endif()
if(TARGET PkgConfig::FFTW3F AND TARGET FFTW3::fftw3f_omp)
  set(HUYGENS_FFTW_FOUND TRUE)
else()
  set(HUYGENS_FFTW_FOUND FALSE)
endif()
# FFTW's MPI transforms in single precision (the fftwf_mpi_* API; Debian: libfftw3-mpi-dev) as
# FFTW3::fftw3f_mpi, for the HUYGENS_MPI build (CMakeLists.txt); HUYGENS_FFTW_MPI_FOUND says whether
# it is there. Its users also link MPI::MPI_CXX.
find_library(HUYGENS_FFTW3F_MPI_LIBRARY NAMES fftw3f_mpi HINTS ${FFTW3F_LIBRARY_DIRS})
if(TARGET PkgConfig::FFTW3F AND HUYGENS_FFTW3F_MPI_LIBRARY AND NOT TARGET FFTW3::fftw3f_mpi)
  add_library(FFTW3::fftw3f_mpi UNKNOWN IMPORTED)
  set_target_properties(FFTW3::fftw3f_mpi PROPERTIES IMPORTED_LOCATION "${HUYGENS_FFTW3F_MPI_LIBRARY}"
                                                     INTERFACE_LINK_LIBRARIES PkgConfig::FFTW3F)
endif()
if(TARGET FFTW3::fftw3f_mpi)
  set(HUYGENS_FFTW_MPI_FOUND TRUE)
else()
  set(HUYGENS_FFTW_MPI_FOUND FALSE)
endif()
