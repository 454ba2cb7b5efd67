// libFuzzer harness: the ROS bag readers (ROS 1 bag, MCAP, rosbag2 SQLite) behind LogReader. The
// first byte chooses the file name extension (so that input without magic bytes still reaches a
// bag reader), the stamp, the non-finite and gap policies, the reorder window and whether the
// topic is named; the rest is the file. list_bag_topics runs on it too.
#include "fuzz_common.hpp"

namespace {
/// Scratch files with a bag extension: <pid>.bag, .mcap, .db3.
const std::string& bag_scratch(int kind) {
  static const std::string names[3] = {sigmatau::fuzz::scratch_file(".bag"),
                                       sigmatau::fuzz::scratch_file(".mcap"),
                                       sigmatau::fuzz::scratch_file(".db3")};
  return names[kind];
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace sigmatau;
  if (size < 1) return 0;
  const std::uint8_t flags = data[0];
  const int kind = (flags & 3) == 3 ? 0 : (flags & 3);
  const std::string& path = bag_scratch(kind);
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) __builtin_trap();
  if (size > 1 && std::fwrite(data + 1, 1, size - 1, f) != size - 1) __builtin_trap();
  std::fclose(f);
  LogOptions o;
  o.path = path;
  o.stamp = (flags & 4) ? BagStamp::receive : BagStamp::header;
  o.nonfinite = (flags & 8) ? NonFinitePolicy::skip_row : NonFinitePolicy::error;
  constexpr std::int64_t kWindows[4] = {0, 1, 4, 10000};
  o.reorder_window = kWindows[(flags >> 4) & 3];
  if (flags & 64) o.topic = "/imu/data";
  o.gaps = (flags & 128) ? GapPolicy::split : GapPolicy::report;
  fuzz::read_all(o);
  try {
    const auto topics = list_bag_topics(path);
    for (const auto& t : topics) {
      if (t.messages < -1) __builtin_trap();
    }
  } catch (const Error&) {
  }
  return 0;
}
