// ROS bags behind LogReader: backend choice, topic choice, the reorder window, SampleBlock rows.
//
// Reorder window (W = LogOptions::reorder_window messages): arriving messages are kept sorted on
// (stamp, arrival number) in a deque; once it holds W + 1 messages the first (smallest) is
// delivered. A message in order (the common case) is appended in O(1); a late one is inserted
// at its place (binary search, then a shift of the later messages: O(W), rare). A min-heap did
// the same at O(log W) per message and cost a quarter of the reading time. A message
// whose stamp is below the last one delivered came too late to be put back in order: ParseError
// naming its location. A stamp below the largest seen so far counts as reordered (and its
// lateness in max_reorder_s). Equal stamps keep their arrival order (the arrival number breaks
// ties), so duplicates reach the TimingAccumulator as duplicates.
#include "bag_log.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "sigmatau/error.hpp"

namespace sigmatau::detail {
namespace {

constexpr std::string_view kRos1Magic = "#ROSBAG V2.0";
/// MCAP magic (mcap.dev/spec): 0x89 "MCAP" '0' "\r\n".
constexpr std::string_view kMcapMagic = "\x89MCAP0\r\n";
/// SQLite file header (sqlite.org/fileformat.html, section 1.3.1): "SQLite format 3" and a NUL.
constexpr std::string_view kSqliteMagic{"SQLite format 3\0", 16};
/// The six channels of a sensor_msgs/Imu, in ImuSample order (gyro[0..2], accel[0..2]).
constexpr const char* kChannelNames[6] = {"gx", "gy", "gz", "ax", "ay", "az"};

enum class Kind { none, ros1, mcap, sqlite, folder };

bool ends_with(const std::string& s, std::string_view suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

Kind kind_of(const std::string& path) {
  if (path.empty() || path == "-") return Kind::none;
  struct stat st {};
  const bool exists = ::stat(path.c_str(), &st) == 0;
  if (exists && S_ISDIR(st.st_mode)) {
    std::ifstream meta(path + "/metadata.yaml");
    return meta.good() ? Kind::folder : Kind::none;
  }
  char head[16] = {};
  std::streamsize got = 0;
  if (exists && S_ISREG(st.st_mode)) {  // never read from a pipe: its bytes would be lost
    std::ifstream in(path, std::ios::binary);
    if (in) {
      in.read(head, sizeof head);
      got = in.gcount();
    }
  }
  const std::string_view start(head, static_cast<std::size_t>(got));
  if (start.substr(0, kRos1Magic.size()) == kRos1Magic) return Kind::ros1;
  if (start.substr(0, kMcapMagic.size()) == kMcapMagic) return Kind::mcap;
  if (start == kSqliteMagic) return Kind::sqlite;
  if (ends_with(path, ".bag")) return Kind::ros1;
  if (ends_with(path, ".mcap")) return Kind::mcap;
  if (ends_with(path, ".db3")) return Kind::sqlite;
  return Kind::none;
}

std::string format_count(std::int64_t n) {
  return n < 0 ? std::string("count unknown") : std::to_string(n) + (n == 1 ? " message" : " messages");
}

/// "/imu/data (sensor_msgs/Imu, 1200 messages), /tf (tf2_msgs/TFMessage, 40 messages)".
std::string topic_list(const std::vector<BagTopic>& topics) {
  if (topics.empty()) return "none";
  std::string out;
  for (const BagTopic& t : topics) {
    if (!out.empty()) out += ", ";
    out += t.name + " (" + t.type + ", " + format_count(t.messages) + ")";
  }
  return out;
}

/// The sensor_msgs/Imu topics of a listing: the one a reader without --topic reads when there
/// is exactly one.
std::vector<const BagTopic*> imu_topics(const std::vector<BagTopic>& topics) {
  std::vector<const BagTopic*> imu;
  for (const BagTopic& t : topics) {
    if (is_imu_type(t.type)) imu.push_back(&t);
  }
  return imu;
}

/// The message count a listing states for topic `name`; -1 when it has no such topic or
/// states no count.
std::int64_t stated_messages(const std::vector<BagTopic>& topics, const std::string& name) {
  for (const BagTopic& t : topics) {
    if (t.name == name) return t.messages;
  }
  return -1;
}

std::string location(const ImuSample& s) {
  if (s.id >= 0) return "message with row id " + std::to_string(s.id);
  return "message at byte offset " + std::to_string(s.offset) +
         " (of its record or compressed chunk)";
}

std::string format_ns(std::int64_t ns) {
  char text[64];
  std::snprintf(text, sizeof text, "%.9g s", static_cast<double>(ns) * 1e-9);
  return text;
}

}  // namespace

std::unique_ptr<BagBackend> open_bag(const std::string& path) {
  switch (kind_of(path)) {
    case Kind::ros1:
      return open_ros1_bag(path);
    case Kind::mcap:
      return open_mcap(path);
    case Kind::sqlite:
      return open_rosbag2_sqlite(path);
    case Kind::folder:
      return open_rosbag2_folder(path);
    case Kind::none:
      break;
  }
  throw Error(path + ": not a ROS bag (no ROS 1 bag, MCAP or SQLite magic bytes, no .bag, .mcap "
                     "or .db3 extension, not a folder with metadata.yaml)");
}

void BagBackend::cut_short(const std::string& file, std::int64_t at_byte,
                           const std::string& detail) {
  if (!cut_allowed_) {
    throw ParseError(file, 0, 0, detail + " (the recording was cut short, or the length is corrupt)");
  }
  cut_ = BagCut{file, at_byte, detail};
}

void add_topic(std::vector<BagTopic>& list, const std::string& name, const std::string& type,
               std::int64_t messages, bool with_counts) {
  auto it = std::find_if(list.begin(), list.end(), [&](const BagTopic& t) { return t.name == name; });
  if (it == list.end()) {
    list.push_back({name, type, with_counts ? 0 : -1});
    it = list.end() - 1;
  }
  if (with_counts) it->messages += messages;
}

void sort_topics(std::vector<BagTopic>& list) {
  std::sort(list.begin(), list.end(),
            [](const BagTopic& a, const BagTopic& b) { return a.name < b.name; });
}

[[noreturn]] void throw_missing_topic(const std::string& file, const std::string& topic,
                                      const std::vector<BagTopic>& topics) {
  std::string names;
  for (const BagTopic& t : topics) names += (names.empty() ? "" : ", ") + t.name + " (" + t.type + ")";
  throw ParseError(file, 0, 0,
                   "no topic " + topic + " in the bag; its topics: " +
                       (names.empty() ? std::string("none") : names));
}

[[noreturn]] void throw_wrong_type(const std::string& file, const std::string& where,
                                   const std::string& topic, const std::string& type) {
  throw ParseError(file, 0, 0,
                   where + ": topic " + topic + " has type " + type +
                       ", expected sensor_msgs/Imu (choose an Imu topic with --topic)");
}

[[noreturn]] void throw_bad_message(const std::string& file, const std::string& where,
                                    const std::string& topic, std::size_t n,
                                    const DecodeError& error) {
  std::string message = where + ": " + std::to_string(n) + "-byte message on " + topic +
                        " is not a sensor_msgs/Imu: " + (error.reason ? error.reason : "undecodable");
  if (error.expected > 0) message += " (expected " + std::to_string(error.expected) + " bytes)";
  throw ParseError(file, 0, 0, message);
}

BagLog::BagLog(const LogOptions& options, TimingAccumulator& timing)
    : file_(options.path),
      timing_(timing),
      nonfinite_(options.nonfinite),
      stamp_(options.stamp),
      truncated_(options.truncated) {
  if (!options.time_column.empty()) {
    throw Error(file_ + ": a ROS bag has its own time stamps; drop the time column (\"" +
                options.time_column + "\") and choose the stamp with --stamp header|receive");
  }
  if (options.binary != BinaryFormat::none || options.skip_bytes != 0) {
    throw Error(file_ + ": the binary options (--binary, --channels, --skip-bytes) do not apply "
                        "to a ROS bag");
  }
  if (!(options.reorder_window >= 0 && options.reorder_window <= kMaxReorderWindow)) {
    throw Error("reorder window must be in 0.." + std::to_string(kMaxReorderWindow) +
                " messages, got " + std::to_string(options.reorder_window));
  }
  window_ = static_cast<std::size_t>(options.reorder_window);

  // Channels first: a typo is reported before the bag is read.
  const std::vector<std::string> wanted =
      options.columns.empty() ? std::vector<std::string>(std::begin(kChannelNames),
                                                         std::end(kChannelNames))
                              : options.columns;
  for (const std::string& name : wanted) {
    const auto* it = std::find(std::begin(kChannelNames), std::end(kChannelNames), name);
    if (it == std::end(kChannelNames)) {
      throw Error(file_ + ": unknown channel \"" + name +
                  "\" for a sensor_msgs/Imu topic (available: gx, gy, gz, ax, ay, az)");
    }
    const int field = static_cast<int>(it - std::begin(kChannelNames));
    if (std::find(fields_.begin(), fields_.end(), field) != fields_.end()) {
      throw Error(file_ + ": channel \"" + name + "\" is selected twice");
    }
    fields_.push_back(field);
    selection_.channel_columns.push_back(field);
    selection_.channel_names.push_back(name);
  }
  selection_.has_time = true;

  backend_ = open_bag(file_);
  backend_->allow_cut();  // check_cut applies the policy, with the topic's count in the message
  topic_ = options.topic;
  if (topic_.empty()) {
    const std::vector<BagTopic> topics = backend_->topics(false);
    const std::vector<const BagTopic*> imu = imu_topics(topics);
    if (imu.size() != 1) {
      check_cut(-1);  // under TruncatedPolicy::error the cut explains a missing topic first
      const BagCut& cut = backend_->cut();
      const std::string before_cut =
          cut.at_byte >= 0 ? " before the cut at byte " + std::to_string(cut.at_byte) : "";
      throw Error(file_ + ": " +
                  (imu.empty() ? "no sensor_msgs/Imu topic in the bag" + before_cut
                               : std::to_string(imu.size()) + " sensor_msgs/Imu topics" +
                                     before_cut + "; choose one with --topic") +
                  "; its topics: " + topic_list(backend_->topics(true)));
    }
    topic_ = imu.front()->name;
    listed_ = topics;
  }
  if (!backend_->select(topic_)) {
    throw Error(file_ + ": no topic " + topic_ + " in the bag; its topics: " +
                topic_list(backend_->topics(true)));
  }
  if (backend_->cut().at_byte >= 0) {  // met by a counting scan: the counts are of the prefix
    check_cut(stated_messages(backend_->topics(false), topic_));
  } else {
    // The counts known without reading the messages (an index, a summary, or the scan that
    // picking the topic made): asking topics() here would make an unindexed bag read twice.
    stated_ = stated_messages(backend_->indexed_topics(), topic_);
  }
  timing_.set_policy(options.gaps, file_);
  timing_.start(true, TimeUnit::ns);
}

void BagLog::check_cut(std::int64_t complete) const {
  const BagCut& cut = backend_->cut();
  if (cut.at_byte < 0 || truncated_ == TruncatedPolicy::use) return;
  throw ParseError(cut.file, 0, 0,
                   cut.detail + ": the recording was cut short at byte " +
                       std::to_string(cut.at_byte) +
                       (complete >= 0 ? " after " + std::to_string(complete) +
                                            " complete message" + (complete == 1 ? "" : "s") +
                                            " of " + topic_
                                      : std::string()) +
                       " (its recorder stopped without closing the file); give --truncated use "
                       "to analyse the complete messages before it");
}

BagLog::~BagLog() = default;

std::int64_t BagLog::key(const ImuSample& s) const {
  return stamp_ == BagStamp::header ? s.header_ns : s.receive_ns;
}

void BagLog::admit(const ImuSample& in) {
  const std::int64_t k = key(in);
  if (emitted_ && k < last_emitted_ns_) {
    throw ParseError(file_, 0, 0,
                     location(in) + " on " + topic_ + ": its " +
                         (stamp_ == BagStamp::header ? "header" : "receive") + " stamp is " +
                         format_ns(max_seen_ns_ - k) +
                         " before the latest stamp seen: it arrived more messages late than the "
                         "reorder window (" + std::to_string(window_) +
                         " messages) can put back in order; raise --reorder-window or try "
                         "--stamp " + (stamp_ == BagStamp::header ? "receive" : "header"));
  }
  if (seen_ && k < max_seen_ns_) {
    ++reordered_;
    max_reorder_ns_ = std::max(max_reorder_ns_, max_seen_ns_ - k);
  }
  if (!seen_ || k > max_seen_ns_) max_seen_ns_ = k;
  seen_ = true;
  // The newcomer has the largest arrival number: it goes after every pending stamp <= its own.
  if (pending_.empty() || pending_.back().key_ns <= k) {
    pending_.push_back({k, seq_++, in});
  } else {
    const auto at = std::upper_bound(pending_.begin(), pending_.end(), k,
                                     [](std::int64_t key, const Pending& p) { return key < p.key_ns; });
    pending_.insert(at, {k, seq_++, in});
  }
}

bool BagLog::pull(ImuSample& out) {
  while (!eof_ && pending_.size() <= window_) {
    ImuSample in;
    if (!backend_->next(in)) {
      eof_ = true;
      check_cut(static_cast<std::int64_t>(seq_));
      if (backend_->cut().at_byte < 0) count_found();
      break;
    }
    admit(in);
  }
  if (pending_.empty()) return false;
  out = pending_.front().sample;
  last_emitted_ns_ = pending_.front().key_ns;
  pending_.pop_front();
  if (!emitted_) first_ns_ = last_emitted_ns_;
  emitted_ = true;
  return true;
}

void BagLog::count_found() {
  const auto found = static_cast<std::int64_t>(seq_);
  for (BagTopic& t : listed_) {
    if (t.name == topic_ && t.messages >= 0) t.messages = found;
  }
  if (stated_ < 0 || stated_ == found) return;
  count_note_ = "the bag states " + format_count(stated_) + " on " + topic_ + ", but " +
                std::to_string(found) + " were found in it and read";
}

std::vector<std::string> BagLog::warnings() const {
  std::vector<std::string> out;
  if (!backend_->undeclared_note().empty()) out.push_back(backend_->undeclared_note());
  if (!count_note_.empty()) out.push_back(count_note_);
  return out;
}

void BagLog::fail_nonfinite(const ImuSample& s) const {
  for (std::size_t c = 0; c < fields_.size(); ++c) {
    const int f = fields_[c];
    const double v = f < 3 ? s.gyro[f] : s.accel[f - 3];
    if (!std::isfinite(v)) {
      throw ParseError(file_, 0, 0,
                       "non-finite value (NaN or Inf) in channel " + selection_.channel_names[c] +
                           " of the " + location(s) + " on " + topic_);
    }
  }
  throw std::logic_error("fail_nonfinite: no non-finite value");
}

std::int64_t BagLog::read_rows(SampleBlock& block, std::int64_t max_rows) {
  const std::size_t channels = fields_.size();
  std::int64_t rows = 0;
  ImuSample s;
  double row[6];
  while (rows < max_rows && pull(s)) {
    bool finite = true;
    for (std::size_t c = 0; c < channels; ++c) {
      const int f = fields_[c];
      row[c] = f < 3 ? s.gyro[f] : s.accel[f - 3];
      finite &= std::isfinite(row[c]);
    }
    if (!finite) {
      if (nonfinite_ == NonFinitePolicy::skip_row) {
        timing_.add_skipped();
        continue;
      }
      fail_nonfinite(s);
    }
    const TimeStamp stamp{key(s) - first_ns_, 0.0};
    timing_.add(stamp, 0);  // before the row enters the block: a throw leaves whole rows only
    for (std::size_t c = 0; c < channels; ++c) block.values[c].push_back(row[c]);
    block.t_s.push_back(timing_.seconds(stamp));
    ++rows;
  }
  return rows;
}

}  // namespace sigmatau::detail

namespace sigmatau {

BagStamp parse_bag_stamp(std::string_view text) {
  if (text == "header") return BagStamp::header;
  if (text == "receive") return BagStamp::receive;
  throw Error("unknown bag stamp \"" + std::string(text) + "\" (expected header or receive)");
}

bool is_bag_path(const std::string& path) { return detail::kind_of(path) != detail::Kind::none; }

std::vector<BagTopic> list_bag_topics(const std::string& path) {
  return detail::open_bag(path)->topics(true);
}

std::int64_t indexed_bag_messages(const std::string& path, const std::string& topic) {
  const std::vector<BagTopic> listed = detail::open_bag(path)->indexed_topics();
  if (!topic.empty()) return detail::stated_messages(listed, topic);
  // Without a topic the reader takes the only Imu topic (and asks which one among several).
  const std::vector<const BagTopic*> imu = detail::imu_topics(listed);
  return imu.size() == 1 ? imu.front()->messages : -1;
}

}  // namespace sigmatau
