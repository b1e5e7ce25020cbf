# The packages the kernels and the filters need, found once for both ways of building
# (the project on its own, or inside a ParaView build; see cmake/Plugin.cmake).
find_package(GDAL REQUIRED)
find_package(nlohmann_json 3 REQUIRED)
find_package(Boost 1.74 REQUIRED)
find_package(OpenMP REQUIRED COMPONENTS CXX)
find_package(PkgConfig REQUIRED)
pkg_check_modules(FFTW3F REQUIRED IMPORTED_TARGET fftw3f)
find_package(OpenCL REQUIRED)
find_package(Eigen3 3.3 REQUIRED NO_MODULE)

# Warnings are errors in the project's own code (not in generated wrapping code).
set(TSYNTH_WARNING_FLAGS -Wall -Wextra -Wshadow -Werror)
