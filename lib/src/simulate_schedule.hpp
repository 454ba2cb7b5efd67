#pragma once
// Internal: the truth of a multi-position schedule and a temperature profile, evaluated at a time
// or averaged over a sample interval (simulate.hpp file comment).
#include <Eigen/Core>

#include <vector>

#include "sigmatau/simulate.hpp"

namespace sigmatau::detail {

class ScheduleTruth {
 public:
  explicit ScheduleTruth(const Schedule& schedule);  ///< validates; throws Error
  const std::vector<ScheduleSegment>& timeline() const { return segments_; }
  double duration_s() const;
  Truth at(double t_s) const;
  /// Mean of the truth over [t0, t1] (t0 < t1).
  Truth mean(double t0_s, double t1_s) const;

 private:
  struct Rotation {
    Eigen::Matrix3d start = Eigen::Matrix3d::Identity();  // body-to-NED attitude at the start
    Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();      // unit rotation axis (body frame)
    double angle = 0;       // theta [rad]
  };
  Truth rotating(std::size_t segment, double s) const;
  Truth mean_in(std::size_t segment, double a, double b) const;
  std::size_t find(double t_s) const;

  std::vector<ScheduleSegment> segments_;
  std::vector<Truth> static_truth_;  // per position
  std::vector<Rotation> rotation_;   // per segment (only used for rotating ones)
  Eigen::Vector3d earth_rate_n_;
  Eigen::Vector3d specific_force_n_;
};

}  // namespace sigmatau::detail
