// sigmatau's joint fit against the read-out rules of MATLAB's Allan variance example,
// imu_utils and allan_variance_ros (baseline_rules.hpp says what each does and where that was
// read) on simulated logs with known truth. For each profile, `seeds` simulated triads (3
// independent axes each, the seeds and profiles of bench_fit_accuracy); each tool's rule reads
// the curve that tool computes (its estimator at its tau grid, computed here with the library),
// the joint fit reads the OADEV at octave taus as `sigmatau fit` does. Reports per method and
// parameter the median |relative error| (with a distribution-free 95 % interval of the
// median), the median signed error, the value the rule reads off the expected curve (the
// exact AVAR of the simulated process at the tool's taus: the rule's bias without scatter),
// the coverage of the 95 % intervals (only the joint fit gives intervals) and the median time
// per channel of curve and read-out. A plain program (not Google Benchmark). Usage:
//   bench_fit_baselines OUT_PREFIX [SEEDS=200] [PROFILES=mems_gyro,tactical_gyro,consumer_accel]
// writes OUT_PREFIX.md and OUT_PREFIX.csv.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "baseline_rules.hpp"
#include "bench_stats.hpp"
#include "fit_profiles.hpp"
#include "sigmatau/allan.hpp"
#include "sigmatau/allan_curve.hpp"
#include "sigmatau/fit.hpp"
#include "sigmatau/noise_model.hpp"
#include "sigmatau/simulate.hpp"
#include "sigmatau/taus.hpp"

namespace {

using namespace sigmatau;
using namespace sigmatau::bench;
using Clock = std::chrono::steady_clock;

// imu_utils works in deg/h for gyros, with 57.3 deg per rad (allan_gyr.cpp, pushRadPerSec).
constexpr double kImuUtilsGyroUnit = 57.3 * 3600;

enum class Method { joint, matlab, imu_utils_fit, imu_utils_yaml, ros };
constexpr Method kMethods[] = {Method::joint, Method::matlab, Method::imu_utils_fit,
                               Method::imu_utils_yaml, Method::ros};
constexpr NoiseTerm kParams[] = {NoiseTerm::white, NoiseTerm::bias_instability,
                                 NoiseTerm::rate_random_walk};

const char* method_name(Method m) {
  switch (m) {
    case Method::joint: return "sigmatau joint fit";
    case Method::matlab: return "MATLAB example (slope read-outs)";
    case Method::imu_utils_fit: return "imu_utils fit parameters (printed N, B, K)";
    case Method::imu_utils_yaml: return "imu_utils yaml (gyr_n/sqrt(rate), gyr_w/0.664)";
    case Method::ros: return "allan_variance_ros (lines at 1 s / 3 s, min ADEV/0.664)";
  }
  return "";
}

const char* curve_name(Method m) {
  switch (m) {
    case Method::joint: return "OADEV, octave m";
    case Method::matlab: return "OADEV, 100 log-spaced m to 2^floor(log2(L/2))";
    case Method::imu_utils_fit:
    case Method::imu_utils_yaml: return "OADEV, 100 log-spaced m to 2^floor(log2(L/2))";
    case Method::ros: return "non-overlapping ADEV, tau = 0.1 s ... 999.9 s step 0.1 s";
  }
  return "";
}

/// The estimate of `term` in a tool's report (NaN: the tool reports none).
double tool_value(const BaselineEstimate& e, Method m, NoiseTerm term) {
  switch (term) {
    case NoiseTerm::white: return m == Method::imu_utils_yaml ? e.adev_1s : e.white;
    case NoiseTerm::bias_instability:
      // Floors are compared with the flicker floor 0.664 B of the truth: B = floor / 0.664.
      return m == Method::imu_utils_yaml || m == Method::ros ? e.floor / kFlickerFloorFactor
                                                             : e.bias_instability;
    case NoiseTerm::rate_random_walk:
      return m == Method::imu_utils_yaml ? std::nan("") : e.rate_random_walk;
    default: return std::nan("");
  }
}

struct Tally {
  std::vector<double> abs_error, signed_error;
  int covered = 0;
  double expected_curve_value = std::nan("");  // rule on the exact expected curve
};

struct MethodTally {
  std::map<NoiseTerm, Tally> terms;
  std::vector<double> curve_ms, rule_ms;
  std::vector<double> gyr_w_over_k;  // imu_utils yaml: gyr_w / K (see the results' note)
};

double ms_since(Clock::time_point t0) {
  return 1e3 * std::chrono::duration<double>(Clock::now() - t0).count();
}

/// Deviations at the factors `m` (all must be defined), as two vectors.
void deviations(const PhaseSeries& series, Statistic statistic,
                const std::vector<std::int64_t>& m, std::vector<double>& tau,
                std::vector<double>& dev) {
  const auto points = compute_deviation(series, statistic, m);
  if (points.size() != m.size()) throw std::runtime_error("a tool's tau is beyond the log");
  tau.clear();
  dev.clear();
  for (const auto& p : points) {
    tau.push_back(p.tau_s);
    dev.push_back(p.dev);
  }
}

struct Grids {
  std::vector<std::int64_t> matlab, imu_utils;
  RosGrid ros;
};

/// The curves the three tools read for one channel (tau in s, deviations in SI).
struct ToolCurves {
  std::vector<double> matlab_tau, matlab_dev, iu_tau, iu_dev, ros_dev;
};

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: bench_fit_baselines OUT_PREFIX [SEEDS=200] [PROFILES=a,b,c]\n";
    return 2;
  }
  const std::string prefix = argv[1];
  const int seeds = argc > 2 ? std::stoi(argv[2]) : 200;
  // By default the first three profiles of bench_fit_accuracy (fit_profiles.hpp), same truths.
  std::vector<std::string> wanted{"mems_gyro", "tactical_gyro", "consumer_accel"};
  if (argc > 3) {
    wanted.clear();
    std::stringstream ss(argv[3]);
    for (std::string item; std::getline(ss, item, ',');) wanted.push_back(item);
  }

  std::ostringstream md, csv;
  csv << "profile,method,param,truth_si,runs,median_abs_rel_error,median_abs_rel_error_low,"
         "median_abs_rel_error_high,median_rel_error,expected_curve_rel_error,coverage,"
         "curve_ms,rule_ms\n";

  for (const auto& profile : profiles()) {
    if (!wanted.empty() && std::find(wanted.begin(), wanted.end(), profile.name) == wanted.end()) continue;
    const NoiseTerms truth = parse_noise_terms(profile.model, profile.sensor);
    std::vector<NoiseTerm> params;
    for (const NoiseTerm t : kParams) {
      if (has_term(truth, t)) params.push_back(t);
    }
    SimulationConfig config = simulation_config(profile, truth);
    const bool accel = profile.sensor == Sensor::accel;
    const double iu_unit = accel ? 1.0 : kImuUtilsGyroUnit;
    const double tau0 = 1 / profile.rate_hz;

    const Grids grids{matlab_example_factors(config.samples), imu_utils_factors(config.samples),
                      allan_variance_ros_grid(profile.rate_hz)};
    std::map<Method, MethodTally> tally;

    // Each rule on the expected curve: sqrt of the exact AVAR of the simulated process.
    const auto expected_start = Clock::now();
    {
      const Sampling sampling = sampling_of(config);
      const auto expected = [&](const std::vector<std::int64_t>& m, std::vector<double>& tau,
                                std::vector<double>& dev) {
        tau.clear();
        dev.clear();
        for (const auto f : m) {
          tau.push_back(static_cast<double>(f) * tau0);
          dev.push_back(std::sqrt(sampled_avar(truth, f, sampling)));
        }
      };
      ToolCurves c;
      std::vector<double> ros_tau_unused;
      expected(grids.matlab, c.matlab_tau, c.matlab_dev);
      expected(grids.imu_utils, c.iu_tau, c.iu_dev);
      expected(grids.ros.m, ros_tau_unused, c.ros_dev);
      const BaselineEstimate mat = matlab_example_rule(c.matlab_tau, c.matlab_dev);
      const BaselineEstimate iu = imu_utils_rule(c.iu_tau, c.iu_dev, accel, iu_unit);
      const BaselineEstimate ros = allan_variance_ros_rule(grids.ros.tau_s, c.ros_dev);
      for (const NoiseTerm term : params) {
        const double x = truth_of(truth, term);
        tally[Method::matlab].terms[term].expected_curve_value = tool_value(mat, Method::matlab, term) / x - 1;
        tally[Method::imu_utils_fit].terms[term].expected_curve_value = tool_value(iu, Method::imu_utils_fit, term) / x - 1;
        tally[Method::imu_utils_yaml].terms[term].expected_curve_value = tool_value(iu, Method::imu_utils_yaml, term) / x - 1;
        tally[Method::ros].terms[term].expected_curve_value = tool_value(ros, Method::ros, term) / x - 1;
      }
    }

    std::cerr << profile.name << ": expected curves in " << ms_since(expected_start) / 1e3 << " s\n";
    std::vector<double> block;
    int runs = 0, iu_not_converged = 0;
    double simulate_ms = 0;
    for (int seed = 1; seed <= seeds; ++seed) {
      config.seed = static_cast<std::uint64_t>(seed);
      const auto sim_start = Clock::now();
      Simulator sim(config);
      std::vector<std::vector<double>> axes(3);
      block.resize(static_cast<std::size_t>(65536 * 3));
      for (std::int64_t rows; (rows = sim.next(block, 65536)) > 0;) {
        for (std::int64_t r = 0; r < rows; ++r) {
          for (int a = 0; a < 3; ++a) axes[a].push_back(block[static_cast<std::size_t>(r * 3 + a)]);
        }
      }
      simulate_ms += ms_since(sim_start);
      for (int a = 0; a < 3; ++a) {
        ++runs;
        const auto series = PhaseSeries::from_rate(axes[a], tau0);
        std::map<Method, BaselineEstimate> est;
        // sigmatau: OADEV at octave taus, joint fit at 95 %.
        auto t0 = Clock::now();
        const AllanCurve curve = compute_allan_curve(series, Statistic::oadev, TauSpec{}, 0.683);
        tally[Method::joint].curve_ms.push_back(ms_since(t0));
        t0 = Clock::now();
        FitOptions options;
        options.method = FitMethod::joint;
        const NoiseFit fit = fit_noise(curve, CurveSource{tau0, series.size(), 0}, options);
        tally[Method::joint].rule_ms.push_back(ms_since(t0));
        ToolCurves c;
        std::vector<double> ros_tau_unused;
        t0 = Clock::now();
        deviations(series, Statistic::oadev, grids.matlab, c.matlab_tau, c.matlab_dev);
        tally[Method::matlab].curve_ms.push_back(ms_since(t0));
        t0 = Clock::now();
        est[Method::matlab] = matlab_example_rule(c.matlab_tau, c.matlab_dev);
        tally[Method::matlab].rule_ms.push_back(ms_since(t0));
        t0 = Clock::now();
        deviations(series, Statistic::oadev, grids.imu_utils, c.iu_tau, c.iu_dev);
        const double iu_curve_ms = ms_since(t0);
        t0 = Clock::now();
        est[Method::imu_utils_fit] = imu_utils_rule(c.iu_tau, c.iu_dev, accel, iu_unit);
        const double iu_rule_ms = ms_since(t0);
        if (est[Method::imu_utils_fit].iterations >= 50) ++iu_not_converged;
        est[Method::imu_utils_yaml] = est[Method::imu_utils_fit];
        for (const Method m : {Method::imu_utils_fit, Method::imu_utils_yaml}) {
          tally[m].curve_ms.push_back(iu_curve_ms);
          tally[m].rule_ms.push_back(iu_rule_ms);
        }
        t0 = Clock::now();
        deviations(series, Statistic::adev, grids.ros.m, ros_tau_unused, c.ros_dev);
        tally[Method::ros].curve_ms.push_back(ms_since(t0));
        t0 = Clock::now();
        est[Method::ros] = allan_variance_ros_rule(grids.ros.tau_s, c.ros_dev);
        tally[Method::ros].rule_ms.push_back(ms_since(t0));
        if (has_term(truth, NoiseTerm::rate_random_walk)) {
          tally[Method::imu_utils_yaml].gyr_w_over_k.push_back(
              est[Method::imu_utils_yaml].floor / truth_of(truth, NoiseTerm::rate_random_walk));
        }

        for (const NoiseTerm term : params) {
          const double x = truth_of(truth, term);
          {
            // A term the selected model leaves out counts as a 100 % error, and as covered
            // when the truth is at most its one-sided upper bound (bench_fit_accuracy's rule).
            const auto& p = fit.joint->parameter(term);
            Tally& t = tally[Method::joint].terms[term];
            const double rel = p.in_model ? p.value / x - 1 : -1.0;
            t.abs_error.push_back(std::abs(rel));
            t.signed_error.push_back(rel);
            if (p.in_model ? (p.ci_low <= x && x <= p.ci_high) : x <= p.upper_bound) ++t.covered;
          }
          for (const auto& [m, e] : est) {
            const double v = tool_value(e, m, term);
            if (std::isnan(v)) continue;
            Tally& t = tally[m].terms[term];
            t.abs_error.push_back(std::abs(v / x - 1));
            t.signed_error.push_back(v / x - 1);
          }
        }
      }
      if (seed % 20 == 0) std::cerr << profile.name << ": " << seed << " seeds\n";
    }

    md << "\n### " << profile.name << ": " << profile.description << "\n\nTruth: "
       << profile.model << " (SI: " << format_noise_terms(truth, profile.sensor) << "). "
       << runs << " channels (" << seeds << " seeds x 3 axes). Tau grids: MATLAB "
       << grids.matlab.size() << " factors, imu_utils " << grids.imu_utils.size()
       << ", allan_variance_ros " << grids.ros.m.size() << "; imu_utils' solver hit its 50 "
       << "iterations on " << iu_not_converged << " channels. Simulating a triad took "
       << simulate_ms / seeds / 1e3 << " s per seed (in no method's time).\n\n"
       << "| method | curve read | param | median abs rel error (95% interval) | median rel error "
          "| rule on the expected curve | 95% interval coverage | time per channel: curve + "
          "read-out |\n|---|---|---|---|---|---|---|---|\n";
    for (const Method m : kMethods) {
      MethodTally& mt = tally[m];
      const double curve_ms = median(mt.curve_ms), rule_ms = median(mt.rule_ms);
      for (const NoiseTerm term : params) {
        const std::string sym(term_symbol(term));
        const auto it = mt.terms.find(term);
        if (it == mt.terms.end() || it->second.abs_error.empty()) {
          md << "| " << method_name(m) << " | " << curve_name(m) << " | " << sym
             << " | none (not reported) | | | none | |\n";
          continue;
        }
        const Tally& t = it->second;
        const double med = median(t.abs_error);
        const auto [lo, hi] = median_interval(t.abs_error);
        const double bias = median(t.signed_error);
        const bool has_ci = m == Method::joint;
        char cov[32], expected[32], line[640];
        if (has_ci) {
          std::snprintf(cov, sizeof cov, "%.1f%%", 100.0 * t.covered / runs);
        } else {
          std::snprintf(cov, sizeof cov, "none");
        }
        if (std::isnan(t.expected_curve_value)) {
          std::snprintf(expected, sizeof expected, "-");
        } else {
          std::snprintf(expected, sizeof expected, "%+.2f%%", 100 * t.expected_curve_value);
        }
        std::snprintf(line, sizeof line,
                      "| %s | %s | %s | %.2f%% (%.2f-%.2f%%) | %+.2f%% | %s | %s | %.3g + %.3g ms |\n",
                      method_name(m), curve_name(m), sym.c_str(), 100 * med, 100 * lo, 100 * hi,
                      100 * bias, expected, cov, curve_ms, rule_ms);
        md << line;
        std::snprintf(line, sizeof line, "%s,\"%s\",%s,%.9e,%zu,%.6f,%.6f,%.6f,%.6f,%.6f,%s,%.4f,%.4f\n",
                      profile.name.c_str(), method_name(m), sym.c_str(), truth_of(truth, term),
                      t.abs_error.size(), med, lo, hi, bias, t.expected_curve_value,
                      has_ci ? std::to_string(static_cast<double>(t.covered) / runs).c_str() : "",
                      curve_ms, rule_ms);
        csv << line;
      }
    }
    const auto& ratio = tally[Method::imu_utils_yaml].gyr_w_over_k;
    if (!ratio.empty()) {
      md << "\nimu_utils' yaml has no K; its gyr_w (the model ADEV floor) is what VINS-style "
            "configs take as the bias random walk. Read that way, its SI number is "
         << median(ratio) << " x the true K (median over the channels).\n";
    }
    std::cerr << md.str();
  }
  std::ofstream(prefix + ".md") << md.str();
  std::ofstream(prefix + ".csv") << csv.str();
  std::cout << md.str();
  return 0;
}
