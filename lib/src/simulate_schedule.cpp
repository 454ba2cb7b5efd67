// Multi-position schedules and temperature profiles for the simulator.
//
// Glossary (simulate.hpp file comment): C body-to-NED attitude; u unit rotation axis (body);
// theta rotation angle; D rotation duration; s time since the rotation started; phi(s) the angle
// turned; Exp(u phi) the rotation matrix about u by phi (Rodrigues).
#include "simulate_schedule.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "sigmatau/error.hpp"

namespace sigmatau {
namespace {

constexpr double kPi = std::numbers::pi;
/// Golden angle pi (3 - sqrt 5) [rad]: successive Fibonacci-sphere points and yaws never line up.
const double kGoldenAngle = kPi * (3.0 - std::sqrt(5.0));
/// Rotations smaller than this [rad] are treated as none (identical orientations).
constexpr double kNoRotation = 1e-12;

/// 8-point Gauss-Legendre nodes and weights on [-1, 1] (Abramowitz & Stegun Table 25.4): exact for
/// polynomials of degree 15; a rotation turns well under 0.1 rad per sample interval in any real
/// schedule, so the smooth integrand is integrated to rounding.
constexpr std::array<double, 8> kGaussNodes{-0.9602898564975363, -0.7966664774136267,
                                            -0.5255324099163290, -0.1834346424956498,
                                            0.1834346424956498,  0.5255324099163290,
                                            0.7966664774136267,  0.9602898564975363};
constexpr std::array<double, 8> kGaussWeights{0.1012285362903763, 0.2223810344533745,
                                              0.3137066238688431, 0.3626837833783620,
                                              0.3626837833783620, 0.3137066238688431,
                                              0.2223810344533745, 0.1012285362903763};

Eigen::Matrix3d body_to_ned(double roll, double pitch, double yaw) {
  return (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

void validate_schedule(const Schedule& s) {
  if (s.positions.empty()) throw Error("schedule: no positions");
  for (std::size_t i = 0; i < s.positions.size(); ++i) {
    const auto& p = s.positions[i];
    if (!std::isfinite(p.roll_rad) || !std::isfinite(p.pitch_rad) || !std::isfinite(p.yaw_rad))
      throw Error("schedule: position " + std::to_string(i + 1) + " has a non-finite angle");
    if (!(p.dwell_s >= 0) || !std::isfinite(p.dwell_s))
      throw Error("schedule: position " + std::to_string(i + 1) + " needs a dwell >= 0 s");
  }
  if (s.positions.size() > 1 &&
      (!(s.rotation_rate_rad_s > 0) || !std::isfinite(s.rotation_rate_rad_s)))
    throw Error("schedule: the rotation rate must be > 0");
  if (!std::isfinite(s.latitude_rad) || std::abs(s.latitude_rad) > kPi / 2)
    throw Error("schedule: latitude must be within +-90 deg");
}

}  // namespace

namespace detail {

ScheduleTruth::ScheduleTruth(const Schedule& schedule) {
  validate_schedule(schedule);
  const double lat = schedule.latitude_rad;
  earth_rate_n_ = earth_rate_ned(lat);
  specific_force_n_ = Eigen::Vector3d(0, 0, -normal_gravity(lat));
  double t = 0;
  const auto& ps = schedule.positions;
  for (std::size_t k = 0; k < ps.size(); ++k) {
    const Eigen::Matrix3d c = body_to_ned(ps[k].roll_rad, ps[k].pitch_rad, ps[k].yaw_rad);
    static_truth_.push_back({c.transpose() * earth_rate_n_, c.transpose() * specific_force_n_});
    segments_.push_back({t, t + ps[k].dwell_s, static_cast<int>(k), false});
    rotation_.push_back({});
    t += ps[k].dwell_s;
    if (k + 1 == ps.size()) break;
    const Eigen::Matrix3d next =
        body_to_ned(ps[k + 1].roll_rad, ps[k + 1].pitch_rad, ps[k + 1].yaw_rad);
    const Eigen::AngleAxisd relative(Eigen::Matrix3d(c.transpose() * next));
    if (relative.angle() < kNoRotation) continue;
    const double duration = 2 * relative.angle() / schedule.rotation_rate_rad_s;
    segments_.push_back({t, t + duration, static_cast<int>(k), true});
    rotation_.push_back({c, relative.axis(), relative.angle()});
    t += duration;
  }
}

double ScheduleTruth::duration_s() const { return segments_.back().end_s; }

std::size_t ScheduleTruth::find(double t_s) const {
  // The last segment starting at or before t (zero-length segments are skipped over).
  const auto it = std::upper_bound(segments_.begin(), segments_.end(), t_s,
                                   [](double t, const ScheduleSegment& s) { return t < s.start_s; });
  if (it == segments_.begin()) return 0;
  return static_cast<std::size_t>(it - segments_.begin()) - 1;
}

Truth ScheduleTruth::rotating(std::size_t i, double s) const {
  const Rotation& r = rotation_[i];
  const double d = segments_[i].end_s - segments_[i].start_s;
  const double x = std::clamp(s / d, 0.0, 1.0);
  const double phi = r.angle * (x - std::sin(2 * kPi * x) / (2 * kPi));
  const double rate = r.angle / d * (1 - std::cos(2 * kPi * x));
  const Eigen::Matrix3d c = r.start * Eigen::AngleAxisd(phi, r.axis).toRotationMatrix();
  return {r.axis * rate + c.transpose() * earth_rate_n_, c.transpose() * specific_force_n_};
}

Truth ScheduleTruth::at(double t_s) const {
  const std::size_t i = find(t_s);
  const ScheduleSegment& seg = segments_[i];
  if (!seg.rotating || t_s >= seg.end_s) {
    // Static, or past the end of the last segment (which is always a dwell).
    const int position = seg.rotating ? seg.position + 1 : seg.position;
    return static_truth_[static_cast<std::size_t>(position)];
  }
  return rotating(i, t_s - seg.start_s);
}

Truth ScheduleTruth::mean_in(std::size_t i, double a, double b) const {
  const ScheduleSegment& seg = segments_[i];
  if (!seg.rotating) return static_truth_[static_cast<std::size_t>(seg.position)];
  Truth sum;
  const double half = (b - a) / 2, mid = (a + b) / 2;
  for (std::size_t q = 0; q < kGaussNodes.size(); ++q) {
    const Truth v = rotating(i, mid + half * kGaussNodes[q] - seg.start_s);
    sum.angular_rate += kGaussWeights[q] / 2 * v.angular_rate;
    sum.specific_force += kGaussWeights[q] / 2 * v.specific_force;
  }
  return sum;
}

Truth ScheduleTruth::mean(double t0_s, double t1_s) const {
  Truth sum;
  double a = t0_s;
  const auto add = [&](const Truth& v, double w) {
    sum.angular_rate += w * v.angular_rate;
    sum.specific_force += w * v.specific_force;
  };
  if (a < 0) {  // before the schedule: the first position
    const double b = std::min(t1_s, 0.0);
    add(static_truth_.front(), b - a);
    a = b;
  }
  for (std::size_t i = find(a); a < t1_s && i < segments_.size(); ++i) {
    const double b = std::min(t1_s, segments_[i].end_s);
    if (b > a) add(mean_in(i, a, b), b - a);
    a = std::max(a, b);
  }
  if (a < t1_s) add(static_truth_.back(), t1_s - a);  // after the end: the last position
  const double w = 1 / (t1_s - t0_s);
  return {sum.angular_rate * w, sum.specific_force * w};
}

}  // namespace detail

std::vector<ScheduleSegment> schedule_timeline(const Schedule& schedule) {
  return detail::ScheduleTruth(schedule).timeline();
}

double schedule_duration_s(const Schedule& schedule) {
  return detail::ScheduleTruth(schedule).duration_s();
}

Truth schedule_truth(const Schedule& schedule, double t_s) {
  return detail::ScheduleTruth(schedule).at(t_s);
}

Schedule calibration_schedule(int count, double dwell_s, double rotation_rate_rad_s,
                              double latitude_rad) {
  if (count < 1) throw Error("calibration schedule: needs at least one position");
  if (!(dwell_s > 0) || !(rotation_rate_rad_s > 0))
    throw Error("calibration schedule: dwell and rotation rate must be > 0");
  Schedule s;
  s.rotation_rate_rad_s = rotation_rate_rad_s;
  s.latitude_rad = latitude_rad;
  for (int i = 0; i < count; ++i) {
    // Down direction in the body frame d = C^T e_z = (-sin p, sin r cos p, cos r cos p).
    const double z = 1 - (2.0 * i + 1) / count;
    const double r = std::sqrt(std::max(0.0, 1 - z * z));
    const double azimuth = i * kGoldenAngle;
    const Eigen::Vector3d d(r * std::cos(azimuth), r * std::sin(azimuth), z);
    SchedulePosition p;
    p.pitch_rad = std::asin(std::clamp(-d.x(), -1.0, 1.0));
    p.roll_rad = std::atan2(d.y(), d.z());
    p.yaw_rad = std::remainder(i * kGoldenAngle, 2 * kPi);
    p.dwell_s = dwell_s;
    s.positions.push_back(p);
  }
  return s;
}

double temperature_at(const TemperatureProfile& profile, double t_s) {
  const auto& p = profile.points;
  if (p.empty()) throw Error("temperature profile: no points");
  const auto it = std::upper_bound(p.begin(), p.end(), t_s,
                                   [](double t, const TemperaturePoint& q) { return t < q.t_s; });
  if (it == p.begin()) return p.front().temperature_k;
  if (it == p.end()) return p.back().temperature_k;
  const TemperaturePoint& a = *(it - 1);
  const TemperaturePoint& b = *it;
  return a.temperature_k + (b.temperature_k - a.temperature_k) * (t_s - a.t_s) / (b.t_s - a.t_s);
}

double mean_temperature(const TemperatureProfile& profile, double t0_s, double t1_s) {
  if (!(t1_s > t0_s)) return temperature_at(profile, t0_s);
  // Exact integral of the piecewise-linear profile: trapezoids between the breakpoints inside.
  double integral = 0, a = t0_s, ta = temperature_at(profile, t0_s);
  for (const auto& q : profile.points) {
    if (q.t_s <= a) continue;
    if (q.t_s >= t1_s) break;
    // The value just before the breakpoint (a step's left value is the previous segment's end).
    const double left = temperature_at(profile, std::nextafter(q.t_s, a));
    integral += (ta + left) / 2 * (q.t_s - a);
    a = q.t_s;
    ta = temperature_at(profile, q.t_s);
  }
  integral += (ta + temperature_at(profile, t1_s)) / 2 * (t1_s - a);
  return integral / (t1_s - t0_s);
}

}  // namespace sigmatau
