# OpenMP for the Monte Carlo and particle loops.
find_package(OpenMP REQUIRED COMPONENTS CXX)
