#pragma once
// Test-only writers of ROS 2 recordings with known sensor_msgs/Imu values: MCAP files (chunks
// uncompressed, zstd or lz4; with or without summary and footer), rosbag2 SQLite .db3 files
// (plain or per-message zstd) and rosbag2 folders (metadata.yaml plus several files). Written
// from the MCAP specification (mcap.dev/spec) and rosbag2's SQLite schema; small and not fast.
#include <lz4frame.h>
#include <sqlite3.h>
#include <zstd.h>

#include <bit>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace sigmatau::test {

/// One Imu message's values [ns, rad/s, m/s^2].
struct ImuValue {
  std::int64_t header_ns = 0;
  std::int64_t receive_ns = 0;
  double gyro[3] = {0, 0, 0};
  double accel[3] = {0, 0, 0};
};

/// `n` messages from a seeded generator: full-precision doubles (no round numbers), header
/// stamps at about 200 Hz with jitter, receive stamps a little later.
inline std::vector<ImuValue> make_imu_values(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::uniform_int_distribution<std::int64_t> jitter(-20000, 20000);
  std::vector<ImuValue> out(n);
  std::int64_t t = 1700000000123456789;
  for (std::size_t i = 0; i < n; ++i) {
    ImuValue& v = out[i];
    t += 5000000 + jitter(rng);
    v.header_ns = t;
    v.receive_ns = t + 150000 + jitter(rng) * 3;
    for (int k = 0; k < 3; ++k) {
      v.gyro[k] = 1e-3 * gauss(rng);
      v.accel[k] = (k == 2 ? 9.80665 : 0.0) + 0.05 * gauss(rng);
    }
  }
  return out;
}

/// CDR encapsulations: XCDR1 (identifiers 0x0000 BE, 0x0001 LE) and XCDR2 (0x0006, 0x0007).
enum class CdrKind { xcdr1_le, xcdr1_be, xcdr2_le, xcdr2_be };

namespace writer_detail {

inline void put_bytes(std::string& s, const void* p, std::size_t n, bool big) {
  const auto* b = static_cast<const char*>(p);
  if (big == (std::endian::native == std::endian::big)) {
    s.append(b, n);
  } else {
    for (std::size_t k = n; k-- > 0;) s.push_back(b[k]);
  }
}
template <class T>
void put(std::string& s, T v, bool big = false) {
  put_bytes(s, &v, sizeof v, big);
}
inline void put_str32(std::string& s, const std::string& v) {
  put<std::uint32_t>(s, static_cast<std::uint32_t>(v.size()));
  s += v;
}

/// The 37 float64 of sensor_msgs/Imu after the header: orientation, covariances filled with
/// distinct values so that a decoder reading the wrong slot fails the test.
inline std::vector<double> imu_body(const ImuValue& v) {
  std::vector<double> d(37);
  for (int k = 0; k < 37; ++k) d[k] = -0.125 * (k + 1) - 1e-9 * k;
  for (int k = 0; k < 3; ++k) {
    d[13 + k] = v.gyro[k];
    d[25 + k] = v.accel[k];
  }
  return d;
}

}  // namespace writer_detail

/// A CDR serialized sensor_msgs/msg/Imu (std_msgs/Header with `frame_id`).
inline std::string encode_cdr_imu(const ImuValue& v, CdrKind kind,
                                  const std::string& frame_id = "imu_link") {
  using namespace writer_detail;
  const bool big = kind == CdrKind::xcdr1_be || kind == CdrKind::xcdr2_be;
  const bool xcdr2 = kind == CdrKind::xcdr2_le || kind == CdrKind::xcdr2_be;
  std::string s;
  s.push_back('\0');
  s.push_back(static_cast<char>((xcdr2 ? 0x06 : 0x00) | (big ? 0 : 1)));
  s.append(2, '\0');
  put<std::int32_t>(s, static_cast<std::int32_t>(v.header_ns / 1000000000), big);
  put<std::uint32_t>(s, static_cast<std::uint32_t>(v.header_ns % 1000000000), big);
  put<std::uint32_t>(s, static_cast<std::uint32_t>(frame_id.size() + 1), big);
  s += frame_id;
  s.push_back('\0');
  const std::size_t align = xcdr2 ? 4 : 8;
  while ((s.size() - 4) % align != 0) s.push_back('\0');
  for (double d : imu_body(v)) put<double>(s, d, big);
  return s;
}

/// A ROS 1 serialized sensor_msgs/Imu.
inline std::string encode_ros1_imu(const ImuValue& v, const std::string& frame_id = "imu_link") {
  using namespace writer_detail;
  std::string s;
  put<std::uint32_t>(s, 7);
  put<std::uint32_t>(s, static_cast<std::uint32_t>(v.header_ns / 1000000000));
  put<std::uint32_t>(s, static_cast<std::uint32_t>(v.header_ns % 1000000000));
  put_str32(s, frame_id);
  for (double d : imu_body(v)) put<double>(s, d);
  return s;
}

/// One topic to write: its messages are Imu values; `type` is only the declared type, so a
/// non-Imu type with Imu payloads tests the type check.
struct Ros2Topic {
  std::string name = "/imu/data";
  std::string type = "sensor_msgs/msg/Imu";
  std::vector<ImuValue> values;
  CdrKind cdr = CdrKind::xcdr1_le;
  std::string encoding = "cdr";  ///< MCAP message_encoding / rosbag2 serialization_format
};

inline std::string encode_message(const Ros2Topic& t, const ImuValue& v) {
  return t.encoding == "ros1" ? encode_ros1_imu(v) : encode_cdr_imu(v, t.cdr);
}

/// The messages of all topics interleaved round-robin: (topic index, message index).
inline std::vector<std::pair<std::size_t, std::size_t>> interleave(
    const std::vector<Ros2Topic>& topics) {
  std::vector<std::pair<std::size_t, std::size_t>> order;
  std::size_t most = 0;
  for (const Ros2Topic& t : topics) most = std::max(most, t.values.size());
  for (std::size_t i = 0; i < most; ++i) {
    for (std::size_t k = 0; k < topics.size(); ++k) {
      if (i < topics[k].values.size()) order.emplace_back(k, i);
    }
  }
  return order;
}

struct McapOptions {
  std::string compression;  ///< "", "zstd", "lz4"; anything else is written uncompressed
  bool chunked = true;
  std::size_t chunk_messages = 40;  ///< messages per chunk
  bool summary = true;              ///< summary section (schemas, channels, chunk indexes, stats)
  bool footer = true;               ///< Data End, summary and footer (false: a crashed recorder)
  bool crc = true;                  ///< chunk uncompressed_crc
};

/// Where the writer put things, for tests that corrupt the file.
struct McapLayout {
  std::vector<std::int64_t> chunk_offsets;    ///< each Chunk record
  std::vector<std::int64_t> message_offsets;  ///< each top-level Message record (unchunked)
  std::int64_t data_end = -1;                 ///< the Data End record
  std::int64_t size = 0;
};

namespace writer_detail {

/// CRC-32 (ISO-HDLC, reflected polynomial 0xEDB88320), bit by bit: slow, obviously right.
inline std::uint32_t crc32(const char* p, std::size_t n) {
  std::uint32_t c = 0xffffffffu;
  for (std::size_t i = 0; i < n; ++i) {
    c ^= static_cast<unsigned char>(p[i]);
    for (int b = 0; b < 8; ++b) c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1u)));
  }
  return ~c;
}

inline void put_record(std::string& s, std::uint8_t op, const std::string& content) {
  s.push_back(static_cast<char>(op));
  put<std::uint64_t>(s, content.size());
  s += content;
}

inline std::string compress(const std::string& c, const std::string& codec) {
  if (codec == "zstd") {
    std::string out(ZSTD_compressBound(c.size()), '\0');
    const std::size_t n = ZSTD_compress(out.data(), out.size(), c.data(), c.size(), 3);
    if (ZSTD_isError(n)) throw std::runtime_error("zstd compression failed");
    out.resize(n);
    return out;
  }
  if (codec == "lz4") {
    std::string out(LZ4F_compressFrameBound(c.size(), nullptr), '\0');
    const std::size_t n = LZ4F_compressFrame(out.data(), out.size(), c.data(), c.size(), nullptr);
    if (LZ4F_isError(n)) throw std::runtime_error("lz4 compression failed");
    out.resize(n);
    return out;
  }
  return c;
}

inline void write_file(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  f.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!f) throw std::runtime_error("cannot write " + path.string());
}

}  // namespace writer_detail

/// Writes an MCAP file (profile ros2) holding `topics` (channel and schema ids 1, 2, ...).
inline McapLayout write_mcap(const std::filesystem::path& path,
                             const std::vector<Ros2Topic>& topics, const McapOptions& opt = {}) {
  using namespace writer_detail;
  static const char kMagic[8] = {'\x89', 'M', 'C', 'A', 'P', '0', '\r', '\n'};
  McapLayout layout;
  std::string f(kMagic, 8);
  {
    std::string h;
    put_str32(h, "ros2");
    put_str32(h, "sigmatau test writer");
    put_record(f, 0x01, h);
  }
  std::vector<std::string> schemas, channels;
  for (std::size_t k = 0; k < topics.size(); ++k) {
    std::string s;
    put<std::uint16_t>(s, static_cast<std::uint16_t>(k + 1));
    put_str32(s, topics[k].type);
    put_str32(s, "ros2msg");
    put_str32(s, "# definition omitted by the test writer");
    schemas.push_back(s);
    std::string c;
    put<std::uint16_t>(c, static_cast<std::uint16_t>(k + 1));
    put<std::uint16_t>(c, static_cast<std::uint16_t>(k + 1));
    put_str32(c, topics[k].name);
    put_str32(c, topics[k].encoding);
    put<std::uint32_t>(c, 0);  // empty metadata map
    channels.push_back(c);
  }
  std::vector<std::string> chunk_indexes;
  std::vector<std::uint64_t> counts(topics.size(), 0);
  std::vector<bool> declared(topics.size(), false);
  std::string records;  // the open chunk's records
  std::map<std::uint16_t, std::vector<std::pair<std::uint64_t, std::uint64_t>>> index;
  std::uint64_t t_min = 0, t_max = 0;
  std::size_t in_chunk = 0;
  std::uint32_t chunk_count = 0;
  const auto flush = [&] {
    if (in_chunk == 0) return;
    const std::string stored = compress(records, opt.compression);
    std::string c;
    put<std::uint64_t>(c, t_min);
    put<std::uint64_t>(c, t_max);
    put<std::uint64_t>(c, records.size());
    put<std::uint32_t>(c, opt.crc ? crc32(records.data(), records.size()) : 0);
    put_str32(c, opt.compression);
    put<std::uint64_t>(c, stored.size());
    c += stored;
    const auto chunk_at = static_cast<std::uint64_t>(f.size());
    layout.chunk_offsets.push_back(static_cast<std::int64_t>(chunk_at));
    put_record(f, 0x06, c);
    const auto chunk_len = f.size() - chunk_at;
    std::string offsets;
    const auto index_at = f.size();
    for (const auto& [id, entries] : index) {
      put<std::uint16_t>(offsets, id);
      put<std::uint64_t>(offsets, f.size());
      std::string m;
      put<std::uint16_t>(m, id);
      put<std::uint32_t>(m, static_cast<std::uint32_t>(entries.size() * 16));
      for (const auto& [t, o] : entries) {
        put<std::uint64_t>(m, t);
        put<std::uint64_t>(m, o);
      }
      put_record(f, 0x07, m);
    }
    std::string ci;
    put<std::uint64_t>(ci, t_min);
    put<std::uint64_t>(ci, t_max);
    put<std::uint64_t>(ci, chunk_at);
    put<std::uint64_t>(ci, chunk_len);
    put_str32(ci, offsets);
    put<std::uint64_t>(ci, f.size() - index_at);
    put_str32(ci, opt.compression);
    put<std::uint64_t>(ci, stored.size());
    put<std::uint64_t>(ci, records.size());
    chunk_indexes.push_back(ci);
    ++chunk_count;
    records.clear();
    index.clear();
    in_chunk = 0;
  };
  for (const auto& [k, i] : interleave(topics)) {
    std::string& out = opt.chunked ? records : f;
    if (!declared[k]) {
      put_record(out, 0x03, schemas[k]);
      put_record(out, 0x04, channels[k]);
      declared[k] = true;
    }
    const ImuValue& v = topics[k].values[i];
    const auto log_time = static_cast<std::uint64_t>(v.receive_ns);
    std::string m;
    put<std::uint16_t>(m, static_cast<std::uint16_t>(k + 1));
    put<std::uint32_t>(m, static_cast<std::uint32_t>(i));
    put<std::uint64_t>(m, log_time);
    // publish_time differs from log_time, so a reader taking the wrong one fails the tests.
    put<std::uint64_t>(m, static_cast<std::uint64_t>(v.header_ns) + 1);
    m += encode_message(topics[k], v);
    if (opt.chunked) {
      if (in_chunk == 0) t_min = t_max = log_time;
      t_min = std::min(t_min, log_time);
      t_max = std::max(t_max, log_time);
      index[static_cast<std::uint16_t>(k + 1)].emplace_back(log_time, records.size());
    } else {
      layout.message_offsets.push_back(static_cast<std::int64_t>(f.size()));
    }
    put_record(out, 0x05, m);
    ++counts[k];
    if (opt.chunked && ++in_chunk == opt.chunk_messages) {
      flush();
      std::fill(declared.begin(), declared.end(), false);  // each chunk declares its channels
    }
  }
  flush();
  if (opt.footer) {
    layout.data_end = static_cast<std::int64_t>(f.size());
    std::string de;
    put<std::uint32_t>(de, 0);
    put_record(f, 0x0F, de);
    std::uint64_t summary_start = 0;
    if (opt.summary) {
      summary_start = f.size();
      for (const std::string& s : schemas) put_record(f, 0x03, s);
      for (const std::string& c : channels) put_record(f, 0x04, c);
      for (const std::string& ci : chunk_indexes) put_record(f, 0x08, ci);
      std::string st;
      std::uint64_t total = 0;
      for (std::uint64_t n : counts) total += n;
      put<std::uint64_t>(st, total);
      put<std::uint16_t>(st, static_cast<std::uint16_t>(topics.size()));
      put<std::uint32_t>(st, static_cast<std::uint32_t>(topics.size()));
      put<std::uint32_t>(st, 0);
      put<std::uint32_t>(st, 0);
      put<std::uint32_t>(st, chunk_count);
      put<std::uint64_t>(st, 0);
      put<std::uint64_t>(st, 0);
      std::string map;
      for (std::size_t k = 0; k < topics.size(); ++k) {
        put<std::uint16_t>(map, static_cast<std::uint16_t>(k + 1));
        put<std::uint64_t>(map, counts[k]);
      }
      put_str32(st, map);
      put_record(f, 0x0B, st);
    }
    std::string footer;
    put<std::uint64_t>(footer, summary_start);
    put<std::uint64_t>(footer, 0);
    const std::size_t footer_at = f.size();
    put_record(f, 0x02, footer + std::string(4, '\0'));
    if (summary_start != 0) {
      const std::uint32_t crc = crc32(f.data() + summary_start, f.size() - 4 - summary_start);
      std::string c;
      put<std::uint32_t>(c, crc);
      f.replace(footer_at + 9 + 16, 4, c);
    }
    f.append(kMagic, 8);
  }
  layout.size = static_cast<std::int64_t>(f.size());
  write_file(path, f);
  return layout;
}

/// Writes a rosbag2 SQLite (.db3) file; with `zstd_messages` every data blob is one zstd frame
/// (rosbag2's compression_mode MESSAGE).
inline void write_db3(const std::filesystem::path& path, const std::vector<Ros2Topic>& topics,
                      bool zstd_messages = false) {
  std::filesystem::remove(path);
  sqlite3* db = nullptr;
  if (sqlite3_open(path.string().c_str(), &db) != SQLITE_OK) {
    sqlite3_close(db);
    throw std::runtime_error("cannot create " + path.string());
  }
  const auto exec = [&](const std::string& sql) {
    if (sqlite3_exec(db, sql.c_str(), nullptr, nullptr, nullptr) != SQLITE_OK) {
      throw std::runtime_error(std::string("sqlite: ") + sqlite3_errmsg(db));
    }
  };
  exec(
      "CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT NULL, "
      "serialization_format TEXT NOT NULL, offered_qos_profiles TEXT NOT NULL);"
      "CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL, "
      "timestamp INTEGER NOT NULL, data BLOB NOT NULL);"
      "BEGIN;");
  sqlite3_stmt* st = nullptr;
  sqlite3_prepare_v2(db, "INSERT INTO topics VALUES(?, ?, ?, ?, '')", -1, &st, nullptr);
  for (std::size_t k = 0; k < topics.size(); ++k) {
    sqlite3_bind_int64(st, 1, static_cast<sqlite3_int64>(k + 1));
    sqlite3_bind_text(st, 2, topics[k].name.c_str(), -1, SQLITE_TRANSIENT);
    sqlite3_bind_text(st, 3, topics[k].type.c_str(), -1, SQLITE_TRANSIENT);
    sqlite3_bind_text(st, 4, topics[k].encoding.c_str(), -1, SQLITE_TRANSIENT);
    sqlite3_step(st);
    sqlite3_reset(st);
  }
  sqlite3_finalize(st);
  sqlite3_prepare_v2(db, "INSERT INTO messages(topic_id, timestamp, data) VALUES(?, ?, ?)", -1, &st,
                     nullptr);
  for (const auto& [k, i] : interleave(topics)) {
    const ImuValue& v = topics[k].values[i];
    std::string data = encode_message(topics[k], v);
    if (zstd_messages) data = writer_detail::compress(data, "zstd");
    sqlite3_bind_int64(st, 1, static_cast<sqlite3_int64>(k + 1));
    sqlite3_bind_int64(st, 2, v.receive_ns);
    sqlite3_bind_blob(st, 3, data.data(), static_cast<int>(data.size()), SQLITE_TRANSIENT);
    if (sqlite3_step(st) != SQLITE_DONE) throw std::runtime_error("sqlite insert failed");
    sqlite3_reset(st);
  }
  sqlite3_finalize(st);
  exec("COMMIT;");
  sqlite3_close(db);
}

/// Writes a rosbag2 folder: metadata.yaml and `files` storage files ("sqlite3" or "mcap"), each
/// topic's messages split evenly across the files in order. `compression_mode` "MESSAGE" writes
/// zstd blobs (sqlite3 only); "FILE" is only declared (for the refusal test).
inline void write_rosbag2_folder(const std::filesystem::path& dir, const std::string& storage,
                                 const std::vector<Ros2Topic>& topics, std::size_t files = 2,
                                 const std::string& compression_mode = "") {
  std::filesystem::create_directories(dir);
  const std::string base = dir.filename().string();
  std::string paths;
  for (std::size_t f = 0; f < files; ++f) {
    std::vector<Ros2Topic> part = topics;
    for (std::size_t k = 0; k < topics.size(); ++k) {
      const std::size_t n = topics[k].values.size();
      part[k].values.assign(
          topics[k].values.begin() + static_cast<std::ptrdiff_t>(n * f / files),
          topics[k].values.begin() + static_cast<std::ptrdiff_t>(n * (f + 1) / files));
    }
    const std::string name =
        base + "_" + std::to_string(f) + (storage == "mcap" ? ".mcap" : ".db3");
    if (storage == "mcap") {
      write_mcap(dir / name, part);
    } else {
      write_db3(dir / name, part, compression_mode == "MESSAGE");
    }
    paths += "    - " + name + "\n";
  }
  std::string y = "rosbag2_bagfile_information:\n  version: 5\n  storage_identifier: " + storage +
                  "\n  relative_file_paths:\n" + paths + "  topics_with_message_count:\n";
  for (const Ros2Topic& t : topics) {
    y += "    - topic_metadata:\n        name: " + t.name + "\n        type: " + t.type +
         "\n        serialization_format: " + t.encoding +
         "\n        offered_qos_profiles: \"\"\n      message_count: " +
         std::to_string(t.values.size()) + "\n";
  }
  y += "  compression_format: \"" + std::string(compression_mode.empty() ? "" : "zstd") +
       "\"\n  compression_mode: \"" + compression_mode + "\"\n";
  writer_detail::write_file(dir / "metadata.yaml", y);
}

}  // namespace sigmatau::test
