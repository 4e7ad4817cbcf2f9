# Eigen 3 (Debian: libeigen3-dev), header only.
find_package(Eigen3 3.3 REQUIRED NO_MODULE)
