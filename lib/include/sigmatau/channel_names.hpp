#pragma once
/// \file channel_names.hpp
/// What a log's column names say about the sensor and axis they hold: the one rule every verb,
/// the compliance reader and the filter exports use (gx / gyro_x / angular_velocity_x is a gyro
/// axis, ax / accel_x / linear_acceleration_x an accelerometer axis).

#include <optional>
#include <string_view>

#include "sigmatau/noise_model.hpp"

namespace sigmatau {

/// Which sensor and axis a column holds, from its name: gx / gyro_x / wx / omega_x /
/// angular_velocity_x / rate_x -> gyro; ax / acc_x / accel_x / linear_acceleration_x / fx ->
/// accel (case-insensitive); the last letter x / y / z is the axis. nullopt for anything else
/// (temperature, time, counters, angle_x, gps_x).
struct ChannelRole {
  Sensor sensor = Sensor::gyro;
  int axis = 0;  ///< 0 x, 1 y, 2 z
};
std::optional<ChannelRole> classify_channel(std::string_view name);

}  // namespace sigmatau
