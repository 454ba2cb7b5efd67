// The model-string parser: data-sheet units in, SI out, errors that name the term.
#include <cmath>
#include <numbers>

#include "sigmatau/error.hpp"
#include "sigmatau/noise_model.hpp"
#include "test_support.hpp"

using namespace sigmatau;
using sigmatau::test::rel;

TEST_CASE("gyro model string in data-sheet units converts to SI (THEORY.md T5)") {
  const NoiseTerms t = parse_noise_terms("N=0.15 deg/sqrt(h), B=0.5 deg/h, K=0.02 deg/h/sqrt(h)",
                                         Sensor::gyro);
  // T5 prints 5 significant digits: 1e-4 relative.
  CHECK(*t.white == rel(4.3633e-5, 1e-4));
  CHECK(*t.bias_instability == rel(2.4241e-6, 1e-4));
  // K: deg/h/sqrt(h) -> rad/s/sqrt(s): x pi/180 / 3600^1.5 (THEORY.md 3.2), exact arithmetic.
  CHECK(*t.rate_random_walk == rel(0.02 * std::numbers::pi / 180 / std::pow(3600.0, 1.5), 1e-12));
  CHECK_FALSE(t.quantization.has_value());
  CHECK(t.gauss_markov.empty());
}

TEST_CASE("accelerometer model, Gauss-Markov and sinusoid terms") {
  const NoiseTerms t =
      parse_noise_terms("N=0.06 m/s/sqrt(h), GM=0.01 m/s^2 @ 100 s, SIN=0.02 m/s^2 @ 2 Hz",
                        Sensor::accel);
  CHECK(*t.white == rel(1e-3, 1e-12));  // T5: 0.06 m/s/sqrt(h) = 1e-3 m/s^1.5
  CHECK(t.gauss_markov.at(0).sigma == rel(0.01, 1e-15));
  CHECK(t.gauss_markov.at(0).tau_c_s == rel(100, 1e-15));
  CHECK(t.sinusoid->frequency_hz == rel(2, 1e-15));
}

TEST_CASE("format_noise_terms reads back to the same terms") {
  NoiseTerms t;
  t.quantization = 1.234567890123e-7;
  t.white = 4.3633e-5;
  t.bias_instability = 2.4e-6;
  t.rate_random_walk = 1e-7;
  t.rate_ramp = -3e-9;
  t.gauss_markov = {GaussMarkov{1e-5, 50}};
  t.sinusoid = Sinusoid{1e-4, 3.5, 0};
  for (Sensor s : {Sensor::gyro, Sensor::accel}) {
    const NoiseTerms back = parse_noise_terms(format_noise_terms(t, s), s);
    // %.17g round trip through SI units (factor 1): bit-exact unless a unit factor rounds.
    SIGMATAU_CHECK_REL(*back.white, *t.white, 1e-15);
    SIGMATAU_CHECK_REL(*back.quantization, *t.quantization, 1e-15);
    SIGMATAU_CHECK_REL(*back.rate_ramp, *t.rate_ramp, 1e-15);
    SIGMATAU_CHECK_REL(back.gauss_markov.at(0).tau_c_s, 50.0, 1e-15);
    SIGMATAU_CHECK_REL(back.sinusoid->amplitude, 1e-4, 1e-15);
  }
}

TEST_CASE("bad model strings name the term and what was expected") {
  CHECK_THROWS_WITH_AS(parse_noise_terms("N=3 deg/h", Sensor::gyro), doctest::Contains("N"), Error);
  CHECK_THROWS_WITH_AS(parse_noise_terms("X=1 deg/h", Sensor::gyro),
                       doctest::Contains("unknown term 'X'"), Error);
  CHECK_THROWS_WITH_AS(parse_noise_terms("B=1 deg/h, B=2 deg/h", Sensor::gyro),
                       doctest::Contains("twice"), Error);
  CHECK_THROWS_WITH_AS(parse_noise_terms("B 1 deg/h", Sensor::gyro),
                       doctest::Contains("KEY=VALUE"), Error);
  CHECK_THROWS_WITH_AS(parse_noise_terms("B=-1 deg/h", Sensor::gyro), doctest::Contains("> 0"),
                       Error);
  CHECK_THROWS_WITH_AS(parse_noise_terms("GM=1 deg/h", Sensor::gyro), doctest::Contains("@"),
                       Error);
  CHECK_THROWS_AS(parse_noise_terms("", Sensor::gyro), Error);
  CHECK_THROWS_AS(parse_noise_terms("N=0.15 deg/sqrt(h),", Sensor::gyro), Error);
  CHECK_THROWS_AS(parse_noise_terms("B=3 deg/h", Sensor::accel), Error);  // wrong dimension
}

TEST_CASE("a sum of Gauss-Markov processes: repeated GM keys, kept in order, read back exactly") {
  const NoiseTerms t = parse_noise_terms(
      "N=0.15 deg/sqrt(h), GM=0.01 deg/s @ 100 s, GM=0.003 deg/s @ 2000 s, B=3 deg/h",
      Sensor::gyro);
  REQUIRE(t.gauss_markov.size() == 2);
  const double deg = std::numbers::pi / 180;
  CHECK(t.gauss_markov[0].sigma == rel(0.01 * deg, 1e-15));
  CHECK(t.gauss_markov[0].tau_c_s == rel(100, 1e-15));
  CHECK(t.gauss_markov[1].sigma == rel(0.003 * deg, 1e-15));
  CHECK(t.gauss_markov[1].tau_c_s == rel(2000, 1e-15));
  // Three entries, with awkward values, through format and parse: the terms compare equal
  // (operator== on every field, i.e. bit-exact: SI units have factor 1 and %.17g round-trips a
  // double).
  NoiseTerms three;
  three.white = 4.3633e-5;
  three.gauss_markov = {GaussMarkov{1.0 / 3, 0.1}, GaussMarkov{2.718281828459045e-6, 123.456},
                        GaussMarkov{7e-9, 1e7 / 3}};
  for (Sensor s : {Sensor::gyro, Sensor::accel}) {
    const std::string text = format_noise_terms(three, s);
    INFO(text);
    const NoiseTerms back = parse_noise_terms(text, s);
    CHECK(back == three);
    CHECK(format_noise_terms(back, s) == text);
  }
}

TEST_CASE("a fourth Gauss-Markov process is an error naming the item and the limit") {
  const std::string three = "GM=1 deg/s @ 1 s, GM=2 deg/s @ 10 s, GM=3 deg/s @ 100 s";
  CHECK(parse_noise_terms(three, Sensor::gyro).gauss_markov.size() == kMaxGaussMarkov);
  CHECK_THROWS_WITH_AS(parse_noise_terms(three + ", GM=4 deg/s @ 1000 s", Sensor::gyro),
                       doctest::Contains("'GM=4 deg/s @ 1000 s' is Gauss-Markov term number 4; "
                                         "at most 3 GM terms are supported"),
                       Error);
  // Every other key stays single.
  CHECK_THROWS_WITH_AS(parse_noise_terms("GM=1 deg/s @ 1 s, N=1 deg/sqrt(h), N=2 deg/sqrt(h)",
                                         Sensor::gyro),
                       doctest::Contains("term N is given twice"), Error);
  // The vocabulary's own check (a model built in code) says the same.
  NoiseTerms four;
  four.gauss_markov.assign(4, GaussMarkov{1e-3, 10});
  CHECK_THROWS_WITH_AS(validate(four, "gyro.x"),
                       doctest::Contains("gyro.x: 4 Gauss-Markov processes, at most 3"), Error);
  four.gauss_markov.pop_back();
  CHECK_NOTHROW(validate(four, "gyro.x"));
  four.gauss_markov[2].tau_c_s = -1;
  CHECK_THROWS_WITH_AS(validate(four, "gyro.x"), doctest::Contains("Gauss-Markov tau_c"), Error);
}
