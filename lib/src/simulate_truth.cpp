// A user truth series: linear in time between rows, constant outside; read from a CSV.
//
// Glossary: rows i = 0..n-1 at times t_i (strictly increasing); v_i the vector of one sensor at
// row i; segment i = [t_i, t_{i+1}].
#include "simulate_truth.hpp"

#include <algorithm>
#include <cmath>

#include "sigmatau/error.hpp"
#include "sigmatau/log_reader.hpp"

namespace sigmatau {
namespace detail {
namespace {

/// v at time u inside segment i (or the held end value when i is the last row).
Eigen::Vector3d value_in(const std::vector<double>& t, const std::vector<Eigen::Vector3d>& v,
                         std::size_t i, double u) {
  if (i + 1 >= t.size()) return v.back();
  const double w = (u - t[i]) / (t[i + 1] - t[i]);
  return v[i] + (v[i + 1] - v[i]) * w;
}

}  // namespace

std::size_t TruthCursor::locate(double u) {
  const auto& t = series_->t_s;
  if (u < t[hint_]) {  // moved backwards: search from the start
    hint_ = static_cast<std::size_t>(std::upper_bound(t.begin(), t.end(), u) - t.begin());
    hint_ = hint_ == 0 ? 0 : hint_ - 1;
    return hint_;
  }
  while (hint_ + 1 < t.size() && t[hint_ + 1] <= u) ++hint_;
  return hint_;
}

Truth TruthCursor::at(double u) {
  const auto& s = *series_;
  Truth x;
  if (u <= s.t_s.front()) {
    if (!s.angular_rate.empty()) x.angular_rate = s.angular_rate.front();
    if (!s.specific_force.empty()) x.specific_force = s.specific_force.front();
    return x;
  }
  const std::size_t i = locate(u);
  if (!s.angular_rate.empty()) x.angular_rate = value_in(s.t_s, s.angular_rate, i, u);
  if (!s.specific_force.empty()) x.specific_force = value_in(s.t_s, s.specific_force, i, u);
  return x;
}

Truth TruthCursor::mean(double a, double b) {
  if (!(b > a)) return at(a);
  const auto& s = *series_;
  const auto& t = s.t_s;
  // Integral over [a, b] piece by piece: held first value, trapezoids of the segments (exact for
  // a linear signal), held last value.
  Eigen::Vector3d gyro = Eigen::Vector3d::Zero(), accel = Eigen::Vector3d::Zero();
  const auto piece = [&](const std::vector<Eigen::Vector3d>& v, double from, double to,
                         std::size_t i, bool inside) -> Eigen::Vector3d {
    if (!inside) return (to - from) * v[i];
    return 0.5 * (to - from) * (value_in(t, v, i, from) + value_in(t, v, i, to));
  };
  const auto add = [&](double from, double to, std::size_t i, bool inside) {
    if (!s.angular_rate.empty()) gyro += piece(s.angular_rate, from, to, i, inside);
    if (!s.specific_force.empty()) accel += piece(s.specific_force, from, to, i, inside);
  };
  double x = a;
  if (x < t.front()) {
    const double end = std::min(b, t.front());
    add(x, end, 0, false);
    x = end;
  }
  if (x < b) {
    std::size_t i = locate(x);
    while (x < b && i + 1 < t.size()) {
      const double end = std::min(b, t[i + 1]);
      add(x, end, i, true);
      x = end;
      if (end == t[i + 1]) ++i;
    }
    if (x < b) add(x, b, t.size() - 1, false);
  }
  Truth m;
  m.angular_rate = gyro / (b - a);
  m.specific_force = accel / (b - a);
  return m;
}

}  // namespace detail

void validate(const TruthSeries& s) {
  const std::size_t n = s.t_s.size();
  if (n == 0) throw Error("truth series: no rows");
  if (!s.angular_rate.empty() && s.angular_rate.size() != n)
    throw Error("truth series: " + std::to_string(s.angular_rate.size()) +
                " angular rates for " + std::to_string(n) + " times");
  if (!s.specific_force.empty() && s.specific_force.size() != n)
    throw Error("truth series: " + std::to_string(s.specific_force.size()) +
                " specific forces for " + std::to_string(n) + " times");
  for (std::size_t i = 0; i < n; ++i) {
    const std::string row = " (row " + std::to_string(i + 1) + ")";
    if (!std::isfinite(s.t_s[i])) throw Error("truth series: time is not finite" + row);
    if (i > 0 && !(s.t_s[i] > s.t_s[i - 1]))
      throw Error("truth series: times must increase strictly" + row);
    if ((!s.angular_rate.empty() && !s.angular_rate[i].allFinite()) ||
        (!s.specific_force.empty() && !s.specific_force[i].allFinite()))
      throw Error("truth series: value is not finite" + row);
  }
}

Truth truth_at(const TruthSeries& series, double t_s) {
  validate(series);
  return detail::TruthCursor(series).at(t_s);
}

Truth truth_mean(const TruthSeries& series, double t0_s, double t1_s) {
  validate(series);
  return detail::TruthCursor(series).mean(t0_s, t1_s);
}

TruthSeries read_truth_csv(const std::filesystem::path& path, bool gyro, bool accel,
                           double gyro_factor, double accel_factor) {
  if (!gyro && !accel) throw Error("truth file " + path.string() + ": no sensor asked for");
  LogOptions options;
  options.path = path.string();
  options.time_column = "t";
  if (gyro) options.columns.insert(options.columns.end(), {"gx", "gy", "gz"});
  if (accel) options.columns.insert(options.columns.end(), {"ax", "ay", "az"});
  const Log log = read_log(options);
  if (log.timing.non_increasing > 0)
    throw ParseError(log.path, log.timing.first_non_increasing_line, 0,
                     "truth time stamps must increase strictly (step " +
                         std::to_string(log.timing.first_non_increasing_step_s) + " s)");
  TruthSeries s;
  s.source = path.string();
  s.t_s = log.t_s;
  const std::size_t n = s.t_s.size();
  const auto take = [&](std::size_t first, double factor) {
    std::vector<Eigen::Vector3d> v(n);
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t a = 0; a < 3; ++a) v[i][static_cast<Eigen::Index>(a)] = log.channels[first + a][i] * factor;
    return v;
  };
  if (gyro) s.angular_rate = take(0, gyro_factor);
  if (accel) s.specific_force = take(gyro ? 3 : 0, accel_factor);
  validate(s);
  return s;
}

}  // namespace sigmatau
