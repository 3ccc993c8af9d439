# CHOLMOD (SuiteSparse) ships neither a CMake config nor a .pc file on Debian 12:
# find the header and the libraries and wrap them in an imported target.
find_path(CHOLMOD_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse)
find_library(CHOLMOD_LIBRARY cholmod)
find_library(SUITESPARSECONFIG_LIBRARY suitesparseconfig)
find_library(SPQR_LIBRARY spqr)
# AMD, which CHOLMOD itself calls: the subdomain factors order with it directly
# (solver/supernodal_factorization.cpp).
find_library(AMD_LIBRARY amd)
# CAMD (constrained AMD, which CHOLMOD calls too): the one factor with the boundary last
# (solver/boundary_last.cpp).
find_library(CAMD_LIBRARY camd)

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(CHOLMOD
  REQUIRED_VARS CHOLMOD_LIBRARY AMD_LIBRARY CAMD_LIBRARY SUITESPARSECONFIG_LIBRARY CHOLMOD_INCLUDE_DIR)

if(CHOLMOD_FOUND AND NOT TARGET SuiteSparse::CHOLMOD)
  add_library(SuiteSparse::CHOLMOD INTERFACE IMPORTED)
  set_target_properties(SuiteSparse::CHOLMOD PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${CHOLMOD_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES "${CHOLMOD_LIBRARY};${AMD_LIBRARY};${CAMD_LIBRARY};${SUITESPARSECONFIG_LIBRARY}")
endif()
# SuiteSparseQR: the rank-revealing sparse QR of the frame mechanism check.
if(CHOLMOD_FOUND AND SPQR_LIBRARY AND NOT TARGET SuiteSparse::SPQR)
  add_library(SuiteSparse::SPQR INTERFACE IMPORTED)
  set_target_properties(SuiteSparse::SPQR PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${CHOLMOD_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES "${SPQR_LIBRARY};${CHOLMOD_LIBRARY};${SUITESPARSECONFIG_LIBRARY}")
endif()
mark_as_advanced(CHOLMOD_INCLUDE_DIR CHOLMOD_LIBRARY AMD_LIBRARY CAMD_LIBRARY SUITESPARSECONFIG_LIBRARY SPQR_LIBRARY)
