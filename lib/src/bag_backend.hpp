#pragma once
// Internal: what the three bag readers (rosbag1.cpp, mcap.cpp, rosbag2_sqlite.cpp) offer to
// bag_log.cpp, which picks the topic, restores stamp order and fills SampleBlocks.
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "cdr.hpp"
#include "sigmatau/log_reader.hpp"

namespace sigmatau::detail {

/// ROS 1 and ROS 2 names of the one message type read.
constexpr std::string_view kRos1ImuType = "sensor_msgs/Imu";
constexpr std::string_view kRos2ImuType = "sensor_msgs/msg/Imu";
inline bool is_imu_type(std::string_view type) {
  return type == kRos1ImuType || type == kRos2ImuType;
}

/// Where a recording was cut short: a file without an index or summary (its recorder died:
/// a crash, a full disk, Ctrl-C) that ends inside a record.
struct BagCut {
  std::string file;           ///< the file cut (one of a rosbag2 folder's files)
  std::int64_t at_byte = -1;  ///< byte offset of the first incomplete record; -1: not cut
  std::string detail;         ///< "truncated record at byte offset ...: ..." (what is missing)
};

/// One bag file (or a rosbag2 folder of them) delivering the IMU messages of one topic.
class BagBackend {
 public:
  virtual ~BagBackend() = default;
  /// From now on a recording cut short ends topics() and next() as a normal end would, after
  /// the complete records before the cut, and cut() says where. Without it (the default) a cut
  /// is a ParseError naming the record. A record running past the end of a file that has an
  /// index, summary or footer is corruption and stays a ParseError either way.
  virtual void allow_cut() { cut_allowed_ = true; }
  /// The cut met so far (at_byte -1 when none).
  virtual const BagCut& cut() const { return cut_; }
  /// The topics in the bag with their types; message counts when the bag states them, or when
  /// `need_counts` (which may read the whole bag), else -1.
  virtual std::vector<BagTopic> topics(bool need_counts) = 0;
  /// The topics as the bag's index or summary lists them (or a counting scan already made),
  /// with the message counts it states (-1 where it states none), without reading any message;
  /// empty when there is no such list (or a backend does not read one).
  virtual std::vector<BagTopic> indexed_topics() { return {}; }
  /// Reads only `topic` from now on. false when the bag has no such topic; ParseError when its
  /// type is not sensor_msgs/Imu, naming where the bag declares it.
  virtual bool select(const std::string& topic) = 0;
  /// The next message of the selected topic in file order (header_ns, receive_ns, values,
  /// location); false at the end. ParseError on corrupt data or a message that is no Imu.
  virtual bool next(ImuSample& sample) = 0;
  virtual std::int64_t bytes_read() const = 0;
  virtual std::int64_t total_bytes() const = 0;
  /// Messages met by next() on a connection (ROS 1) or channel (MCAP) that no record of the bag
  /// declares, so their topic is unknown: skipped, and said here ("" when there was none):
  /// "skipped N message(s) on connection 9, which no connection record declares ...".
  const std::string& undeclared_note() const { return undeclared_note_; }

 protected:
  /// A message on `kind` ("connection" or "channel") `id` that no record declares, at
  /// `location()` (called for the first one only): counted into undeclared_note().
  template <class Location>
  void count_undeclared(const char* kind, std::uint64_t id, const Location& location) {
    if (undeclared_++ == 0) first_undeclared_ = std::string(kind) + " " + std::to_string(id) +
                                                ", which no " + kind + " record declares (the "
                                                "first: " + location() + ")";
    undeclared_note_ = "skipped " + std::to_string(undeclared_) +
                       (undeclared_ == 1 ? " message on " : " messages on ") + first_undeclared_ +
                       ": its topic is unknown, the bag is corrupt there";
  }

  /// A backend met a cut at `at_byte` of `file`: records it when allowed, else throws
  /// ParseError "<detail> (the recording was cut short, or the length is corrupt)".
  void cut_short(const std::string& file, std::int64_t at_byte, const std::string& detail);

  bool cut_allowed_ = false;
  BagCut cut_;

 private:
  std::int64_t undeclared_ = 0;
  std::string first_undeclared_;
  std::string undeclared_note_;
};

std::unique_ptr<BagBackend> open_ros1_bag(const std::string& path);
std::unique_ptr<BagBackend> open_mcap(const std::string& path);
std::unique_ptr<BagBackend> open_rosbag2_sqlite(const std::string& path);
/// A rosbag2 recording folder: reads `dir`/metadata.yaml (storage sqlite3 or mcap, its files in
/// order, per-message zstd compression) and chains its files. Throws Error / ParseError naming
/// metadata.yaml (with line and column) or the file at fault; refuses file-level compression.
std::unique_ptr<BagBackend> open_rosbag2_folder(const std::string& dir);

/// Adds one connection / channel to `list`: several may share a topic, which is listed once
/// (with the first type seen); with `with_counts` their message counts add up, else the topic's
/// count stays -1 (unknown).
void add_topic(std::vector<BagTopic>& list, const std::string& name, const std::string& type,
               std::int64_t messages, bool with_counts);
/// Sorts a topic list by name (the order the topic listings print).
void sort_topics(std::vector<BagTopic>& list);
/// ParseError "no topic <topic> in the bag; its topics: <name (type), ...>" (or "none").
[[noreturn]] void throw_missing_topic(const std::string& file, const std::string& topic,
                                      const std::vector<BagTopic>& topics);

/// ParseError "<where>: topic <topic> has type <type>, expected sensor_msgs/Imu ...".
[[noreturn]] void throw_wrong_type(const std::string& file, const std::string& where,
                                   const std::string& topic, const std::string& type);
/// ParseError "<where>: <n>-byte message on <topic> is not a sensor_msgs/Imu: <reason>".
[[noreturn]] void throw_bad_message(const std::string& file, const std::string& where,
                                    const std::string& topic, std::size_t n,
                                    const DecodeError& error);

}  // namespace sigmatau::detail
