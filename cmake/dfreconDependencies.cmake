# The third-party packages dfrecon's libraries build and link with, and the
# helper targets that wrap them (dfrecon_opencl, dfrecon_openmesh,
# dfrecon_nifti, dfrecon_teem). Included twice: by the top-level
# CMakeLists.txt, and by the installed dfreconConfig.cmake, so that a project
# using the installed package finds exactly what the libraries were built
# against (a static library's private dependencies are its users' link
# dependencies).
#
# In the package (DFRECON_FINDING_PACKAGE set by dfreconConfig.cmake) a missing
# dependency makes find_package(dfrecon) fail with a message naming it; in
# the project it stops configuring.
#
# The helper targets are IMPORTED so that the exported dfrecon:: targets can
# name them without exporting them: each include defines them anew (once).

if(DFRECON_FINDING_PACKAGE)
  include(CMakeFindDependencyMacro)
  macro(_dfrecon_require)
    find_dependency(${ARGV})
  endmacro()
  macro(_dfrecon_missing what)
    set(dfrecon_FOUND FALSE)
    set(dfrecon_NOT_FOUND_MESSAGE "dfrecon needs ${what}, which was not found")
    return()
  endmacro()
else()
  macro(_dfrecon_require)
    find_package(${ARGV} REQUIRED)
  endmacro()
  macro(_dfrecon_missing what)
    message(FATAL_ERROR "dfrecon needs ${what}, which was not found (make setup installs it)")
  endmacro()
endif()

_dfrecon_require(OpenCL 1.2)
_dfrecon_require(OpenMesh)
_dfrecon_require(nlohmann_json 3.10)
_dfrecon_require(Threads)
_dfrecon_require(OpenCV COMPONENTS core imgproc)
# PNG and TIFF files through their own libraries, not OpenCV's imgcodecs
# (io/images/ImageFiles.hpp says why).
_dfrecon_require(PNG)
_dfrecon_require(TIFF)
# Debian ships OpenVDB's find module (not a config file) in its cmake folder.
list(APPEND CMAKE_MODULE_PATH /usr/lib/${CMAKE_LIBRARY_ARCHITECTURE}/cmake/OpenVDB
     /usr/lib/x86_64-linux-gnu/cmake/OpenVDB)
_dfrecon_require(OpenVDB)
# DICOM RT Structure Sets: dcmdata to read, dcmrt's IOD classes to write.
_dfrecon_require(DCMTK CONFIG)
# Header-only: exact planar Boolean operations (geometry/PolygonXor.cpp) and the
# constrained Delaunay triangulation with crossing constraints for caps and
# closings (recon/PlanarRegion.cpp), corefinement (compare/).
set(CGAL_DO_NOT_WARN_ABOUT_CMAKE_BUILD_TYPE TRUE)
_dfrecon_require(CGAL)
_dfrecon_require(ZLIB)

# Label volumes (io/labels/LabelVolume*): NIfTI through niftilib, NRRD through
# teem. Debian 12's CMake files for both are broken (NIFTIConfig.cmake
# expects /usr/lib/libznz.so.3.0.0 and the nifti tools in /usr/bin, and stops
# configuring without them; TeemConfig.cmake imports libteem from the
# package's build tree), so the headers and libraries are found directly.
find_path(NIFTI_INCLUDE_DIR nifti2_io.h PATH_SUFFIXES nifti)
find_library(NIFTI2_LIBRARY nifti2)
find_library(ZNZ_LIBRARY znz)
if(NOT NIFTI_INCLUDE_DIR OR NOT NIFTI2_LIBRARY OR NOT ZNZ_LIBRARY)
  _dfrecon_missing("niftilib (nifti2_io.h, libnifti2, libznz; Debian: libnifti2-dev)")
endif()
find_path(TEEM_INCLUDE_DIR teem/nrrd.h)
find_library(TEEM_LIBRARY teem)
if(NOT TEEM_INCLUDE_DIR OR NOT TEEM_LIBRARY)
  _dfrecon_missing("teem (teem/nrrd.h, libteem; Debian: libteem-dev)")
endif()

if(NOT TARGET dfrecon_nifti)
  add_library(dfrecon_nifti INTERFACE IMPORTED)
  target_include_directories(dfrecon_nifti SYSTEM INTERFACE ${NIFTI_INCLUDE_DIR})
  target_link_libraries(dfrecon_nifti INTERFACE ${NIFTI2_LIBRARY} ${ZNZ_LIBRARY} ZLIB::ZLIB)
  # znzlib.h lays out its file struct by this macro; Debian builds it with zlib.
  target_compile_definitions(dfrecon_nifti INTERFACE HAVE_ZLIB)
endif()
if(NOT TARGET dfrecon_teem)
  add_library(dfrecon_teem INTERFACE IMPORTED)
  target_include_directories(dfrecon_teem SYSTEM INTERFACE ${TEEM_INCLUDE_DIR})
  target_link_libraries(dfrecon_teem INTERFACE ${TEEM_LIBRARY})
endif()

# OpenCL C++ bindings: target and minimum version must match (300 works;
# target 300 with minimum 120 fails to compile). Public: cl/ headers include
# the bindings, so users compile them with the same definitions.
if(NOT TARGET dfrecon_opencl)
  add_library(dfrecon_opencl INTERFACE IMPORTED)
  target_link_libraries(dfrecon_opencl INTERFACE OpenCL::OpenCL)
  target_compile_definitions(dfrecon_opencl INTERFACE CL_HPP_TARGET_OPENCL_VERSION=300
                             CL_HPP_MINIMUM_OPENCL_VERSION=300 CL_HPP_ENABLE_EXCEPTIONS
                             CL_TARGET_OPENCL_VERSION=300)
endif()

# OpenMesh's Debian config exports OpenMeshCore without a usable include dir;
# wrap it so every user gets headers, library and the math define in one go.
if(NOT TARGET dfrecon_openmesh)
  add_library(dfrecon_openmesh INTERFACE IMPORTED)
  target_link_libraries(dfrecon_openmesh INTERFACE OpenMeshCore OpenMeshTools)
  target_include_directories(dfrecon_openmesh SYSTEM INTERFACE /usr/include)
  target_compile_definitions(dfrecon_openmesh INTERFACE _USE_MATH_DEFINES)
  if(NOT DFRECON_FINDING_PACKAGE)
    # OpenMesh's PropertyT::push_back() appends a default-constructed VectorT,
    # which leaves its elements uninitialised on purpose; GCC 12 flags that
    # inlined code in every user. Not our code, so silence just this warning
    # (in our build: a package user's warnings are theirs to choose).
    target_compile_options(dfrecon_openmesh
                           INTERFACE $<$<CXX_COMPILER_ID:GNU>:-Wno-maybe-uninitialized>)
  endif()
endif()
