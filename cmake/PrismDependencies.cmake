# Finds Prism's dependencies, all from Debian 12 packages. A missing one stops the configure step
# with the name of the package that provides it.

function(prism_require found package)
  if(NOT ${found})
    message(FATAL_ERROR "Prism needs the Debian package '${package}'. Install it with:\n"
                        "  sudo apt-get install -y ${package}\n"
                        "(or run 'make deps', which installs everything Prism needs).")
  endif()
endfunction()

find_package(Threads REQUIRED)
find_package(PkgConfig QUIET)
prism_require(PkgConfig_FOUND pkg-config)

find_package(OpenEXR 3 CONFIG QUIET)
prism_require(OpenEXR_FOUND libopenexr-dev)
# Debian installs OpenColorIO's CMake config outside CMake's search path; pkg-config finds it.
pkg_check_modules(OCIO QUIET IMPORTED_TARGET OpenColorIO>=2.1)
prism_require(OCIO_FOUND libopencolorio-dev)
find_package(TinyGLTF CONFIG QUIET)
prism_require(TinyGLTF_FOUND libtinygltf-dev)
find_package(nlohmann_json 3 CONFIG QUIET)
prism_require(nlohmann_json_FOUND nlohmann-json3-dev)
find_package(TBB CONFIG QUIET)
prism_require(TBB_FOUND libtbb-dev)
find_package(CLI11 CONFIG QUIET)
prism_require(CLI11_FOUND libcli11-dev)
find_package(fmt CONFIG QUIET)
prism_require(fmt_FOUND libfmt-dev)
pkg_check_modules(STB QUIET IMPORTED_TARGET stb)
prism_require(STB_FOUND libstb-dev)
find_package(draco CONFIG QUIET)  # KHR_draco_mesh_compression
prism_require(draco_FOUND libdraco-dev)
# Debian's libdraco also holds its own copies of tinygltf and stb_image (archive member
# tiny_gltf_utils.cc.o, exported by libdraco.so too): linked, they would stand in for the system's
# (another version, another layout) and crash. Prism links a copy of the static archive without
# that member: prism::draco, the decoder and encoder only.
get_target_property(PRISM_DRACO_ARCHIVE draco::draco_static IMPORTED_LOCATION_NONE)
set(PRISM_DRACO ${CMAKE_BINARY_DIR}/libprism_draco.a)
if(NOT EXISTS ${PRISM_DRACO} OR ${PRISM_DRACO_ARCHIVE} IS_NEWER_THAN ${PRISM_DRACO})
  file(COPY_FILE ${PRISM_DRACO_ARCHIVE} ${PRISM_DRACO})
  execute_process(COMMAND ${CMAKE_AR} d ${PRISM_DRACO} tiny_gltf_utils.cc.o RESULT_VARIABLE PRISM_DRACO_AR)
  if(NOT PRISM_DRACO_AR EQUAL 0)
    message(FATAL_ERROR "Cannot remove tinygltf from a copy of ${PRISM_DRACO_ARCHIVE}")
  endif()
endif()
add_library(prism::draco STATIC IMPORTED GLOBAL)
set_target_properties(prism::draco PROPERTIES IMPORTED_LOCATION ${PRISM_DRACO} INTERFACE_INCLUDE_DIRECTORIES
                                                                                 /usr/include)
find_package(meshoptimizer CONFIG QUIET)  # EXT_/KHR_meshopt_compression
prism_require(meshoptimizer_FOUND libmeshoptimizer-dev)
pkg_check_modules(WEBP QUIET IMPORTED_TARGET libwebp)  # EXT_texture_webp
prism_require(WEBP_FOUND libwebp-dev)
find_package(yaml-cpp CONFIG QUIET)  # refractiveindex.info's YAML pages (core/scene/refractive_index_file)
prism_require(yaml-cpp_FOUND libyaml-cpp-dev)
if(PRISM_BUILD_TESTS)
  find_package(Catch2 2 CONFIG QUIET)
  prism_require(Catch2_FOUND catch2)
endif()
