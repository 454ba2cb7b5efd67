// Internal: ROS 1 bag format 2.0 reader for sensor_msgs/Imu messages.
//
// Format (wiki.ros.org/Bags/Format/2.0): the magic "#ROSBAG V2.0\n", then records
//   <header_len u32><header: fields <len u32>name=value ...><data_len u32><data>,
// all little endian, the field "op" giving the kind: 0x02 message data (conn, time), 0x03 bag
// header (index_pos, conn_count, chunk_count), 0x04 index data, 0x05 chunk (compression "none",
// "bz2" or "lz4" [an lz4 frame], size = uncompressed bytes; its data holds connection and message
// records), 0x06 chunk info (ver, chunk_pos, start_time, end_time, count; data: count x (conn u32,
// messages u32)), 0x07 connection (conn, topic; data: the connection header, fields type,
// md5sum, message_definition, ...). A time is sec u32 then nsec u32.
// The index (connections and chunk infos at index_pos) is used when present. A bag whose
// recorder crashed has index_pos 0 (or one past its end): it is read by a sequential scan of its
// chunks. When such a bag ends inside a record, the recording was cut short: the records before
// the cut are read, and so are the complete messages of an uncompressed chunk the file ends
// inside (rosbag's default); a compressed chunk cut short is not used. The cut is reported by
// BagBackend::cut_short at the first incomplete record. An indexed bag ending inside a record is
// corrupt (rosbag writes index_pos last, when the bag is closed): always a ParseError.
#include <algorithm>
#include <unordered_map>

#include "bag_backend.hpp"
#include "sigmatau/error.hpp"

namespace sigmatau::detail {
namespace {

constexpr std::string_view kMagic = "#ROSBAG V2.0\n";
/// md5sum of sensor_msgs/Imu's definition, as rosbag stores it in each connection.
constexpr std::string_view kImuMd5 = "6a62c6daae103f4ff57a132d6f95cec2";
/// Largest record header accepted [bytes]: headers hold a handful of short fields (a connection
/// header's message_definition sits in the data); more is corruption.
constexpr std::uint32_t kMaxHeaderBytes = 1u << 20;
/// Largest data of a record outside chunks (connection, index) [bytes]: message definitions are a
/// few kB, an index record 12 bytes per message of a chunk.
constexpr std::uint32_t kMaxRecordDataBytes = 64u << 20;

enum Op : int { kMessage = 2, kBagHeader = 3, kIndex = 4, kChunk = 5, kChunkInfo = 6, kConn = 7 };

struct Fields {
  int op = -1;
  std::uint32_t conn = 0;
  bool has_conn = false;
  std::uint64_t time = 0;
  std::string_view compression;
  std::uint32_t size = 0;
  std::uint64_t index_pos = 0;
  std::uint64_t chunk_pos = 0;
  std::uint32_t count = 0;
  std::string_view topic, type, md5sum;
};

/// Parses the name=value fields of a record header (or a connection header). false when the
/// fields do not tile the header exactly.
bool parse_fields(const char* p, std::size_t n, Fields& f) {
  std::size_t i = 0;
  while (i < n) {
    if (n - i < 4) return false;
    const std::uint32_t len = load_le32(p + i);
    i += 4;
    if (len > n - i) return false;
    const std::string_view field(p + i, len);
    i += len;
    const std::size_t eq = field.find('=');
    if (eq == std::string_view::npos) return false;
    const std::string_view name = field.substr(0, eq);
    const std::string_view value = field.substr(eq + 1);
    const char* v = value.data();
    if (name == "op" && value.size() == 1) {
      f.op = static_cast<unsigned char>(v[0]);
    } else if (name == "conn" && value.size() == 4) {
      f.conn = load_le32(v);
      f.has_conn = true;
    } else if (name == "time" && value.size() == 8) {
      f.time = load_le64(v);
    } else if (name == "compression") {
      f.compression = value;
    } else if (name == "size" && value.size() == 4) {
      f.size = load_le32(v);
    } else if (name == "index_pos" && value.size() == 8) {
      f.index_pos = load_le64(v);
    } else if (name == "chunk_pos" && value.size() == 8) {
      f.chunk_pos = load_le64(v);
    } else if (name == "count" && value.size() == 4) {
      f.count = load_le32(v);
    } else if (name == "topic") {
      f.topic = value;
    } else if (name == "type") {
      f.type = value;
    } else if (name == "md5sum") {
      f.md5sum = value;
    }
  }
  return true;
}

std::int64_t ros_time_ns(std::uint64_t time) {
  const auto sec = static_cast<std::int64_t>(time & 0xffffffffu);
  const auto nsec = static_cast<std::int64_t>(time >> 32);
  return sec * 1000000000 + nsec;
}

struct Connection {
  std::string topic, type, md5sum;
  std::int64_t offset = 0;     // where the connection record is (file, or chunk + inner)
  std::int64_t messages = 0;   // from the chunk infos or a counting scan
};

struct ChunkInfo {
  std::uint64_t pos = 0;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> counts;  // (conn, messages)
};

class Ros1Bag final : public BagBackend {
 public:
  explicit Ros1Bag(const std::string& path) : file_(path) {
    const char* magic = file_.view(0, kMagic.size(), "ROS bag magic");
    if (std::string_view(magic, kMagic.size()) != kMagic) {
      throw ParseError(file_.name(), 0, 0,
                       "not a ROS 1 bag v2.0: byte offset 0 does not hold \"#ROSBAG V2.0\"");
    }
    std::int64_t pos = static_cast<std::int64_t>(kMagic.size());
    Fields f;
    std::int64_t data_at = 0;
    std::uint32_t data_len = 0;
    read_header(pos, f, data_at, data_len);
    if (f.op != kBagHeader) {
      throw ParseError(file_.name(), 0, 0,
                       "expected the bag header record (op 0x03) at " + at_offset(pos) +
                           ", found op " + std::to_string(f.op));
    }
    data_start_ = data_at + data_len;
    if (f.index_pos >= static_cast<std::uint64_t>(data_start_) &&
        f.index_pos < static_cast<std::uint64_t>(file_.size())) {
      read_index(static_cast<std::int64_t>(f.index_pos));
      indexed_ = true;
    }
  }

  std::vector<BagTopic> topics(bool need_counts) override {
    if (!indexed_ && !scanned_) {
      if (!need_counts && !conns_.empty()) return topic_list(false);
      scan_pass();
    }
    return topic_list(true);
  }

  std::vector<BagTopic> indexed_topics() override {
    return indexed_ || scanned_ ? topic_list(true) : std::vector<BagTopic>{};
  }

  bool select(const std::string& topic) override {
    topic_ = topic;
    selected_.clear();
    if (!indexed_ && !scanned_) return true;  // checked as connections appear (one pass)
    bool found = false;
    for (const auto& [id, c] : conns_) {
      if (c.topic != topic) continue;
      found = true;
      accept(id, c);
    }
    if (!found) return false;
    if (indexed_) {
      for (const ChunkInfo& ci : chunk_infos_) {
        for (const auto& [conn, n] : ci.counts) {
          if (n > 0 && is_selected(conn)) {
            chunks_.push_back(ci.pos);
            break;
          }
        }
      }
      std::sort(chunks_.begin(), chunks_.end());
    }
    return true;
  }

  bool next(ImuSample& s) override {
    while (true) {
      if (in_chunk_ < chunk_.size()) {
        if (next_in_chunk(s)) return true;
        continue;
      }
      if (!next_chunk()) {
        if (!indexed_ && !scanned_ && !seen_topic_)
          throw_missing_topic(file_.name(), topic_, topic_list(false));
        return false;
      }
    }
  }

  std::int64_t bytes_read() const override { return file_.bytes_read(); }
  std::int64_t total_bytes() const override { return file_.size(); }

 private:
  /// Reads the header of the record at `pos`: its fields, where its data starts and how long it
  /// is. With `may_cut` (an unindexed bag) a file ending inside the record is a cut: false after
  /// cut_short, except for an uncompressed chunk whose data alone is cut (true, `data_cut` set:
  /// its complete messages are read). Otherwise such a file is a ParseError.
  bool read_header(std::int64_t pos, Fields& f, std::int64_t& data_at, std::uint32_t& data_len,
                   bool may_cut = false, bool* data_cut = nullptr) {
    const std::int64_t remaining = file_.size() - pos;
    if (may_cut && remaining < 4) {
      cut_short(file_.name(), pos,
                "truncated record at " + at_offset(pos) + ": " + std::to_string(remaining) +
                    " bytes remain, less than a header length");
      return false;
    }
    const std::uint32_t header_len = load_le32(file_.view(pos, 4, "record header length"));
    if (header_len > kMaxHeaderBytes) bad_record(pos, "record header length " +
                                                          std::to_string(header_len) +
                                                          " is implausible");
    if (may_cut && remaining < std::int64_t{8} + header_len) {
      cut_short(file_.name(), pos,
                "truncated record at " + at_offset(pos) + ": its header needs " +
                    std::to_string(header_len + 8) + " bytes, the file ends at byte " +
                    std::to_string(file_.size()));
      return false;
    }
    const char* h = file_.view(pos + 4, header_len, "record header");
    f = Fields{};
    if (!parse_fields(h, header_len, f)) bad_record(pos, "record header fields are malformed");
    data_len = load_le32(file_.view(pos + 4 + header_len, 4, "record data length"));
    data_at = pos + 8 + header_len;
    if (static_cast<std::uint64_t>(data_at) + data_len > static_cast<std::uint64_t>(file_.size())) {
      const std::string detail = "truncated record at " + at_offset(pos) + ": its data needs " +
                                 std::to_string(data_len) + " bytes from byte " +
                                 std::to_string(data_at) + ", the file ends at byte " +
                                 std::to_string(file_.size());
      if (may_cut && data_len <= kMaxBagChunkBytes) {
        if (data_cut && f.op == kChunk && f.compression == "none") {
          *data_cut = true;
          return true;
        }
        cut_short(file_.name(), pos, detail);
        return false;
      }
      throw ParseError(file_.name(), 0, 0, detail);
    }
    return true;
  }

  [[noreturn]] void bad_record(std::int64_t pos, const std::string& why) const {
    throw ParseError(file_.name(), 0, 0, "corrupt record at " + at_offset(pos) + ": " + why);
  }

  void read_index(std::int64_t pos) {
    while (pos < file_.size()) {
      Fields f;
      std::int64_t data_at = 0;
      std::uint32_t data_len = 0;
      read_header(pos, f, data_at, data_len);
      if (data_len > kMaxRecordDataBytes) bad_record(pos, "index record data is implausibly long");
      if (f.op == kConn) {
        learn_connection(f, file_.view(data_at, data_len, "connection header"), data_len, pos);
      } else if (f.op == kChunkInfo) {
        const char* d = file_.view(data_at, data_len, "chunk info");
        if (std::uint64_t{f.count} * 8 != data_len) {
          bad_record(pos, "chunk info lists " + std::to_string(f.count) + " connections in " +
                              std::to_string(data_len) + " bytes");
        }
        ChunkInfo ci;
        ci.pos = f.chunk_pos;
        for (std::uint32_t i = 0; i < f.count; ++i) {
          const std::uint32_t conn = load_le32(d + 8 * i);
          const std::uint32_t n = load_le32(d + 8 * i + 4);
          ci.counts.emplace_back(conn, n);
          const auto it = conns_.find(conn);
          if (it != conns_.end()) it->second.messages += n;
          else pending_counts_[conn] += n;
        }
        chunk_infos_.push_back(std::move(ci));
      } else {
        bad_record(pos, "expected a connection (op 0x07) or chunk info (op 0x06) record in the "
                        "index, found op " + std::to_string(f.op));
      }
      pos = data_at + data_len;
    }
    for (auto& [conn, n] : pending_counts_) {
      const auto it = conns_.find(conn);
      if (it != conns_.end()) it->second.messages += n;
    }
  }

  void learn_connection(const Fields& header, const char* data, std::uint32_t n,
                        std::int64_t where) {
    if (!header.has_conn) bad_record(where, "connection record without a conn field");
    if (conns_.count(header.conn)) return;
    Fields h;
    if (!parse_fields(data, n, h)) bad_record(where, "connection header fields are malformed");
    Connection c;
    c.topic = std::string(header.topic.empty() ? h.topic : header.topic);
    c.type = std::string(h.type);
    c.md5sum = std::string(h.md5sum);
    c.offset = where;
    const auto pending = pending_counts_.find(header.conn);
    if (pending != pending_counts_.end()) {
      c.messages = pending->second;
      pending_counts_.erase(pending);
    }
    const auto& stored = conns_.emplace(header.conn, std::move(c)).first->second;
    if (!topic_.empty() && stored.topic == topic_ && !indexed_ && !scanned_) {
      accept(header.conn, stored);
    }
  }

  void accept(std::uint32_t id, const Connection& c) {
    if (!is_imu_type(c.type)) {
      throw_wrong_type(file_.name(), "connection record at " + at_offset(c.offset), c.topic,
                       c.type);
    }
    if (!c.md5sum.empty() && c.md5sum != "*" && c.md5sum != kImuMd5) {
      throw ParseError(file_.name(), 0, 0,
                       "connection record at " + at_offset(c.offset) + ": topic " + c.topic +
                           " has sensor_msgs/Imu md5sum " + c.md5sum + ", expected " +
                           std::string(kImuMd5) + " (a different definition of the message)");
    }
    seen_topic_ = true;
    if (!is_selected(id)) selected_.push_back(id);
  }

  bool is_selected(std::uint32_t conn) const {
    return std::find(selected_.begin(), selected_.end(), conn) != selected_.end();
  }

  std::vector<BagTopic> topic_list(bool with_counts) const {
    std::vector<BagTopic> list;
    for (const auto& [id, c] : conns_) add_topic(list, c.topic, c.type, c.messages, with_counts);
    sort_topics(list);
    return list;
  }

  /// Counts the messages of every connection by reading the whole (unindexed) bag.
  void scan_pass() {
    counting_ = true;
    ImuSample unused;
    while (next_chunk()) {
      while (in_chunk_ < chunk_.size()) next_in_chunk(unused);
    }
    counting_ = false;
    scanned_ = true;
    scan_pos_ = 0;
  }

  /// Loads the next chunk holding the selected topic (or any chunk while counting). false at the
  /// end of the bag.
  bool next_chunk() {
    if (cut_chunk_) {  // a cut chunk read to its last byte, which ended a record
      cut_chunk_ = false;
      cut_short(file_.name(), chunk_data_at_ + static_cast<std::int64_t>(chunk_.size()),
                "chunk at " + at_offset(chunk_pos_) + " cut short at byte " +
                    std::to_string(file_.size()) + " (its records before are complete)");
    }
    chunk_.clear();
    in_chunk_ = 0;
    while (true) {
      std::int64_t pos = 0;
      if (indexed_) {
        if (chunk_index_ >= chunks_.size()) return false;
        pos = static_cast<std::int64_t>(chunks_[chunk_index_++]);
      } else {
        if (scan_pos_ == 0) scan_pos_ = data_start_;
        if (scan_pos_ >= file_.size()) return false;
        pos = scan_pos_;
      }
      Fields f;
      std::int64_t data_at = 0;
      std::uint32_t data_len = 0;
      bool data_cut = false;
      if (!read_header(pos, f, data_at, data_len, !indexed_, &data_cut)) {
        scan_pos_ = file_.size();  // cut short here: nothing after it
        return false;
      }
      if (data_cut) {
        load_cut_chunk(pos, data_at);
        return true;
      }
      scan_pos_ = data_at + data_len;
      if (f.op == kConn && !indexed_) {
        if (data_len > kMaxRecordDataBytes) bad_record(pos, "connection header is too long");
        learn_connection(f, file_.view(data_at, data_len, "connection header"), data_len, pos);
        continue;
      }
      if (f.op != kChunk) {
        if (indexed_) {
          bad_record(pos, "the index points here for a chunk but the record has op " +
                              std::to_string(f.op));
        }
        if (f.op == kMessage) bad_record(pos, "message data record outside a chunk");
        continue;  // index data, chunk info, or a second bag header: nothing to read
      }
      load_chunk(pos, f, data_at, data_len);
      return true;
    }
  }

  void load_chunk(std::int64_t pos, const Fields& f, std::int64_t data_at, std::uint32_t data_len) {
    Codec codec = Codec::none;
    if (f.compression == "bz2") {
      codec = Codec::bz2;
    } else if (f.compression == "lz4") {
      codec = Codec::lz4;
    } else if (f.compression != "none") {
      throw ParseError(file_.name(), 0, 0,
                       "chunk at " + at_offset(pos) + ": unknown compression \"" +
                           std::string(f.compression) + "\" (expected none, bz2 or lz4)");
    }
    if (f.size > kMaxBagChunkBytes || data_len > kMaxBagChunkBytes) {
      bad_record(pos, "chunk of " + std::to_string(f.size) + " bytes (" +
                          std::to_string(data_len) + " stored) is over the " +
                          std::to_string(kMaxBagChunkBytes >> 20) + " MiB limit");
    }
    chunk_pos_ = pos;
    chunk_data_at_ = data_at;
    codec_ = codec;
    if (codec == Codec::none) {
      if (f.size != data_len) {
        bad_record(pos, "uncompressed chunk states " + std::to_string(f.size) + " bytes but holds " +
                            std::to_string(data_len));
      }
      chunk_.resize(data_len);
      file_.read(data_at, data_len, chunk_.data(), "chunk data");
      return;
    }
    raw_.resize(data_len);
    file_.read(data_at, data_len, raw_.data(), "chunk data");
    chunk_.resize(f.size);
    decompress(codec, std::string_view(raw_.data(), raw_.size()), chunk_, file_.name(), pos,
               "chunk");
  }

  /// An uncompressed chunk the file ends inside: its bytes up to the end of the file, whose
  /// complete records are read (next_in_chunk reports the cut at the first incomplete one).
  void load_cut_chunk(std::int64_t pos, std::int64_t data_at) {
    chunk_pos_ = pos;
    chunk_data_at_ = data_at;
    codec_ = Codec::none;
    const auto have = static_cast<std::size_t>(file_.size() - data_at);
    chunk_.resize(have);
    file_.read(data_at, have, chunk_.data(), "chunk data");
    scan_pos_ = file_.size();
    cut_chunk_ = true;
  }

  /// A record of a cut chunk runs past the end of the file: the cut.
  void cut_inside_chunk(std::size_t at) {
    cut_chunk_ = false;
    in_chunk_ = chunk_.size();
    cut_short(file_.name(), chunk_data_at_ + static_cast<std::int64_t>(at),
              "truncated " + inner_location(at) + ": the file ends at byte " +
                  std::to_string(file_.size()) + " inside it");
  }

  /// Where a record inside the current chunk is, for messages.
  std::string inner_location(std::size_t inner) const {
    if (codec_ == Codec::none) {
      return "record at " + at_offset(chunk_data_at_ + static_cast<std::int64_t>(inner)) +
             " (in the chunk at byte offset " + std::to_string(chunk_pos_) + ")";
    }
    return "record at byte " + std::to_string(inner) + " of the uncompressed chunk at " +
           at_offset(chunk_pos_);
  }

  [[noreturn]] void bad_inner(std::size_t inner, const std::string& why) const {
    throw ParseError(file_.name(), 0, 0, "corrupt " + inner_location(inner) + ": " + why);
  }

  /// Parses the record at in_chunk_ and advances; true when it was a selected message (in `s`).
  bool next_in_chunk(ImuSample& s) {
    const std::size_t at = in_chunk_;
    const std::size_t n = chunk_.size();
    const char* c = chunk_.data();
    if (n - at < 4) {
      if (cut_chunk_) return cut_inside_chunk(at), false;
      bad_inner(at, "truncated record header length");
    }
    const std::uint32_t header_len = load_le32(c + at);
    if (header_len > n - at - 4 || n - at - 4 - header_len < 4) {
      if (cut_chunk_ && header_len <= kMaxHeaderBytes) return cut_inside_chunk(at), false;
      bad_inner(at, "record header of " + std::to_string(header_len) +
                        " bytes runs past the end of the chunk");
    }
    const std::uint32_t data_len = load_le32(c + at + 4 + header_len);
    const std::size_t data_at = at + 8 + header_len;
    if (data_len > n - data_at) {
      if (cut_chunk_ && data_len <= kMaxRecordDataBytes) return cut_inside_chunk(at), false;
      bad_inner(at, "record data of " + std::to_string(data_len) +
                        " bytes runs past the end of the chunk");
    }
    in_chunk_ = data_at + data_len;
    Fields f;
    if (!parse_fields(c + at + 4, header_len, f)) bad_inner(at, "header fields are malformed");
    if (f.op == kConn) {
      learn_connection(f, c + data_at, data_len,
                       codec_ == Codec::none ? chunk_data_at_ + static_cast<std::int64_t>(at)
                                             : chunk_pos_);
      return false;
    }
    if (f.op != kMessage) bad_inner(at, "unexpected op " + std::to_string(f.op) + " in a chunk");
    if (counting_) {
      const auto it = conns_.find(f.conn);
      if (it != conns_.end()) ++it->second.messages;
      return false;
    }
    if (!is_selected(f.conn)) {
      if (!conns_.count(f.conn)) count_undeclared("connection", f.conn, [&] { return inner_location(at); });
      return false;
    }
    DecodeError e;
    if (!decode_ros1_imu(c + data_at, data_len, s, e)) {
      throw_bad_message(file_.name(), inner_location(at), topic_, data_len, e);
    }
    s.receive_ns = ros_time_ns(f.time);
    s.offset = codec_ == Codec::none ? chunk_data_at_ + static_cast<std::int64_t>(at) : chunk_pos_;
    return true;
  }

  BagFile file_;
  std::int64_t data_start_ = 0;
  bool indexed_ = false;
  bool scanned_ = false;
  bool counting_ = false;
  bool seen_topic_ = false;
  bool cut_chunk_ = false;  // the current chunk is cut short by the end of the file
  std::unordered_map<std::uint32_t, Connection> conns_;
  std::unordered_map<std::uint32_t, std::int64_t> pending_counts_;
  std::vector<ChunkInfo> chunk_infos_;
  std::string topic_;
  std::vector<std::uint32_t> selected_;
  std::vector<std::uint64_t> chunks_;  // indexed: positions of the chunks to read
  std::size_t chunk_index_ = 0;
  std::int64_t scan_pos_ = 0;          // unindexed: next top-level record
  std::vector<char> raw_, chunk_;
  std::size_t in_chunk_ = 0;
  std::int64_t chunk_pos_ = 0, chunk_data_at_ = 0;
  Codec codec_ = Codec::none;
};

}  // namespace

std::unique_ptr<BagBackend> open_ros1_bag(const std::string& path) {
  return std::make_unique<Ros1Bag>(path);
}

}  // namespace sigmatau::detail
