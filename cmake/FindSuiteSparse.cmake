# SPDX-License-Identifier: MIT
# Debian 12 ships SuiteSparse 5.x without CMake package files: find the headers and the
# libraries of the requested components and make SuiteSparse::<component> targets.
find_path(SuiteSparse_INCLUDE_DIR NAMES SuiteSparse_config.h PATH_SUFFIXES suitesparse)
set(SuiteSparse_INCLUDE_DIRS ${SuiteSparse_INCLUDE_DIR})

set(_ss_header_UMFPACK umfpack.h)
set(_ss_header_CHOLMOD cholmod.h)
set(_ss_header_AMD amd.h)
set(_ss_header_SuiteSparse_config SuiteSparse_config.h)
set(_ss_library_UMFPACK umfpack)
set(_ss_library_CHOLMOD cholmod)
set(_ss_library_AMD amd)
set(_ss_library_SuiteSparse_config suitesparseconfig)

foreach(_component IN LISTS SuiteSparse_FIND_COMPONENTS)
    find_library(SuiteSparse_${_component}_LIBRARY NAMES ${_ss_library_${_component}})
    if(SuiteSparse_INCLUDE_DIR AND SuiteSparse_${_component}_LIBRARY
       AND EXISTS "${SuiteSparse_INCLUDE_DIR}/${_ss_header_${_component}}")
        set(SuiteSparse_${_component}_FOUND TRUE)
        if(NOT TARGET SuiteSparse::${_component})
            add_library(SuiteSparse::${_component} UNKNOWN IMPORTED)
            set_target_properties(SuiteSparse::${_component} PROPERTIES
                IMPORTED_LOCATION "${SuiteSparse_${_component}_LIBRARY}"
                INTERFACE_INCLUDE_DIRECTORIES "${SuiteSparse_INCLUDE_DIR}")
        endif()
    endif()
endforeach()

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(SuiteSparse
    REQUIRED_VARS SuiteSparse_INCLUDE_DIR HANDLE_COMPONENTS)
