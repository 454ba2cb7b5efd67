# The OAVAR covariance's previous FFT path (fit_covariance_fft.cpp): the reference of
# test_fit_covariance and the baseline of bench_fit_covariance, not part of the library.
# Included by tests/CMakeLists.txt and bench/CMakeLists.txt; defined once.
if(NOT TARGET sigmatau_fit_covariance_fft)
  add_library(sigmatau_fit_covariance_fft STATIC ${CMAKE_CURRENT_LIST_DIR}/fit_covariance_fft.cpp)
  target_include_directories(sigmatau_fit_covariance_fft PUBLIC ${CMAKE_CURRENT_LIST_DIR})
  target_link_libraries(sigmatau_fit_covariance_fft
    PUBLIC sigmatau
    PRIVATE PkgConfig::FFTW3 sigmatau_warnings sigmatau_sanitize)
endif()
