# OpenCV's modules as imported targets from the arm64 sysroot
# (cmake/cross/aarch64-linux-gnu.cmake): what find_package(OpenCV COMPONENTS
# ...) gives the engine, for the modules it uses.
set(OpenCV_VERSION 4.6.0)
set(OpenCV_INCLUDE_DIRS ${BOWG_ARM64_SYSROOT}/usr/include/opencv4
                        ${BOWG_ARM64_SYSROOT}/usr/include/aarch64-linux-gnu/opencv4)
set(OpenCV_LIBS)
foreach(module ${OpenCV_FIND_COMPONENTS})
  set(library ${BOWG_ARM64_SYSROOT}/usr/lib/aarch64-linux-gnu/libopencv_${module}.so)
  if(NOT EXISTS ${library})
    set(OpenCV_FOUND FALSE)
    set(OpenCV_NOT_FOUND_MESSAGE "arm64 OpenCV module ${module} not in ${BOWG_ARM64_SYSROOT}: run scripts/arm64_sysroot.sh")
    return()
  endif()
  if(NOT TARGET opencv_${module})
    add_library(opencv_${module} SHARED IMPORTED)
    set_target_properties(opencv_${module} PROPERTIES
      IMPORTED_LOCATION ${library}
      INTERFACE_INCLUDE_DIRECTORIES "${OpenCV_INCLUDE_DIRS}")
  endif()
  list(APPEND OpenCV_LIBS opencv_${module})
endforeach()
set(OpenCV_FOUND TRUE)
