# How each dependency is found. Everything comes from Debian packages; nothing is vendored.
# (See README "Set-up" for the apt-get line.)
find_package(glm REQUIRED)
find_package(PkgConfig REQUIRED)

# OpenSubdiv (libosd-dev) is optional: the Catmull-Clark oracle test and `bench`'s peer column.
find_path(OSD_INCLUDE_DIR opensubdiv/far/topologyRefiner.h)
find_library(OSD_CPU_LIBRARY osdCPU)
if(OSD_INCLUDE_DIR AND OSD_CPU_LIBRARY)
  set(POLARVIEW_HAVE_OSD ON)
  add_library(polarview_osd INTERFACE)
  target_include_directories(polarview_osd INTERFACE ${OSD_INCLUDE_DIR})
  target_link_libraries(polarview_osd INTERFACE ${OSD_CPU_LIBRARY})
  message(STATUS "OpenSubdiv found: ${OSD_CPU_LIBRARY}")
else()
  set(POLARVIEW_HAVE_OSD OFF)
  message(STATUS "OpenSubdiv not found: oracle test and bench peer disabled")
endif()

# stb_image_write: the pipeline's PNG files (screenshots, figures).
pkg_check_modules(STB REQUIRED IMPORTED_TARGET stb)

if(POLARVIEW_BUILD_VIEWER)
  find_package(OpenGL REQUIRED)
  find_package(glfw3 REQUIRED)
  pkg_check_modules(IMGUI REQUIRED IMPORTED_TARGET imgui)

  # glad2 loader, generated offline at build time by Debian's `glad` (python3-glad).
  find_program(GLAD_EXECUTABLE glad PATHS /usr/bin NO_DEFAULT_PATH)
  if(NOT GLAD_EXECUTABLE)
    find_program(GLAD_EXECUTABLE glad REQUIRED)
  endif()
  set(GLAD_OUT ${CMAKE_BINARY_DIR}/glad)
  add_custom_command(
    OUTPUT ${GLAD_OUT}/src/gl.c ${GLAD_OUT}/include/glad/gl.h
    COMMAND ${GLAD_EXECUTABLE} --api gl:core=4.5 --extensions= --out-path ${GLAD_OUT} --reproducible --quiet c
    COMMENT "Generating the glad GL 4.5 core loader"
    VERBATIM)
  add_library(polarview_glad STATIC ${GLAD_OUT}/src/gl.c)
  target_include_directories(polarview_glad PUBLIC ${GLAD_OUT}/include)
  set_target_properties(polarview_glad PROPERTIES POSITION_INDEPENDENT_CODE ON)
endif()
