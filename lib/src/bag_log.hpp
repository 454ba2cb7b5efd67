#pragma once
// Internal: a ROS bag behind LogReader. Opens the right backend (ROS 1 bag, MCAP, rosbag2 SQLite
// or a rosbag2 folder), picks the sensor_msgs/Imu topic, restores stamp order within the reorder
// window and fills SampleBlock rows (channels gx gy gz ax ay az, t_s from the chosen stamp).
//
// Time: t_s counts from the stamp of the first message delivered, t_s = (stamp_ns - first_ns) /
// 1e9, so that int64 nanosecond epoch stamps keep nanosecond resolution in the double (exact for
// the first 2^53 ns = 104 days of a bag). The TimingAccumulator is fed the same relative integer
// nanoseconds, so its intervals are exact and its gap start times match t_s.
#include <cstdint>
#include <deque>
#include <memory>
#include <string>
#include <vector>

#include "bag_backend.hpp"
#include "log_internal.hpp"

namespace sigmatau::detail {

/// Largest LogOptions::reorder_window accepted [messages]: 10^7 x about 90 bytes = 0.9 GB would
/// already be the whole memory budget of a bag read; a larger value is a typo.
constexpr std::int64_t kMaxReorderWindow = 10000000;

/// The backend for `path` (magic bytes first, then extension, or a rosbag2 folder). Throws Error
/// when the path is not a bag or cannot be opened, ParseError when its start is corrupt.
std::unique_ptr<BagBackend> open_bag(const std::string& path);

class BagLog {
 public:
  /// Opens the bag, chooses the topic and the channels. Throws Error for options that do not
  /// apply to a bag, an unknown channel, an absent or ambiguous topic (listing the topics).
  BagLog(const LogOptions& options, TimingAccumulator& timing);
  ~BagLog();

  const ColumnSelection& selection() const { return selection_; }
  const std::string& topic() const { return topic_; }
  /// The bag's topics as listed when no topic was asked for and the only sensor_msgs/Imu topic
  /// was picked (counts -1 where the bag does not state them); empty when a topic was given.
  /// Once the bag is read to its end, the topic's count is the messages found in it.
  const std::vector<BagTopic>& topics_listed() const { return listed_; }
  /// What the reading met that did not stop it (TimingReport::warnings): messages on an
  /// undeclared connection or channel, a topic whose stated count differs from the messages
  /// found (once read to the end).
  std::vector<std::string> warnings() const;

  /// Appends up to max_rows rows to `block` (values sized to the channels, t_s). Returns the
  /// count, 0 at the end. Throws ParseError on corrupt data, a message later than the reorder
  /// window allows, or a non-finite value under NonFinitePolicy::error.
  std::int64_t read_rows(SampleBlock& block, std::int64_t max_rows);

  /// The topic's message count as the bag states it (its index or summary, or a counting scan
  /// of a bag without one that has been made anyway); -1 when unknown.
  std::int64_t messages_stated() const { return stated_; }
  std::int64_t reordered_samples() const { return reordered_; }
  double max_reorder_s() const { return static_cast<double>(max_reorder_ns_) / 1e9; }
  /// Where the recording was cut short (at_byte -1 when it was not, or not yet met); only
  /// under TruncatedPolicy::use, as the other policy throws.
  const BagCut& cut() const { return backend_->cut(); }
  std::int64_t bytes_read() const { return backend_->bytes_read(); }
  std::int64_t total_bytes() const { return backend_->total_bytes(); }

 private:
  struct Pending {
    std::int64_t key_ns;  // the chosen stamp
    std::uint64_t seq;    // arrival order, so that equal stamps keep it
    ImuSample sample;
  };
  bool pull(ImuSample& out);
  void admit(const ImuSample& in);
  std::int64_t key(const ImuSample& s) const;
  [[noreturn]] void fail_nonfinite(const ImuSample& s) const;
  /// At the end of a bag read through: the topic's listed count becomes the messages found,
  /// and count_note_ says so when the bag stated another count.
  void count_found();
  /// Under TruncatedPolicy::error, a cut met by the backend is a ParseError naming it, with the
  /// `complete` messages of the topic before it (-1: not known) and how to use them.
  void check_cut(std::int64_t complete) const;

  std::string file_;
  std::unique_ptr<BagBackend> backend_;
  TimingAccumulator& timing_;
  NonFinitePolicy nonfinite_;
  BagStamp stamp_;
  TruncatedPolicy truncated_;
  std::string topic_;
  std::vector<BagTopic> listed_;
  std::int64_t stated_ = -1;  // messages of the topic the bag states (index, summary), or -1
  std::string count_note_;    // stated_ against the messages found, when they differ
  ColumnSelection selection_;
  std::vector<int> fields_;  // per channel: 0..2 gyro, 3..5 accel
  // Reorder window: at most window_ + 1 messages sorted on (key_ns, seq).
  std::size_t window_ = 0;
  std::deque<Pending> pending_;
  std::uint64_t seq_ = 0;
  bool eof_ = false;
  bool emitted_ = false;
  std::int64_t last_emitted_ns_ = 0;
  bool seen_ = false;
  std::int64_t max_seen_ns_ = 0;
  std::int64_t reordered_ = 0;
  std::int64_t max_reorder_ns_ = 0;
  std::int64_t first_ns_ = 0;
};

}  // namespace sigmatau::detail
