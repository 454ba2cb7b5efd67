// Accuracy of the noise fit on simulated logs with known truth (issue 5): for each profile,
// `seeds` simulated triads (3 independent axes each), the OADEV curve at octave taus, then the
// joint fit and the slope read-outs. Reports per parameter the median |relative error| (with a
// distribution-free 95 % interval of that median), the coverage of the intervals, how often the
// selected model is the true set of terms, and the run time of each method. A third row per
// parameter, "joint, true terms", is the joint fit told the true set (--terms): what the curve
// holds about a parameter once the model is known, so the cost of selecting it shows. The row
// "as reported" is what fit and analyze report (NoiseFit::reported): the joint fit, or the
// curve's read-outs where the consistency guards or the goodness of fit reject it. A plain
// program (not Google Benchmark): it measures error and speed together. Usage:
//   bench_fit_accuracy OUT_PREFIX [SEEDS=200] [PROFILES=mems_gyro,tactical_gyro,consumer_accel,
//                      weak_flicker_gyro,flicker_accel,ramp_gyro,quantized_gyro,short_gyro_5min,
//                      short_gyro_30min] [TAUS=octave] [FIRST_SEED=1]
// (default: every profile; the short_gyro_* profiles are bench/results_fit_short_logs.md's)
// (TAUS: a --taus spec: octave, many:P, ...; FIRST_SEED: seeds FIRST_SEED .. FIRST_SEED+SEEDS-1,
// so that exploration runs can use seeds the reported table does not) writes OUT_PREFIX.md,
// OUT_PREFIX.csv and OUT_PREFIX.channels.csv (every channel's estimates, one row per method and
// true term, for looking into a distribution behind a median).
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

#include "bench_stats.hpp"
#include "fit_profiles.hpp"
#include "sigmatau/allan_curve.hpp"
#include "sigmatau/fit.hpp"
#include "sigmatau/noise_model.hpp"
#include "sigmatau/simulate.hpp"
#include "sigmatau/taus.hpp"
#include "sigmatau/units.hpp"

namespace {

using namespace sigmatau;
using namespace sigmatau::bench;
using Clock = std::chrono::steady_clock;

struct Tally {
  std::vector<double> rel_error;
  std::vector<double> signed_error;  // value / truth - 1 (-1 when left out)
  int covered = 0;
  int estimated = 0;
  // Channels that kept the term: value / truth, and whether the interval covers, split by the
  // short-log rule (rise_without_floor: flagged).
  std::vector<double> kept_ratio[2];
  int kept_covered[2] = {0, 0};
};

struct MethodTally {
  std::map<NoiseTerm, Tally> terms;
  std::map<std::string, int> models;  // selected model ("N,B,K") -> runs
  int correct_model = 0;
  int runs = 0;
  double seconds = 0;
};

/// Where one channel's result goes in the per-channel table.
struct ChannelRow {
  std::ostream& out;
  std::string profile;
  std::string method;
  int seed;
  int axis;
};

void record(MethodTally& tally, const ChannelFit& fit, const NoiseTerms& truth,
            const std::vector<NoiseTerm>& true_terms, const ChannelRow& row) {
  ++tally.runs;
  if (fit.model_terms == true_terms) ++tally.correct_model;
  std::string name;
  for (const NoiseTerm t : fit.model_terms) name += (name.empty() ? "" : ",") + std::string(term_symbol(t));
  ++tally.models[name.empty() ? "-" : name];
  for (const NoiseTerm term : true_terms) {
    const auto& p = fit.parameter(term);
    const double x = truth_of(truth, term);
    row.out << row.profile << ',' << row.method << ',' << row.seed << ',' << row.axis << ",\""
            << name << "\"," << term_symbol(term) << ',' << x << ',' << (p.in_model ? 1 : 0)
            << ',' << p.value << ',' << p.ci_low << ',' << p.ci_high << ',' << p.upper_bound
            << ',' << p.leading_points << ',' << p.edf << '\n';
    Tally& t = tally.terms[term];
    // A true term the model left out counts as a 100% error; its report is the statement
    // "below upper_bound", i.e. the interval [0, upper_bound], which covers when x <= bound.
    t.rel_error.push_back(p.in_model ? std::abs(p.value / x - 1) : 1.0);
    t.signed_error.push_back(p.in_model ? p.value / x - 1 : -1.0);
    if (p.in_model) {
      ++t.estimated;
      const bool covers = p.ci_low <= x && x <= p.ci_high;
      if (covers) ++t.covered;
      const int flagged = rise_without_floor(fit) ? 1 : 0;
      t.kept_ratio[flagged].push_back(p.value / x);
      if (covers) ++t.kept_covered[flagged];
    } else if (x <= p.upper_bound) {
      ++t.covered;
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: bench_fit_accuracy OUT_PREFIX [SEEDS=200] [PROFILES=a,b,c] [TAUS=octave] "
                 "[FIRST_SEED=1]\n";
    return 2;
  }
  const std::string prefix = argv[1];
  const int seeds = argc > 2 ? std::stoi(argv[2]) : 200;
  const TauSpec taus = argc > 4 ? parse_tau_spec(argv[4]) : TauSpec{};
  const int first_seed = argc > 5 ? std::stoi(argv[5]) : 1;
  std::vector<std::string> wanted;
  if (argc > 3) {
    std::stringstream ss(argv[3]);
    for (std::string item; std::getline(ss, item, ',');) wanted.push_back(item);
  }

  std::ostringstream md, csv;
  md << "Joint fit and IEEE slope read-outs on simulated logs with known truth (bench_fit_accuracy, "
     << seeds << " seeds (" << first_seed << " to " << first_seed + seeds - 1
     << ") x 3 independent axes per profile, OADEV at " << (argc > 4 ? argv[4] : "octave")
     << " taus). A true term the selected model leaves out counts as a 100 % error and as "
        "covered when the truth is at most its one-sided 95 % upper bound. Times are wall clock "
        "on a shared 2-core VM.\n\n";
  md << "| profile | method | param | truth | median abs rel error (its 95% interval) | "
        "median rel error | 95% CI coverage | true model selected | fit time per channel |\n"
        "|---|---|---|---|---|---|---|---|---|\n";
  std::ostringstream channels;
  channels.precision(9);
  channels << "profile,method,seed,axis,model,param,truth_si,in_model,value,ci_low,ci_high,"
              "upper_bound,leading_points,edf\n";
  csv << "profile,method,param,truth_si,runs,median_abs_rel_error,median_abs_rel_error_low,"
         "median_abs_rel_error_high,median_rel_error,coverage,model_correct,"
         "fit_ms_per_channel,curve_ms_per_channel,covariance_build_ms\n";

  for (const auto& profile : profiles()) {
    if (!wanted.empty() && std::find(wanted.begin(), wanted.end(), profile.name) == wanted.end()) continue;
    const NoiseTerms truth = parse_noise_terms(profile.model, profile.sensor);
    std::vector<NoiseTerm> true_terms;
    for (const NoiseTerm t : kFitTerms) {
      if (has_term(truth, t)) true_terms.push_back(t);
    }
    SimulationConfig config = simulation_config(profile, truth);

    MethodTally joint, slopes, told;  // told: the joint fit given the true terms
    // What is reported (NoiseFit::reported): the joint fit, or the curve's read-outs where the
    // joint fit is rejected or contradicted by the curve (consistency guards); how often, why.
    MethodTally reported;
    int replaced = 0, contradicted = 0;
    // Spread of the estimates at each tau, to set beside the exact covariance the fit weights
    // by: v_j / mu_j (mu_j the true AVAR of the simulated process) over all channels.
    std::vector<std::int64_t> curve_m;
    std::vector<std::vector<double>> ratios;
    const Sampling truth_sampling = sampling_of(config);
    double curve_seconds = 0, covariance_build_seconds = 0;
    std::vector<double> block;
    for (int seed = first_seed; seed < first_seed + seeds; ++seed) {
      config.seed = static_cast<std::uint64_t>(seed);
      Simulator sim(config);
      std::vector<std::vector<double>> axes(3);
      block.resize(static_cast<std::size_t>(65536 * 3));
      for (std::int64_t rows; (rows = sim.next(block, 65536)) > 0;) {
        for (std::int64_t r = 0; r < rows; ++r) {
          for (int a = 0; a < 3; ++a) axes[a].push_back(block[static_cast<std::size_t>(r * 3 + a)]);
        }
      }
      for (int a = 0; a < 3; ++a) {
        auto t0 = Clock::now();
        const auto series = PhaseSeries::from_rate(axes[a], 1 / profile.rate_hz);
        const AllanCurve curve = compute_allan_curve(series, Statistic::oadev, taus, 0.683);
        auto t1 = Clock::now();
        curve_seconds += std::chrono::duration<double>(t1 - t0).count();
        const CurveSource source{1 / profile.rate_hz, series.size(), 0};
        FitOptions options;
        options.method = FitMethod::joint;
        const NoiseFit j = fit_noise(curve, source, options);
        auto t2 = Clock::now();
        const double joint_seconds = std::chrono::duration<double>(t2 - t1).count();
        if (seed == first_seed && a == 0) {
          covariance_build_seconds = joint_seconds;  // first fit builds the cached covariance basis
        } else {
          joint.seconds += joint_seconds;
        }
        options.method = FitMethod::slopes;
        const NoiseFit s = fit_noise(curve, source, options);
        auto t3 = Clock::now();
        slopes.seconds += std::chrono::duration<double>(t3 - t2).count();
        options.method = FitMethod::joint;
        options.terms = true_terms;
        const NoiseFit k = fit_noise(curve, source, options);
        told.seconds += std::chrono::duration<double>(Clock::now() - t3).count();
        if (curve_m.empty()) {
          for (const auto& p : curve.points) curve_m.push_back(p.value.m);
          ratios.resize(curve_m.size());
        }
        for (std::size_t i = 0; i < curve_m.size(); ++i) {
          const double dev = curve.points[i].value.dev;
          ratios[i].push_back(dev * dev / sampled_avar(truth, curve_m[i], truth_sampling));
        }
        record(joint, *j.joint, truth, true_terms, {channels, profile.name, "joint", seed, a});
        record(reported, j.reported(), truth, true_terms, {channels, profile.name, "reported", seed, a});
        replaced += j.readings.has_value();
        contradicted += !j.joint->contradictions.empty();
        record(slopes, *s.slopes, truth, true_terms, {channels, profile.name, "slopes", seed, a});
        record(told, *k.joint, truth, true_terms,
               {channels, profile.name, "joint_true_terms", seed, a});
      }
      if ((seed - first_seed + 1) % 20 == 0) std::cerr << profile.name << ": " << seed << " seeds\n";
    }
    const int runs = joint.runs;
    for (const auto* m : {&joint, &reported, &told, &slopes}) {
      const bool is_joint = m == &joint;
      const char* method = is_joint            ? "joint"
                           : m == &reported    ? "as reported"
                           : m == &told        ? "joint, true terms"
                                               : "slopes";
      const double per_fit_ms =
          m == &reported ? 0 : 1e3 * m->seconds / (is_joint ? runs - 1 : runs);
      for (const NoiseTerm term : true_terms) {
        const Tally& t = m->terms.at(term);
        const double med = median(t.rel_error);
        const auto [med_low, med_high] = median_interval(t.rel_error);
        const double bias = median(t.signed_error);
        const double cov = static_cast<double>(t.covered) / runs;
        char line[512];
        std::snprintf(line, sizeof line,
                      "| %s | %s | %s | %s | %.2f%% (%.2f-%.2f%%) | %+.2f%% | %.1f%% | %.1f%% | %.3g ms |\n",
                      profile.name.c_str(), method, std::string(term_symbol(term)).c_str(),
                      format_noise_terms(only(truth, term), profile.sensor).c_str(), 100 * med,
                      100 * med_low, 100 * med_high, 100 * bias,
                      100 * cov, 100.0 * m->correct_model / runs, per_fit_ms);
        md << line;
        std::snprintf(line, sizeof line, "%s,%s,%s,%.6e,%d,%.6f,%.6f,%.6f,%.6f,%.4f,%.4f,%.4f,%.4f,%.1f\n",
                      profile.name.c_str(), m == &told ? "joint_true_terms" : m == &reported ? "reported" : method,
                      std::string(term_symbol(term)).c_str(), truth_of(truth, term), runs, med, med_low, med_high, bias, cov,
                      static_cast<double>(m->correct_model) / runs, per_fit_ms,
                      1e3 * curve_seconds / runs, 1e3 * covariance_build_seconds);
        csv << line;
      }
    }
    // Channels that kept K or R, split by the short-log rule (rise_without_floor, joint fit
    // only): how often the term is kept, how often its interval covers, the median of
    // value / truth.
    for (const auto* m : {&joint}) {
      for (const NoiseTerm term : true_terms) {
        if (term != NoiseTerm::rate_random_walk && term != NoiseTerm::rate_ramp) continue;
        const Tally& t = m->terms.at(term);
        md << "| " << profile.name << " | joint | "
           << term_symbol(term) << " | kept | ";
        for (int flagged = 0; flagged < 2; ++flagged) {
          const auto& r = t.kept_ratio[flagged];
          char text[200];
          std::snprintf(text, sizeof text, "%s%s: kept %d of %d (%.1f%%), interval covers %d (%.1f%%), "
                        "median value/truth %.2f",
                        flagged ? "; " : "",
                        flagged ? "no floor (warned)" : "not warned",
                        static_cast<int>(r.size()), runs, 100.0 * static_cast<double>(r.size()) / runs,
                        t.kept_covered[flagged],
                        r.empty() ? 0.0 : 100.0 * t.kept_covered[flagged] / static_cast<double>(r.size()),
                        median(r));
          md << text;
        }
        md << " | | | | | |\n";
      }
    }
    md << "| " << profile.name << " | | | " << profile.description << ", " << runs
       << " channels (" << seeds << " seeds x 3 axes); OADEV curve "
       << 1e3 * curve_seconds / runs << " ms/channel; covariance basis built once in "
       << 1e3 * covariance_build_seconds << " ms; joint fit replaced by the curve's read-outs on "
       << replaced << " (contradicted by the curve on " << contradicted << ")"
       << "; models selected (joint):";
    for (const auto& [name, count] : joint.models) md << " " << name << " " << count;
    md << "; (slopes):";
    for (const auto& [name, count] : slopes.models) md << " " << name << " " << count;
    // EDF = 2 / Var(v / mu): exact (oavar_covariance of the truth) against the simulated spread,
    // and the simulated mean of v / mu, at the four largest taus.
    const Eigen::MatrixXd exact = oavar_covariance(truth, curve_m, config.samples + 1, 1 / profile.rate_hz);
    md << "; EDF exact/simulated (mean v/mu) at the largest taus:";
    for (std::size_t i = curve_m.size() >= 4 ? curve_m.size() - 4 : 0; i < curve_m.size(); ++i) {
      double mean = 0, var = 0;
      const auto count = static_cast<double>(ratios[i].size());
      for (const double r : ratios[i]) mean += r / count;
      for (const double r : ratios[i]) var += (r - mean) * (r - mean) / (count - 1);
      const double mu = sampled_avar(truth, curve_m[i], truth_sampling);
      const auto ii = static_cast<Eigen::Index>(i);
      char text[160];
      std::snprintf(text, sizeof text, " %g s %.1f/%.1f (%.3f)", static_cast<double>(curve_m[i]) / profile.rate_hz,
                    2 * mu * mu / exact(ii, ii), 2 / var, mean);
      md << text;
    }
    md << " | | | | | |\n";
    std::cerr << md.str();
  }
  std::ofstream(prefix + ".md") << md.str();
  std::ofstream(prefix + ".csv") << csv.str();
  std::ofstream(prefix + ".channels.csv") << channels.str();
  std::cout << md.str();
  return 0;
}
