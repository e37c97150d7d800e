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
find_package(meshoptimizer CONFIG QUIET)  # EXT_/KHR_meshopt_compression
prism_require(meshoptimizer_FOUND libmeshoptimizer-dev)
pkg_check_modules(WEBP QUIET IMPORTED_TARGET libwebp)  # EXT_texture_webp
prism_require(WEBP_FOUND libwebp-dev)
if(PRISM_BUILD_TESTS)
  find_package(Catch2 2 CONFIG QUIET)
  prism_require(Catch2_FOUND catch2)
endif()
