#pragma once
// Shared helpers for the doctest suite: relative comparisons that print both operands, and the
// location of reference data (skipped, with a message, when absent).
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <cstdint>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "sigmatau/error.hpp"

namespace sigmatau::test {

/// Relative approximate equality: |actual/expected - 1| <= rtol (never doctest's default
/// absolute-ish tolerance). Use as CHECK(actual == rel(expected, 1e-4)); write the reason for rtol
/// next to each use.
inline doctest::Approx rel(double expected, double rtol) {
  return doctest::Approx(expected).epsilon(rtol).scale(0);
}

/// Checks |a - b| <= rtol * |b| and prints both numbers on failure.
#define SIGMATAU_CHECK_REL(a, b, rtol)                                                  \
  do {                                                                                  \
    const double sigmatau_a_ = (a), sigmatau_b_ = (b);                                  \
    INFO(#a " = " << sigmatau_a_ << ", " #b " = " << sigmatau_b_ << ", rtol = " << (rtol)); \
    CHECK(std::abs(sigmatau_a_ - sigmatau_b_) <= (rtol) * std::abs(sigmatau_b_));       \
  } while (0)

/// n Gaussian values of `mean` and standard deviation `sigma` (std::mt19937_64 from `seed`).
inline std::vector<double> white(std::size_t n, double mean, double sigma, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(mean, sigma);
  std::vector<double> x(n);
  for (auto& v : x) v = normal(rng);
  return x;
}

/// Reference data root (configured with -DSIGMATAU_DATA_DIR, default ../shared/data).
inline std::filesystem::path reference_data_dir() { return SIGMATAU_DATA_DIR; }

/// Small inputs shipped with the tests (tests/data).
inline std::filesystem::path test_data_dir() { return SIGMATAU_TEST_DATA_DIR; }

/// True when `relative` exists under the reference data root; otherwise prints why the calling
/// test is skipped. Usage: if (!has_reference_data("allantools/phasedat")) return;
inline bool has_reference_data(const std::string& relative) {
  const auto p = reference_data_dir() / relative;
  if (std::filesystem::exists(p)) return true;
  MESSAGE("SKIPPED: reference data not found at " << p.string()
                                                  << " (configure with -DSIGMATAU_DATA_DIR=...)");
  return false;
}

/// The whole content of a file ("" when it cannot be read).
inline std::string file_text(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The message of the sigmatau::Error `f` throws, or "" when it throws none.
template <class F>
std::string error_of(F f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace sigmatau::test
