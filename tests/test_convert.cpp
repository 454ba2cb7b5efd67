// Continuous -> discrete conversion: THEORY.md section 9 worked values (T1, T2, T3, T5, T6, T7),
// the Gauss-Markov rule checked against the GM Allan variance of noise_model.hpp, inflation,
// correlation, bad options, and every shipped data sheet.
#include <cmath>
#include <numbers>

#include "sigmatau/convert.hpp"
#include "sigmatau/error.hpp"
#include "sigmatau/filter_export.hpp"
#include "sigmatau/units.hpp"
#include "test_support.hpp"

using namespace sigmatau;

namespace {

constexpr double kDeg = std::numbers::pi / 180;
/// Round-off of a handful of floating-point operations on exact inputs.
constexpr double kRoundOff = 1e-12;

TriadNoise gyro_terms(std::optional<double> n, std::optional<double> b_ds,
                      std::optional<double> k = std::nullopt) {
  NoiseTerms t;
  t.white = n;
  if (b_ds) t.bias_instability = *b_ds / kFlickerFloorFactor;  // printed value = ADEV floor
  t.rate_random_walk = k;
  return uniform_triad(Sensor::gyro, t);
}

ConvertOptions at(double rate_hz) {
  ConvertOptions o;
  o.rate_hz = rate_hz;
  return o;
}

}  // namespace

TEST_CASE("T1: 0.015 deg/s/sqrt(Hz) at 10 Hz gives Q = 0.00225 (deg/s)^2, sigma = 0.0474 deg/s") {
  // THEORY.md section 9 T1 (the seed): Q = 0.015^2 x 10 = 0.00225 (deg/s)^2, sigma_d 0.0474.
  const TriadDiscrete r = discretize(gyro_terms(0.015 * kDeg, std::nullopt), at(10));
  REQUIRE(r.white);
  SIGMATAU_CHECK_REL(r.white->variance_per_sample(0) / (kDeg * kDeg), 0.00225, kRoundOff);
  // 0.0474 is printed to 3 digits: exact 0.0474342, so rtol 1e-3.
  SIGMATAU_CHECK_REL(r.white->sigma_per_sample(2) / kDeg, 0.0474, 1e-3);
  // The 3x3 matrix: diagonal, no cross-correlation given.
  SIGMATAU_CHECK_REL(r.white->q(1, 1), r.white->variance_per_sample(1), kRoundOff);
  CHECK(r.white->q(0, 1) == 0);
  CHECK(!r.bias);

  SUBCASE("one-sided reading: 0.001125 (deg/s)^2 (T1)") {
    const TriadNoise t = triad_from_data_sheet(
        parse_data_sheet("schema: 1\nmanufacturer: T\npart: P\ngrade: consumer\nsources:\n"
                         "  s: {document: D, kind: secondary}\ngyro:\n"
                         "  noise_density: {typ: 0.015 deg/s/sqrt(Hz), source: s}\n",
                         "inline.yaml"),
        Sensor::gyro, DensityConvention::one_sided);
    const TriadDiscrete one = discretize(t, at(10));
    SIGMATAU_CHECK_REL(one.white->variance_per_sample(0) / (kDeg * kDeg), 0.001125, kRoundOff);
  }
}

TEST_CASE("T2: 3 deg/h reached after T_ref = 100 s gives Q_bb = 6.944e-11 (deg/s)^2 at 100 Hz") {
  // THEORY.md section 9 T2: (3/3600)^2 x dt/100 = 6.944e-11, 6.944e-10, 6.944e-9 (deg/s)^2 for
  // dt = 0.01, 0.1, 1 s; printed to 4 digits (exact 6.9444e-11), so rtol 1e-4.
  const double expected[] = {6.944e-11, 6.944e-10, 6.944e-9};
  const double rates[] = {100, 10, 1};
  for (int i = 0; i < 3; ++i) {
    const TriadDiscrete r = discretize(gyro_terms(std::nullopt, 3 * kDeg / 3600), at(rates[i]));
    REQUIRE(r.bias);
    CHECK(r.bias->source == BiasSource::bias_stability);
    SIGMATAU_CHECK_REL(r.bias->variance_per_step(0) / (kDeg * kDeg), expected[i], 1e-4);
    // The walk reaches B_ds after T_ref: Q_bb x (T_ref / T_s) = B_ds^2.
    SIGMATAU_CHECK_REL(r.bias->variance_per_step(0) * 100 * rates[i],
                       std::pow(3 * kDeg / 3600, 2), kRoundOff);
  }
}

TEST_CASE("T3: Kalibr discrete std of 0.2 rad/s/sqrt(Hz) at 100 Hz is 2.0 rad/s") {
  // THEORY.md section 9 T3 (Kalibr wiki copy prints "2.0 rad/s").
  const TriadDiscrete r = discretize(gyro_terms(0.2, std::nullopt), at(100));
  SIGMATAU_CHECK_REL(r.white->sigma_per_sample(0), 2.0, kRoundOff);
}

TEST_CASE("T5, T7: printed ARW, VRW and bias stability give the published SI densities") {
  // T5 STIM300: 0.15 deg/sqrt(h) -> 4.3633e-5 rad/s^0.5; 0.06 m/s/sqrt(h) -> 1e-3 m/s^1.5.
  // T7 ENGO623: 0.01 deg/sqrt(h) -> 2.909e-6; 0.003 m/s/sqrt(h) -> 5e-5; 0.1 deg/h -> 4.848e-7.
  // Rounded to 4-5 digits where printed: rtol 1e-4 (4.3633e-5, 2.909e-6 and 4.848e-7 are within
  // 1.2e-4 of the exact values; 2.909e-6 is 2.9089e-6 exactly, 4.848e-7 is 4.8481e-7).
  struct Case {
    const char* text;
    Dimension dimension;
    double expected, rtol;
  };
  const Case cases[] = {
      {"0.15 deg/sqrt(h)", dim::angle_random_walk, 4.3633e-5, 1e-4},
      {"0.06 m/s/sqrt(h)", dim::velocity_random_walk, 1e-3, kRoundOff},
      {"0.01 deg/sqrt(hr)", dim::angle_random_walk, 2.909e-6, 1e-4},
      {"0.003 m/s/sqrt(hr)", dim::velocity_random_walk, 5e-5, kRoundOff},
      {"0.1 deg/hr", dim::angular_rate, 4.848e-7, 1e-4},
  };
  for (const auto& c : cases) {
    INFO(c.text);
    SIGMATAU_CHECK_REL(parse_quantity_as(c.text, c.dimension, "test"), c.expected, c.rtol);
  }
  // The same densities pass through the conversion unchanged (F = 1): N is the exported density.
  const TriadDiscrete r = discretize(gyro_terms(4.36332e-5, std::nullopt), at(200));
  SIGMATAU_CHECK_REL(r.white->density(0), 4.36332e-5, kRoundOff);
}

TEST_CASE("a data sheet's ARW is used as N in preference to its noise density") {
  // ADIS16470 prints ND 0.008 deg/s/sqrt(Hz) and ARW 0.34 deg/sqrt(h): N = 0.34/60 deg/s/sqrt(Hz).
  const DataSheet s = load_data_sheet(std::filesystem::path(SIGMATAU_SOURCE_DIR) / "specs" /
                                      "adi_adis16470.yaml");
  const TriadNoise t = triad_from_data_sheet(s, Sensor::gyro, DensityConvention::two_sided);
  SIGMATAU_CHECK_REL(*t.axes[0].white, 0.34 / 60 * kDeg, kRoundOff);
  CHECK(t.white_origin.find("Allan N itself") != std::string::npos);
  // Bias stability 8 deg/h read as the ADEV floor: B = 8 deg/h / 0.664.
  SIGMATAU_CHECK_REL(*t.axes[0].bias_instability * kFlickerFloorFactor, 8 * kDeg / 3600,
                     kRoundOff);
}

TEST_CASE("a measured K gives Q_bb = K^2 T_s and takes precedence over B for rw") {
  const double k = 2e-5;  // rad/s^2/sqrt(Hz)
  const TriadDiscrete r = discretize(gyro_terms(1e-4, 3 * kDeg / 3600, k), at(200));
  CHECK(r.bias->source == BiasSource::rate_random_walk);
  SIGMATAU_CHECK_REL(r.bias->variance_per_step(0), k * k / 200, kRoundOff);
  SIGMATAU_CHECK_REL(r.bias->random_walk_density(0), k, kRoundOff);
}

TEST_CASE("Gauss-Markov from a bias stability peaks at B_ds at tau_min (THEORY.md fact 11)") {
  const double b_ds = 3 * kDeg / 3600;
  ConvertOptions o = at(100);
  o.bias_model = BiasModel::gauss_markov;
  o.tau_min_s = 400;
  const TriadDiscrete r = discretize(gyro_terms(std::nullopt, b_ds), o);
  REQUIRE(r.bias);
  const double sigma = b_ds / kGaussMarkovPeakFactor;  // the stated rule
  const double tau_c = 400 / kGaussMarkovPeakTau;
  const double phi = std::exp(-0.01 / tau_c);
  SIGMATAU_CHECK_REL(r.bias->sigma(0), sigma, kRoundOff);
  SIGMATAU_CHECK_REL(r.bias->tau_c_s(0), tau_c, kRoundOff);
  SIGMATAU_CHECK_REL(r.bias->phi(0), phi, kRoundOff);
  // q = sigma^2 (1 - phi^2): 1 - phi^2 is computed from phi ~ 0.99995, so allow 1e-9.
  SIGMATAU_CHECK_REL(r.bias->variance_per_step(0), sigma * sigma * (1 - phi * phi), 1e-9);
  // Independent check with the continuous GM Allan variance of noise_model.hpp: its ADEV at
  // tau_min equals B_ds to the 4 digits of 0.6174 and 1.892 (rtol 1e-3).
  NoiseTerms gm;
  gm.gauss_markov = {GaussMarkov{r.bias->sigma(0), r.bias->tau_c_s(0)}};
  SIGMATAU_CHECK_REL(std::sqrt(continuous_avar(gm, 400.0)), b_ds, 1e-3);
  // ... and it is the peak: 10% either side is lower.
  CHECK(continuous_avar(gm, 360.0) < continuous_avar(gm, 400.0));
  CHECK(continuous_avar(gm, 440.0) < continuous_avar(gm, 400.0));

  SUBCASE("without tau_min, T_ref is used") {
    ConvertOptions o2 = at(100);
    o2.bias_model = BiasModel::gauss_markov;
    const TriadDiscrete r2 = discretize(gyro_terms(std::nullopt, b_ds), o2);
    SIGMATAU_CHECK_REL(r2.bias->tau_c_s(0), kDefaultReferenceTime / kGaussMarkovPeakTau,
                       kRoundOff);
  }
  SUBCASE("a GM cannot be made from K alone") {
    CHECK_THROWS_AS(discretize(gyro_terms(std::nullopt, std::nullopt, 1e-5), o), Error);
  }
}

TEST_CASE("a sum of Gauss-Markov processes: gm carries the largest sigma, rw sums K^2") {
  NoiseTerms t;
  t.white = 1e-4;
  // The larger sigma is the second entry, with the shorter T_c: the rule is the ADEV bump's
  // height (0.6174 sigma), not the order written nor the correlation time.
  const GaussMarkov slow{2e-5, 500.0}, dominant{6e-5, 30.0};
  t.gauss_markov = {slow, dominant};
  const std::vector<TriadNoise> triads{uniform_triad(Sensor::gyro, t)};

  SUBCASE("gm: one state, the dominant entry, and the files say what was left out") {
    ConvertOptions o = at(100);
    o.bias_model = BiasModel::gauss_markov;
    const DiscreteNoise n = convert_noise(triads, o, "a test model");
    REQUIRE(n.gyro->bias);
    CHECK(n.gyro->bias->source == BiasSource::gauss_markov);
    CHECK(n.gyro->bias->sigma(0) == dominant.sigma);
    CHECK(n.gyro->bias->tau_c_s(0) == dominant.tau_c_s);
    // Left out: 4e-10 of 4e-10 + 3.6e-9 of stationary variance, 10 %.
    REQUIRE(n.notes.size() == 1);
    CHECK(n.notes[0].find("sum of 2 Gauss-Markov processes") != std::string::npos);
    CHECK(n.notes[0].find("T_c 30 s") != std::string::npos);
    CHECK(n.notes[0].find("(10 % of the stationary bias variance)") != std::string::npos);
    for (ExportFormat f : {ExportFormat::json, ExportFormat::openvins}) {
      const std::string file = export_filter_config(n, f);
      INFO(to_string(f));
      CHECK(file.find("sum of 2 Gauss-Markov processes") != std::string::npos);
    }
    CHECK(n.explain.find("the entry with the largest sigma") != std::string::npos);
  }
  SUBCASE("rw: K^2 is the sum of 2 sigma_i^2 / T_c_i, the sum's short-tau random walk") {
    const DiscreteNoise n = convert_noise(triads, at(100), "a test model");
    REQUIRE(n.gyro->bias);
    const double k = n.gyro->bias->random_walk_density(0);
    SIGMATAU_CHECK_REL(k * k, 2 * slow.sigma * slow.sigma / slow.tau_c_s +
                                  2 * dominant.sigma * dominant.sigma / dominant.tau_c_s,
                       kRoundOff);
    // Independent check: the sum's continuous AVAR at tau = 1e-3 x the shortest T_c is
    // K^2 tau / 3 to O(tau / T_c): the next term of each entry's series is -(3/4) tau/T_c
    // relative, 7.5e-4 here, so 1e-3.
    NoiseTerms gm_only;
    gm_only.gauss_markov = t.gauss_markov;
    const double tau = 0.03;
    SIGMATAU_CHECK_REL(continuous_avar(gm_only, tau), k * k * tau / 3, 1e-3);
    REQUIRE(n.notes.size() == 1);
    CHECK(n.notes[0].find("K^2 = sum 2 sigma_i^2/T_c_i") != std::string::npos);
  }
  SUBCASE("one entry: no note (files as before)") {
    NoiseTerms one;
    one.gauss_markov = {dominant};
    ConvertOptions o = at(100);
    o.bias_model = BiasModel::gauss_markov;
    CHECK(convert_noise({uniform_triad(Sensor::gyro, one)}, o, "x").notes.empty());
  }
}

TEST_CASE("inflation multiplies densities and sigmas by F and variances by F^2") {
  ConvertOptions o = at(50);
  const TriadDiscrete plain = discretize(gyro_terms(1e-4, 1e-5), o);
  o.inflate = 10;
  const TriadDiscrete inflated = discretize(gyro_terms(1e-4, 1e-5), o);
  SIGMATAU_CHECK_REL(inflated.white->density(0), 10 * plain.white->density(0), kRoundOff);
  SIGMATAU_CHECK_REL(inflated.white->variance_per_sample(0),
                     100 * plain.white->variance_per_sample(0), kRoundOff);
  SIGMATAU_CHECK_REL(inflated.bias->variance_per_step(0), 100 * plain.bias->variance_per_step(0),
                     kRoundOff);
}

TEST_CASE("a given cross-correlation fills the off-diagonal: Q_ij = sigma_i sigma_j c_ij") {
  TriadNoise t = gyro_terms(1e-3, std::nullopt);
  t.white_correlation(0, 1) = t.white_correlation(1, 0) = 0.5;
  const TriadDiscrete r = discretize(t, at(100));
  const double var = 1e-6 * 100;
  SIGMATAU_CHECK_REL(r.white->q(0, 1), 0.5 * var, kRoundOff);
  SIGMATAU_CHECK_REL(r.white->q(1, 0), 0.5 * var, kRoundOff);
  CHECK(r.white->q(0, 2) == 0);
  SUBCASE("an invalid correlation is rejected") {
    t.white_correlation(0, 1) = 0.9;  // no longer symmetric
    CHECK_THROWS_AS(discretize(t, at(100)), Error);
  }
}

TEST_CASE("bad options are errors, NaN included") {
  const TriadNoise t = gyro_terms(1e-4, 1e-5);
  for (double bad : {0.0, -1.0, std::nan("")}) {
    CHECK_THROWS_AS(discretize(t, at(bad)), Error);
    ConvertOptions o = at(100);
    o.t_ref_s = bad;
    CHECK_THROWS_AS(discretize(t, o), Error);
    o = at(100);
    o.inflate = bad;
    CHECK_THROWS_AS(discretize(t, o), Error);
  }
  CHECK_THROWS_AS(parse_bias_model("walk"), Error);
  CHECK_THROWS_AS(parse_density_convention("double"), Error);
}

TEST_CASE("the explanation shows the arithmetic and the convention") {
  const TriadNoise t = gyro_terms(0.015 * kDeg, 3 * kDeg / 3600);
  ConvertOptions o = at(10);
  const DiscreteNoise d = convert_noise({t}, o, "test");
  CHECK(d.explain.find("Q = N^2 f_s") != std::string::npos);
  CHECK(d.explain.find("0.00225 (deg/s)^2") != std::string::npos);
  CHECK(d.explain.find("density convention two-sided") != std::string::npos);
  CHECK(d.explain.find("Q_bb = K^2 T_s") != std::string::npos);
}

TEST_CASE("every shipped data sheet with noise terms converts to finite positive covariances") {
  const auto dir = std::filesystem::path(SIGMATAU_SOURCE_DIR) / "specs";
  int converted = 0;
  for (const auto& file : list_data_sheets(dir)) {
    INFO(file.string());
    const DataSheet s = load_data_sheet(file);
    for (const Sensor sensor : {Sensor::gyro, Sensor::accel}) {
      if (!s.sensor(sensor)) continue;
      for (const BiasModel model : {BiasModel::random_walk, BiasModel::gauss_markov}) {
        const TriadNoise t = triad_from_data_sheet(s, sensor, DensityConvention::two_sided);
        ConvertOptions o = at(200);
        o.bias_model = model;
        const bool k_only = !t.axes[0].bias_instability && t.axes[0].rate_random_walk;
        if (model == BiasModel::gauss_markov && k_only) continue;
        const TriadDiscrete r = discretize(t, o);
        if (r.white) {
          CHECK(r.white->variance_per_sample.minCoeff() > 0);
          CHECK(std::isfinite(r.white->q.sum()));
          ++converted;
        }
        if (r.bias) {
          CHECK(r.bias->variance_per_step.minCoeff() > 0);
          CHECK(std::isfinite(r.bias->q.sum()));
        }
      }
    }
  }
  CHECK(converted >= 20);  // 13 sheets print gyro or accel white noise, most both
}
