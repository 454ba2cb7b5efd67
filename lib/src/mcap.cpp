// Internal: MCAP reader for sensor_msgs/Imu messages (ROS 2 "cdr" and ROS 1 "ros1" encodings).
//
// Format (mcap.dev/spec, major version 0): the magic 89 'M' 'C' 'A' 'P' '0' '\r' '\n', then
// records <opcode u8><content length u64><content>, all little endian; a string is <u32 length>
// <bytes>, a map <u32 byte length><entries>. Records read here: 0x01 Header, 0x02 Footer
// (summary_start u64, summary_offset_start u64, summary_crc u32), 0x03 Schema (id u16, name,
// encoding, data), 0x04 Channel (id u16, schema_id u16, topic, message_encoding, metadata),
// 0x05 Message (channel_id u16, sequence u32, log_time u64, publish_time u64, data), 0x06 Chunk
// (message_start_time u64, message_end_time u64, uncompressed_size u64, uncompressed_crc u32,
// compression string "" / "zstd" / "lz4", records <u64 length><bytes>), 0x08 Chunk Index
// (start, end, chunk_start_offset u64, chunk_length u64, message_index_offsets map<u16,u64>, ...),
// 0x0B Statistics (message_count u64, schema_count u16, channel_count u32, attachment_count u32,
// metadata_count u32, chunk_count u32, start u64, end u64, channel_message_counts
// map<u16,u64>), 0x0F Data End. Other records (message indexes, attachments, metadata, unknown
// opcodes) are skipped by their length, as the specification asks of readers.
//
// Reading: the data section is always walked in file order, one top-level record at a time,
// holding at most one chunk (compressed and uncompressed). The summary section, when the footer
// points to one, supplies the channels and schemas (so a missing topic or a wrong type is found
// before reading), the message counts (Statistics) and, from the chunk indexes, which channels a
// chunk holds, so chunks without the selected topic are skipped without decompressing them.
// A file whose writer crashed has no summary and no footer: it is read by the same walk; when it
// ends exactly at a record boundary it ends cleanly (every record in it is complete), when it ends
// inside a record the messages before that record are delivered and then the cut is reported
// (BagBackend::cut_short: a ParseError naming the record's byte offset, or, after allow_cut(), a
// normal end with cut() saying where). The messages of a chunk cut short are not used (a chunk
// is compressed as a whole). A file with a footer whose record runs past the data section is
// corrupt, never cut: always a ParseError.
#include <algorithm>
#include <unordered_map>

#include "bag_backend.hpp"
#include "sigmatau/error.hpp"

namespace sigmatau::detail {
namespace {

constexpr char kMagic[8] = {'\x89', 'M', 'C', 'A', 'P', '0', '\r', '\n'};
enum Op : unsigned {
  kHeader = 0x01,
  kFooter = 0x02,
  kSchema = 0x03,
  kChannel = 0x04,
  kMessage = 0x05,
  kChunk = 0x06,
  kChunkIndex = 0x08,
  kStatistics = 0x0B,
  kDataEnd = 0x0F,
};
/// Opcode and content length in front of every record [bytes].
constexpr std::int64_t kPrefixBytes = 9;
/// A whole Footer record: prefix plus summary_start, summary_offset_start, summary_crc [bytes].
constexpr std::int64_t kFooterRecordBytes = kPrefixBytes + 20;
/// Message fields in front of the data: channel_id, sequence, log_time, publish_time [bytes].
constexpr std::size_t kMessageFieldBytes = 2 + 4 + 8 + 8;
/// Chunk fields in front of the compression string: two times, size, crc, string length [bytes].
constexpr std::size_t kChunkFixedBytes = 8 + 8 + 8 + 4 + 4;
/// Largest record other than a chunk or message accepted [bytes]: schemas carry a message
/// definition (a few kB), chunk indexes and statistics a few bytes per channel; more is corruption.
constexpr std::uint64_t kMaxMetaRecordBytes = std::uint64_t{64} << 20;

/// Bounds-checked reader of one record's fields; `ok` turns false on an overrun.
struct Fields {
  const char* p;
  std::size_t n;
  std::size_t i = 0;
  bool ok = true;

  bool need(std::size_t k) {
    if (!ok || k > n - i) ok = false;
    return ok;
  }
  std::uint16_t u16() { return need(2) ? (i += 2, load_le16(p + i - 2)) : std::uint16_t{0}; }
  std::uint32_t u32() { return need(4) ? (i += 4, load_le32(p + i - 4)) : std::uint32_t{0}; }
  std::uint64_t u64() { return need(8) ? (i += 8, load_le64(p + i - 8)) : std::uint64_t{0}; }
  std::string_view str() {
    const std::uint32_t len = u32();
    if (!need(len)) return {};
    i += len;
    return {p + i - len, len};
  }
};

enum class Encoding : std::uint8_t { unsupported, cdr, ros1 };

struct Channel {
  std::string topic, encoding;
  std::uint16_t schema_id = 0;
  std::int64_t offset = 0;    // where the channel record is (file, or the chunk holding it)
  std::int64_t messages = 0;  // from Statistics or a counting pass
};

class McapFile final : public BagBackend {
 public:
  explicit McapFile(const std::string& path)
      : file_(path), selected_(65536, Encoding::unsupported) {
    const char* head = file_.view(0, sizeof kMagic, "MCAP magic");
    if (is_zstd_frame(head, sizeof kMagic)) {
      throw Error(path +
                  ": this file is compressed as a whole with zstd (rosbag2 "
                  "compression_mode FILE, a .mcap.zstd file) and is not read in place; "
                  "decompress it first (zstd -d, or ros2 bag decompress) and read the "
                  ".mcap it gives");
    }
    if (std::string_view(head, sizeof kMagic) != std::string_view(kMagic, sizeof kMagic)) {
      throw ParseError(file_.name(), 0, 0,
                       "not an MCAP file: byte offset 0 does not hold the MCAP magic "
                       "(89 4D 43 41 50 30 0D 0A)");
    }
    const char* h = file_.view(sizeof kMagic, kPrefixBytes, "MCAP header record");
    if (static_cast<unsigned char>(h[0]) != kHeader) {
      throw ParseError(file_.name(), 0, 0,
                       "expected the header record (op 0x01) at byte offset 8, found op " +
                           std::to_string(static_cast<unsigned char>(h[0])));
    }
    const std::uint64_t len = load_le64(h + 1);
    data_start_ = static_cast<std::int64_t>(sizeof kMagic) + kPrefixBytes;
    if (len > static_cast<std::uint64_t>(file_.size() - data_start_)) {
      throw ParseError(file_.name(), 0, 0,
                       truncated_detail(8, len) + " (the file ends inside its header record)");
    }
    data_start_ += static_cast<std::int64_t>(len);
    scan_end_ = file_.size();
    read_summary();
    pos_ = data_start_;
  }

  std::vector<BagTopic> topics(bool need_counts) override {
    if (!scanned_ && (!has_summary_ || (need_counts && !counts_known_))) scan_pass();
    return topic_list(counts_known_ || scanned_);
  }

  std::vector<BagTopic> indexed_topics() override {
    return has_summary_ || scanned_ ? topic_list(counts_known_ || scanned_)
                                    : std::vector<BagTopic>{};
  }

  bool select(const std::string& topic) override {
    topic_ = topic;
    std::fill(selected_.begin(), selected_.end(), Encoding::unsupported);
    lazy_ = !has_summary_ && !scanned_;
    if (lazy_) return true;  // checked as channels appear (one pass)
    bool found = false;
    for (const auto& [id, c] : channels_) {
      if (c.topic != topic) continue;
      found = true;
      accept(id, c);
    }
    return found;
  }

  bool next(ImuSample& s) override {
    while (true) {
      if (in_chunk_ < chunk_.size()) {
        if (next_in_chunk(s)) return true;
        continue;
      }
      bool produced = false;
      if (!next_top(s, produced)) {
        if (lazy_ && !seen_topic_) throw_missing_topic(file_.name(), topic_, topic_list(false));
        return false;
      }
      if (produced) return true;
    }
  }

  std::int64_t bytes_read() const override { return file_.bytes_read(); }
  std::int64_t total_bytes() const override { return file_.size(); }

 private:
  [[noreturn]] void bad_record(std::int64_t pos, const std::string& why) const {
    throw ParseError(file_.name(), 0, 0, "corrupt record at " + at_offset(pos) + ": " + why);
  }

  /// "truncated record at byte offset <pos>: its content needs <len> bytes from byte ...".
  std::string truncated_detail(std::int64_t pos, std::uint64_t len) const {
    return "truncated record at " + at_offset(pos) + ": its content needs " + std::to_string(len) +
           " bytes from byte " + std::to_string(pos + kPrefixBytes) + ", the file ends at byte " +
           std::to_string(file_.size());
  }

  /// Reads the footer and, when it points to one, the summary section.
  void read_summary() {
    const std::int64_t footer_at =
        file_.size() - static_cast<std::int64_t>(sizeof kMagic) - kFooterRecordBytes;
    if (footer_at < data_start_) return;
    const char* tail = file_.view(footer_at, kFooterRecordBytes + sizeof kMagic, "MCAP footer");
    if (std::string_view(tail + kFooterRecordBytes, sizeof kMagic) !=
            std::string_view(kMagic, sizeof kMagic) ||
        static_cast<unsigned char>(tail[0]) != kFooter || load_le64(tail + 1) != 20) {
      return;  // no footer: a recording cut short, read by the walk alone
    }
    has_footer_ = true;
    scan_end_ = footer_at;
    const std::uint64_t summary_start = load_le64(tail + 9);
    const std::uint64_t offsets_start = load_le64(tail + 17);
    const std::uint32_t summary_crc = load_le32(tail + 25);
    if (summary_start == 0) return;
    if (summary_start < static_cast<std::uint64_t>(data_start_) ||
        summary_start > static_cast<std::uint64_t>(footer_at) ||
        (offsets_start != 0 && (offsets_start < summary_start ||
                                offsets_start > static_cast<std::uint64_t>(footer_at)))) {
      bad_record(footer_at, "the footer's summary_start " + std::to_string(summary_start) +
                                " or summary_offset_start " + std::to_string(offsets_start) +
                                " lies outside the file's records");
    }
    const auto start = static_cast<std::int64_t>(summary_start);
    const std::int64_t end =
        offsets_start != 0 ? static_cast<std::int64_t>(offsets_start) : footer_at;
    if (summary_crc != 0) check_summary_crc(start, footer_at, summary_crc);
    for (std::int64_t pos = start; pos < end;) {
      const char* prefix = file_.view(pos, kPrefixBytes, "summary record");
      const auto op = static_cast<unsigned char>(prefix[0]);
      const std::uint64_t len = load_le64(prefix + 1);
      if (len > static_cast<std::uint64_t>(end - pos - kPrefixBytes)) {
        bad_record(pos, "summary record of " + std::to_string(len) +
                            " bytes runs past the end of the summary section at byte " +
                            std::to_string(end));
      }
      if (op == kSchema || op == kChannel || op == kChunkIndex || op == kStatistics) {
        if (len > kMaxMetaRecordBytes) bad_record(pos, "summary record is implausibly long");
        const char* c = file_.view(pos + kPrefixBytes, len, "summary record");
        if (op == kSchema) learn_schema(c, len, pos);
        if (op == kChannel) learn_channel(c, len, pos);
        if (op == kChunkIndex) learn_chunk_index(c, len, pos);
        if (op == kStatistics) learn_statistics(c, len, pos);
      }
      pos += kPrefixBytes + static_cast<std::int64_t>(len);
    }
    scan_end_ = start;
    has_summary_ = !channels_.empty();
  }

  void check_summary_crc(std::int64_t start, std::int64_t footer_at, std::uint32_t stated) {
    // Covers the summary and summary offset sections and the footer up to its summary_crc field.
    const std::int64_t end = footer_at + kPrefixBytes + 16;
    std::uint32_t crc = 0;
    constexpr std::int64_t kPiece = std::int64_t{1} << 20;
    for (std::int64_t at = start; at < end; at += kPiece) {
      const auto n = static_cast<std::size_t>(std::min(kPiece, end - at));
      crc = crc32_of(file_.view(at, n, "summary section"), n, crc);
    }
    if (crc != stated) {
      throw ParseError(file_.name(), 0, 0,
                       "summary section at " + at_offset(start) + ": CRC32 mismatch (computed " +
                           hex(crc) + ", the footer states " + hex(stated) + ")");
    }
  }

  static std::string hex(std::uint32_t v) {
    static const char* digits = "0123456789abcdef";
    std::string s = "0x00000000";
    for (int k = 0; k < 8; ++k) s[9 - k] = digits[(v >> (4 * k)) & 0xf];
    return s;
  }

  void learn_schema(const char* p, std::size_t n, std::int64_t where) {
    Fields f{p, n};
    const std::uint16_t id = f.u16();
    const std::string_view name = f.str();
    if (!f.ok) bad_record(where, "schema record fields run past its end");
    if (id != 0) schemas_.try_emplace(id, name);
  }

  void learn_channel(const char* p, std::size_t n, std::int64_t where) {
    Fields f{p, n};
    const std::uint16_t id = f.u16();
    const std::uint16_t schema_id = f.u16();
    const std::string_view topic = f.str();
    const std::string_view encoding = f.str();
    if (!f.ok) bad_record(where, "channel record fields run past its end");
    if (channels_.count(id)) return;
    Channel c;
    c.topic = std::string(topic);
    c.encoding = std::string(encoding);
    c.schema_id = schema_id;
    c.offset = where;
    const Channel& stored = channels_.emplace(id, std::move(c)).first->second;
    if (lazy_ && stored.topic == topic_) accept(id, stored);
  }

  void learn_chunk_index(const char* p, std::size_t n, std::int64_t where) {
    Fields f{p, n};
    f.u64();
    f.u64();
    const std::uint64_t chunk_at = f.u64();
    f.u64();
    const std::uint32_t map_bytes = f.u32();
    if (!f.need(map_bytes) || map_bytes % 10 != 0) {
      bad_record(where, "chunk index message_index_offsets map is malformed");
    }
    std::vector<std::uint16_t> ids;
    for (std::uint32_t k = 0; k < map_bytes; k += 10) ids.push_back(load_le16(p + f.i + k));
    if (!ids.empty()) chunk_channels_[chunk_at] = std::move(ids);
  }

  void learn_statistics(const char* p, std::size_t n, std::int64_t where) {
    Fields f{p, n};
    f.u64();
    f.u16();
    for (int k = 0; k < 4; ++k) f.u32();
    f.u64();
    f.u64();
    const std::uint32_t map_bytes = f.u32();
    if (!f.need(map_bytes) || map_bytes % 10 != 0) {
      bad_record(where, "statistics channel_message_counts map is malformed");
    }
    if (map_bytes == 0) return;  // counts not available
    for (std::uint32_t k = 0; k < map_bytes; k += 10) {
      const auto it = channels_.find(load_le16(p + f.i + k));
      if (it != channels_.end())
        it->second.messages = static_cast<std::int64_t>(load_le64(p + f.i + k + 2));
    }
    counts_known_ = true;
  }

  std::string type_of(const Channel& c) const {
    const auto it = schemas_.find(c.schema_id);
    return it == schemas_.end() ? std::string() : it->second;
  }

  void accept(std::uint16_t id, const Channel& c) {
    const std::string type = type_of(c);
    const std::string where = "channel record at " + at_offset(c.offset);
    if (!is_imu_type(type)) {
      throw_wrong_type(file_.name(), where, c.topic,
                       type.empty() ? std::string("(none: the channel names no schema)") : type);
    }
    Encoding e = Encoding::unsupported;
    if (c.encoding == "cdr") e = Encoding::cdr;
    if (c.encoding == "ros1") e = Encoding::ros1;
    if (e == Encoding::unsupported) {
      throw ParseError(file_.name(), 0, 0,
                       where + ": topic " + c.topic + " has message encoding \"" + c.encoding +
                           "\", expected cdr (ROS 2) or ros1");
    }
    selected_[id] = e;
    seen_topic_ = true;
  }

  std::vector<BagTopic> topic_list(bool with_counts) const {
    std::vector<BagTopic> list;
    for (const auto& [id, c] : channels_) add_topic(list, c.topic, type_of(c), c.messages, with_counts);
    sort_topics(list);
    return list;
  }

  /// Counts the messages of every channel by reading the whole file, then rewinds.
  void scan_pass() {
    for (auto& [id, c] : channels_) c.messages = 0;
    counting_ = true;
    ImuSample unused;
    bool produced = false;
    pos_ = data_start_;
    while (true) {
      while (in_chunk_ < chunk_.size()) next_in_chunk(unused);
      if (!next_top(unused, produced)) break;
    }
    counting_ = false;
    scanned_ = true;
    pos_ = data_start_;
  }

  /// Handles the next top-level record of the data section. false at its end; `produced` when it
  /// was a message of the selected topic (in `s`).
  bool next_top(ImuSample& s, bool& produced) {
    produced = false;
    chunk_.clear();
    in_chunk_ = 0;
    if (pos_ >= scan_end_) return false;
    const std::int64_t pos = pos_;
    if (file_.size() - pos < kPrefixBytes) {  // only without a footer (it is 37 bytes)
      cut_short(file_.name(), pos,
                "truncated record at " + at_offset(pos) + ": " +
                    std::to_string(file_.size() - pos) +
                    " bytes remain, less than an opcode and a length");
      pos_ = scan_end_;
      return false;
    }
    const std::int64_t body = pos + kPrefixBytes;
    if (body > scan_end_) bad_record(pos, "record prefix runs past the end of the data section");
    const char* prefix = file_.view(pos, kPrefixBytes, "record");
    const auto op = static_cast<unsigned char>(prefix[0]);
    const std::uint64_t len = load_le64(prefix + 1);
    if (len > static_cast<std::uint64_t>(scan_end_ - body)) {
      // Without a footer scan_end_ is the end of the file: the recording was cut here, unless
      // the length is beyond any record (a corrupt length, not a cut).
      if (!has_footer_ && len <= kMaxBagChunkBytes) {
        cut_short(file_.name(), pos, truncated_detail(pos, len));
        pos_ = scan_end_;
        return false;
      }
      bad_record(pos, "content of " + std::to_string(len) +
                          " bytes runs past the end of the data section at byte " +
                          std::to_string(scan_end_));
    }
    pos_ = body + static_cast<std::int64_t>(len);
    switch (op) {
      case kDataEnd:
      case kFooter:
        pos_ = scan_end_;
        return false;
      case kSchema:
      case kChannel: {
        if (len > kMaxMetaRecordBytes)
          bad_record(pos, "schema or channel record is implausibly long");
        const char* c = file_.view(body, len, "record");
        if (op == kSchema)
          learn_schema(c, len, pos);
        else
          learn_channel(c, len, pos);
        return true;
      }
      case kMessage: {
        if (len > kMaxBagChunkBytes) bad_record(pos, "message record is implausibly long");
        const char* c = file_.view(body, len, "message record");
        produced = handle_message(c, len, pos, s, [&] { return "record at " + at_offset(pos); });
        return true;
      }
      case kChunk:
        load_chunk(pos, body, len);
        return true;
      default:
        return true;  // message index, attachment, metadata, or an opcode from a later version
    }
  }

  void load_chunk(std::int64_t pos, std::int64_t body, std::uint64_t len) {
    if (len < kChunkFixedBytes + 8)
      bad_record(pos, "chunk record of " + std::to_string(len) + " bytes is too short");
    const char* h = file_.view(body, kChunkFixedBytes, "chunk header");
    const std::uint64_t size = load_le64(h + 16);
    const std::uint32_t crc = load_le32(h + 24);
    const std::uint32_t name_len = load_le32(h + 28);
    if (name_len > len - kChunkFixedBytes - 8)
      bad_record(pos, "chunk compression name runs past the record");
    const char* h2 = file_.view(body + static_cast<std::int64_t>(kChunkFixedBytes), name_len + 8,
                                "chunk header");
    const std::string compression(h2, name_len);
    const std::uint64_t stored = load_le64(h2 + name_len);
    const std::int64_t records_at =
        body + static_cast<std::int64_t>(kChunkFixedBytes) + name_len + 8;
    if (stored > len - kChunkFixedBytes - 8 - name_len) {
      bad_record(pos, "chunk records of " + std::to_string(stored) + " bytes run past the record");
    }
    Codec codec = Codec::none;
    if (compression == "zstd") {
      codec = Codec::zstd;
    } else if (compression == "lz4") {
      codec = Codec::lz4;
    } else if (!compression.empty()) {
      throw ParseError(file_.name(), 0, 0,
                       "chunk at " + at_offset(pos) + ": unknown compression \"" + compression +
                           "\" (expected none, zstd or lz4)");
    }
    if (size > kMaxBagChunkBytes || stored > kMaxBagChunkBytes) {
      bad_record(pos, "chunk of " + std::to_string(size) + " bytes (" + std::to_string(stored) +
                          " stored) is over the " + std::to_string(kMaxBagChunkBytes >> 20) +
                          " MiB limit");
    }
    if (!counting_ && !lazy_ && skippable(pos)) return;
    chunk_pos_ = pos;
    chunk_data_at_ = records_at;
    codec_ = codec;
    if (codec == Codec::none) {
      if (size != stored) {
        bad_record(pos, "uncompressed chunk states " + std::to_string(size) + " bytes but holds " +
                            std::to_string(stored));
      }
      chunk_.resize(stored);
      file_.read(records_at, stored, chunk_.data(), "chunk records");
    } else {
      raw_.resize(stored);
      file_.read(records_at, stored, raw_.data(), "chunk records");
      chunk_.resize(size);
      decompress(codec, std::string_view(raw_.data(), raw_.size()), chunk_, file_.name(), pos,
                 "chunk");
    }
    if (crc != 0) {
      const std::uint32_t got = crc32_of(chunk_.data(), chunk_.size());
      if (got != crc) {
        chunk_.clear();
        throw ParseError(file_.name(), 0, 0,
                         "chunk at " + at_offset(pos) + ": CRC32 of the uncompressed records is " +
                             hex(got) + ", the chunk states " + hex(crc) + " (corrupt data)");
      }
    }
  }

  /// True when the summary's chunk index says the chunk at `pos` holds no selected channel.
  bool skippable(std::int64_t pos) const {
    const auto it = chunk_channels_.find(static_cast<std::uint64_t>(pos));
    if (it == chunk_channels_.end()) return false;
    return std::none_of(it->second.begin(), it->second.end(),
                        [&](std::uint16_t id) { return selected_[id] != Encoding::unsupported; });
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

  /// Parses the record at in_chunk_ and advances; true when it was a selected message (in `s`).
  bool next_in_chunk(ImuSample& s) {
    const std::size_t at = in_chunk_;
    const std::size_t n = chunk_.size();
    const char* c = chunk_.data();
    if (n - at < kPrefixBytes) {
      throw ParseError(
          file_.name(), 0, 0,
          "corrupt " + inner_location(at) + ": truncated opcode and length at the chunk's end");
    }
    const auto op = static_cast<unsigned char>(c[at]);
    const std::uint64_t len = load_le64(c + at + 1);
    if (len > n - at - kPrefixBytes) {
      throw ParseError(file_.name(), 0, 0,
                       "corrupt " + inner_location(at) + ": content of " + std::to_string(len) +
                           " bytes runs past the end of the chunk");
    }
    in_chunk_ = at + kPrefixBytes + len;
    const char* body = c + at + kPrefixBytes;
    const std::int64_t where =
        codec_ == Codec::none ? chunk_data_at_ + static_cast<std::int64_t>(at) : chunk_pos_;
    if (op == kSchema) learn_schema(body, len, where);
    if (op == kChannel) learn_channel(body, len, where);
    if (op != kMessage) return false;
    return handle_message(body, len, where, s, [&] { return inner_location(at); });
  }

  /// Decodes a message record's content when its channel is selected (counts it when counting).
  template <class Location>
  bool handle_message(const char* p, std::size_t n, std::int64_t where, ImuSample& s,
                      const Location& location) {
    if (n < kMessageFieldBytes) {
      throw ParseError(file_.name(), 0, 0,
                       "corrupt " + location() + ": message record of " + std::to_string(n) +
                           " bytes is too short");
    }
    const std::uint16_t id = load_le16(p);
    if (counting_) {
      const auto it = channels_.find(id);
      if (it != channels_.end()) ++it->second.messages;
      return false;
    }
    const Encoding e = selected_[id];
    if (e == Encoding::unsupported) {
      if (!channels_.count(id)) count_undeclared("channel", id, location);
      return false;
    }
    const char* data = p + kMessageFieldBytes;
    const std::size_t m = n - kMessageFieldBytes;
    DecodeError err;
    const bool ok =
        e == Encoding::cdr ? decode_cdr_imu(data, m, s, err) : decode_ros1_imu(data, m, s, err);
    if (!ok) throw_bad_message(file_.name(), location(), topic_, m, err);
    s.receive_ns = static_cast<std::int64_t>(load_le64(p + 6));
    s.offset = where;
    s.id = -1;
    return true;
  }

  BagFile file_;
  std::int64_t data_start_ = 0;
  std::int64_t scan_end_ = 0;  // where the data section ends (summary, footer or end of file)
  bool has_footer_ = false;
  bool has_summary_ = false;
  bool counts_known_ = false;
  bool scanned_ = false;
  bool counting_ = false;
  bool lazy_ = false;  // no summary: the topic is checked as its channel appears
  bool seen_topic_ = false;
  std::unordered_map<std::uint16_t, std::string> schemas_;
  std::unordered_map<std::uint16_t, Channel> channels_;
  std::unordered_map<std::uint64_t, std::vector<std::uint16_t>> chunk_channels_;
  std::string topic_;
  std::vector<Encoding> selected_;  // per channel id: how to decode, or not selected
  std::int64_t pos_ = 0;            // next top-level record
  std::vector<char> raw_, chunk_;
  std::size_t in_chunk_ = 0;
  std::int64_t chunk_pos_ = 0, chunk_data_at_ = 0;
  Codec codec_ = Codec::none;
};

}  // namespace

std::unique_ptr<BagBackend> open_mcap(const std::string& path) {
  return std::make_unique<McapFile>(path);
}

}  // namespace sigmatau::detail
