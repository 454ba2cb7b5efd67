#pragma once
// Internal: decoding one sensor_msgs/Imu message, in the ROS 1 serialization (little endian, no
// padding) or in CDR (the ROS 2 encoding: a 4-byte encapsulation header, then XCDR1 or XCDR2
// plain data, little or big endian).
//
// Layout of sensor_msgs/Imu after its std_msgs/Header (both encodings, 8-byte aligned in CDR):
// orientation (4 float64), orientation_covariance (9), angular_velocity (3),
// angular_velocity_covariance (9), linear_acceleration (3), linear_acceleration_covariance (9):
// 37 float64 = 296 bytes; angular_velocity at +104, linear_acceleration at +200.
// ROS 1 std_msgs/Header: uint32 seq, uint32 sec, uint32 nsec, uint32 length + frame_id bytes.
// ROS 2 std_msgs/Header: int32 sec, uint32 nanosec, uint32 length (with the NUL) + frame_id.
// CDR alignment counts from the end of the encapsulation header; XCDR2 aligns 8-byte values to 4
// only (OMG DDS-XTypes 1.3, section 7.4.1: MAXALIGN(XCDR2) = 4).
#include <bit>
#include <cstdint>
#include <cstring>

#include "bag_io.hpp"

namespace sigmatau::detail {

/// One IMU message as read from a bag.
struct ImuSample {
  std::int64_t header_ns = 0;   ///< header.stamp [ns since the epoch]
  std::int64_t receive_ns = 0;  ///< the recorder's receive time [ns since the epoch]
  double gyro[3] = {0, 0, 0};   ///< angular_velocity [rad/s]
  double accel[3] = {0, 0, 0};  ///< linear_acceleration [m/s^2]
  std::int64_t offset = -1;     ///< byte offset of the message record (or chunk) for messages
  std::int64_t id = -1;         ///< SQLite row id (rosbag2 .db3), else -1
};

/// Why a message did not decode: a fixed reason and, for size mismatches, the expected size.
struct DecodeError {
  const char* reason = nullptr;
  std::size_t expected = 0;
};

/// Bytes of the 37 float64 that follow the header in sensor_msgs/Imu.
constexpr std::size_t kImuBodyBytes = 37 * 8;
constexpr std::size_t kAngularVelocityAt = 13 * 8;
constexpr std::size_t kLinearAccelerationAt = 25 * 8;
/// Trailing bytes tolerated after a CDR message: writers may pad the payload to a multiple of 4
/// or 8 (the encapsulation options count padding); more is a different type.
constexpr std::size_t kMaxCdrPadding = 7;

template <bool kSwap>
inline double load_f64(const char* p) {
  std::uint64_t u;
  std::memcpy(&u, p, sizeof u);
  if constexpr (kSwap) u = __builtin_bswap64(u);
  return std::bit_cast<double>(u);
}
template <bool kSwap>
inline std::uint32_t load_u32(const char* p) {
  std::uint32_t u;
  std::memcpy(&u, p, sizeof u);
  if constexpr (kSwap) u = __builtin_bswap32(u);
  return u;
}

template <bool kSwap>
inline void load_imu_body(const char* body, ImuSample& s) {
  for (int k = 0; k < 3; ++k) {
    s.gyro[k] = load_f64<kSwap>(body + kAngularVelocityAt + 8 * k);
    s.accel[k] = load_f64<kSwap>(body + kLinearAccelerationAt + 8 * k);
  }
}

constexpr bool kNativeLittle = std::endian::native == std::endian::little;

/// Decodes a ROS 1 serialized sensor_msgs/Imu (fills header_ns and the values).
inline bool decode_ros1_imu(const char* p, std::size_t n, ImuSample& s, DecodeError& e) {
  if (n < 16) {
    e = {"too short for a std_msgs/Header", 16 + kImuBodyBytes};
    return false;
  }
  const std::uint32_t sec = load_le32(p + 4);
  const std::uint32_t nsec = load_le32(p + 8);
  const std::uint32_t len = load_le32(p + 12);
  if (len > n - 16 || n - 16 - len != kImuBodyBytes) {
    e = {"size does not match a sensor_msgs/Imu",
         len > n ? 16 + kImuBodyBytes : 16 + std::size_t{len} + kImuBodyBytes};
    return false;
  }
  s.header_ns = static_cast<std::int64_t>(sec) * 1000000000 + static_cast<std::int64_t>(nsec);
  load_imu_body<!kNativeLittle>(p + 16 + len, s);
  return true;
}

/// Decodes a CDR encoded sensor_msgs/msg/Imu (fills header_ns and the values).
inline bool decode_cdr_imu(const char* p, std::size_t n, ImuSample& s, DecodeError& e) {
  if (n < 4 + 12) {
    e = {"too short for a CDR std_msgs/Header", 4 + 12 + kImuBodyBytes};
    return false;
  }
  // Encapsulation identifiers (DDS-XTypes 1.3, 7.6.3.1.2): 0x0000 CDR_BE, 0x0001 CDR_LE,
  // 0x0006 PLAIN_CDR2_BE, 0x0007 PLAIN_CDR2_LE.
  const auto id = static_cast<unsigned char>(p[1]);
  if (p[0] != 0 || !(id == 0x00 || id == 0x01 || id == 0x06 || id == 0x07)) {
    e = {"unsupported CDR encapsulation (expected plain XCDR1 or XCDR2: 00 00, 00 01, 00 06 or "
         "00 07)",
         0};
    return false;
  }
  const bool little = (id & 1) != 0;
  const std::size_t max_align = id >= 0x06 ? 4 : 8;
  const char* b = p + 4;
  const std::size_t m = n - 4;
  const bool swap = little != kNativeLittle;
  const auto u32 = [&](const char* q) { return swap ? load_u32<true>(q) : load_u32<false>(q); };
  const auto sec = static_cast<std::int32_t>(u32(b));
  const std::uint32_t nsec = u32(b + 4);
  const std::uint32_t len = u32(b + 8);
  if (len > m - 12) {
    e = {"frame_id length runs past the end of the message", 0};
    return false;
  }
  std::size_t pos = 12 + std::size_t{len};
  pos = (pos + max_align - 1) / max_align * max_align;
  if (m < pos || m - pos < kImuBodyBytes || m - pos - kImuBodyBytes > kMaxCdrPadding) {
    e = {"size does not match a sensor_msgs/msg/Imu", 4 + pos + kImuBodyBytes};
    return false;
  }
  s.header_ns = static_cast<std::int64_t>(sec) * 1000000000 + static_cast<std::int64_t>(nsec);
  if (swap) {
    load_imu_body<true>(b + pos, s);
  } else {
    load_imu_body<false>(b + pos, s);
  }
  return true;
}

}  // namespace sigmatau::detail
