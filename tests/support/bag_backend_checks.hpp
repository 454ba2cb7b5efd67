#pragma once
// Helpers of the ROS 2 backend tests (test_bag_mcap, test_bag_rosbag2): read a topic through the
// internal BagBackend interface and compare it with the values the writer was given.
#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "../../lib/src/bag_backend.hpp"  // internal interface under test
#include "ros2_bag_writer.hpp"

namespace sigmatau::test {

/// Every message of `topic`, in file order.
inline std::vector<detail::ImuSample> read_all(detail::BagBackend& bag, const std::string& topic) {
  REQUIRE(bag.select(topic));
  std::vector<detail::ImuSample> out;
  detail::ImuSample s;
  while (bag.next(s)) out.push_back(s);
  return out;
}

/// Stamps and values equal bit for bit (==, no tolerance: the reader copies the float64 of the
/// message unchanged, so any difference is a decoding bug).
inline void check_same(const std::vector<detail::ImuSample>& got, const std::vector<ImuValue>& want) {
  REQUIRE(got.size() == want.size());
  for (std::size_t i = 0; i < want.size(); ++i) {
    INFO("message " << i);
    CHECK(got[i].header_ns == want[i].header_ns);
    CHECK(got[i].receive_ns == want[i].receive_ns);
    for (int k = 0; k < 3; ++k) {
      CHECK(got[i].gyro[k] == want[i].gyro[k]);
      CHECK(got[i].accel[k] == want[i].accel[k]);
    }
  }
}

}  // namespace sigmatau::test
