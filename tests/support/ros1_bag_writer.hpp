#pragma once
// A small ROS 1 bag (format 2.0) writer for tests and benchmarks: chunks uncompressed, bz2 or lz4
// (an LZ4 frame, as roslz4 writes it), indexed (connection and chunk info records at index_pos,
// index data records after each chunk, like rosbag record) or unindexed (index_pos 0, as left by
// a recorder that crashed). Streams to a file: memory is one chunk plus a few bytes per chunk.
// Format: wiki.ros.org/Bags/Format/2.0. Link with BZip2 and LZ4 (tests/CMakeLists.txt).
#include <bzlib.h>
#include <lz4frame.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace sigmatau::test {

/// One sensor_msgs/Imu message: stamps [ns since the epoch], rates [rad/s], accelerations [m/s^2].
struct Ros1Imu {
  std::int64_t header_ns = 0;
  std::int64_t receive_ns = 0;
  double gyro[3] = {0, 0, 0};
  double accel[3] = {0, 0, 0};
  std::string frame_id = "imu_link";
};

class Ros1BagWriter {
 public:
  enum class Compression { none, bz2, lz4 };
  struct Options {
    Compression compression = Compression::none;
    bool indexed = true;
    /// A chunk is closed once its uncompressed data reaches this size [bytes] (rosbag: 768 KiB).
    std::size_t chunk_bytes = 768 * 1024;
    /// When set, written as the chunks' compression field instead of the real name (the data is
    /// still compressed as `compression` says): for "unknown compression" tests.
    std::string compression_name;
  };

  static constexpr const char* kImuMd5 = "6a62c6daae103f4ff57a132d6f95cec2";

  Ros1BagWriter(const std::string& path, Options options)
      : out_(path, std::ios::binary | std::ios::trunc), options_(std::move(options)) {
    if (!out_) throw std::runtime_error("cannot write " + path);
    out_.write("#ROSBAG V2.0\n", 13);
    pos_ = 13;
    write_bag_header(0, 0, 0);
  }

  /// Declares a connection (topic, type) and returns its id. md5sum empty: Imu's for Imu types,
  /// else "*".
  std::uint32_t add_connection(const std::string& topic, const std::string& type,
                               std::string md5sum = "") {
    if (md5sum.empty()) md5sum = type == "sensor_msgs/Imu" ? kImuMd5 : "*";
    const auto id = static_cast<std::uint32_t>(conns_.size());
    conns_.push_back({topic, type, md5sum, false});
    return id;
  }

  /// The ROS 1 serialization of `m` (seq 0).
  static std::string serialize(const Ros1Imu& m) {
    std::string d;
    put32(d, 0);
    put32(d, static_cast<std::uint32_t>(m.header_ns / 1000000000));
    put32(d, static_cast<std::uint32_t>(m.header_ns % 1000000000));
    put32(d, static_cast<std::uint32_t>(m.frame_id.size()));
    d += m.frame_id;
    double body[37] = {};
    body[3] = 1;  // orientation w
    for (int k = 0; k < 3; ++k) {
      body[13 + k] = m.gyro[k];
      body[25 + k] = m.accel[k];
    }
    d.append(reinterpret_cast<const char*>(body), sizeof body);
    return d;
  }

  /// Writes one Imu message; returns where the reader locates it: the file offset of its record
  /// in an uncompressed chunk, else the offset of its chunk.
  std::int64_t write_imu(std::uint32_t conn, const Ros1Imu& m) {
    return write_message(conn, m.receive_ns, serialize(m));
  }

  /// A message record with any payload (a non-Imu message, or a corrupt one); returns its location
  /// as write_imu does.
  std::int64_t write_message(std::uint32_t conn, std::int64_t receive_ns, const std::string& data) {
    Connection& c = conns_.at(conn);
    if (!c.in_bag) {
      chunk_ += connection_record(conn);
      c.in_bag = true;
    }
    const std::uint64_t time = ros_time(receive_ns);
    const std::int64_t location = options_.compression == Compression::none
                                      ? pos_ + 4 + chunk_header_bytes() + 4 +
                                            static_cast<std::int64_t>(chunk_.size())
                                      : pos_;
    auto& entries = chunk_index_[conn];
    entries.push_back({time, static_cast<std::uint32_t>(chunk_.size())});
    std::string h;
    field(h, "op", std::string(1, '\x02'));
    field(h, "conn", bytes32(conn));
    field(h, "time", bytes64(time));
    record(chunk_, h, data);
    if (!have_time_ || time_ns(time) < time_ns(start_)) start_ = time;
    if (!have_time_ || time_ns(time) > time_ns(end_)) end_ = time;
    have_time_ = true;
    if (chunk_.size() >= options_.chunk_bytes) close_chunk();
    return location;
  }

  /// Closes the last chunk, writes the index (when indexed) and patches the bag header.
  void finish() {
    close_chunk();
    std::int64_t index_pos = 0;
    if (options_.indexed) {
      index_pos = pos_;
      std::string index;
      for (std::uint32_t id = 0; id < conns_.size(); ++id) index += connection_record(id);
      for (const ChunkInfo& ci : infos_) {
        std::string h;
        field(h, "op", std::string(1, '\x06'));
        field(h, "ver", bytes32(1));
        field(h, "chunk_pos", bytes64(static_cast<std::uint64_t>(ci.pos)));
        field(h, "start_time", bytes64(ci.start));
        field(h, "end_time", bytes64(ci.end));
        field(h, "count", bytes32(static_cast<std::uint32_t>(ci.counts.size())));
        std::string d;
        for (const auto& [conn, n] : ci.counts) {
          put32(d, conn);
          put32(d, n);
        }
        record(index, h, d);
      }
      emit(index);
    }
    out_.seekp(13);
    write_bag_header(index_pos, options_.indexed ? conns_.size() : 0,
                     options_.indexed ? infos_.size() : 0);
    out_.close();
    if (!out_) throw std::runtime_error("bag write failed");
  }

  /// File offsets of the chunks written, in order.
  const std::vector<std::int64_t>& chunk_positions() const { return chunk_positions_; }
  std::int64_t bytes_written() const { return pos_; }

 private:
  struct Connection {
    std::string topic, type, md5sum;
    bool in_bag;
  };
  struct ChunkInfo {
    std::int64_t pos;
    std::uint64_t start, end;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> counts;
  };
  struct IndexEntry {
    std::uint64_t time;
    std::uint32_t offset;
  };

  static void put32(std::string& s, std::uint32_t v) {
    char b[4];
    std::memcpy(b, &v, 4);
    s.append(b, 4);
  }
  static std::string bytes32(std::uint32_t v) {
    std::string s;
    put32(s, v);
    return s;
  }
  static std::string bytes64(std::uint64_t v) {
    std::string s(8, '\0');
    std::memcpy(s.data(), &v, 8);
    return s;
  }
  static void field(std::string& h, const std::string& name, const std::string& value) {
    put32(h, static_cast<std::uint32_t>(name.size() + 1 + value.size()));
    h += name;
    h += '=';
    h += value;
  }
  static void record(std::string& out, const std::string& header, const std::string& data) {
    put32(out, static_cast<std::uint32_t>(header.size()));
    out += header;
    put32(out, static_cast<std::uint32_t>(data.size()));
    out += data;
  }
  static std::uint64_t ros_time(std::int64_t ns) {
    return static_cast<std::uint64_t>(ns / 1000000000) |
           (static_cast<std::uint64_t>(ns % 1000000000) << 32);
  }
  static std::int64_t time_ns(std::uint64_t t) {
    return static_cast<std::int64_t>(t & 0xffffffffu) * 1000000000 +
           static_cast<std::int64_t>(t >> 32);
  }

  std::string connection_record(std::uint32_t id) const {
    const Connection& c = conns_[id];
    std::string h;
    field(h, "op", std::string(1, '\x07'));
    field(h, "conn", bytes32(id));
    field(h, "topic", c.topic);
    std::string d;
    field(d, "topic", c.topic);
    field(d, "type", c.type);
    field(d, "md5sum", c.md5sum);
    field(d, "message_definition", "# (definition left out by the test writer)\n");
    std::string r;
    record(r, h, d);
    return r;
  }

  std::string compression_name() const {
    if (!options_.compression_name.empty()) return options_.compression_name;
    switch (options_.compression) {
      case Compression::bz2:
        return "bz2";
      case Compression::lz4:
        return "lz4";
      case Compression::none:
        break;
    }
    return "none";
  }

  std::string chunk_header(std::uint32_t size) const {
    std::string h;
    field(h, "op", std::string(1, '\x05'));
    field(h, "compression", compression_name());
    field(h, "size", bytes32(size));
    return h;
  }
  std::int64_t chunk_header_bytes() const {
    return static_cast<std::int64_t>(chunk_header(0).size());
  }

  std::string compress(const std::string& raw) const {
    if (options_.compression == Compression::bz2) {
      auto n = static_cast<unsigned int>(raw.size() + raw.size() / 100 + 600);
      std::string out(n, '\0');
      if (BZ2_bzBuffToBuffCompress(out.data(), &n, const_cast<char*>(raw.data()),
                                   static_cast<unsigned int>(raw.size()), 9, 0, 30) != BZ_OK) {
        throw std::runtime_error("bz2 compression failed");
      }
      out.resize(n);
      return out;
    }
    if (options_.compression == Compression::lz4) {
      std::string out(LZ4F_compressFrameBound(raw.size(), nullptr), '\0');
      const std::size_t n =
          LZ4F_compressFrame(out.data(), out.size(), raw.data(), raw.size(), nullptr);
      if (LZ4F_isError(n)) throw std::runtime_error("lz4 compression failed");
      out.resize(n);
      return out;
    }
    return raw;
  }

  void close_chunk() {
    if (chunk_.empty()) return;
    const std::int64_t chunk_pos = pos_;
    chunk_positions_.push_back(chunk_pos);
    std::string r;
    record(r, chunk_header(static_cast<std::uint32_t>(chunk_.size())), compress(chunk_));
    ChunkInfo ci{chunk_pos, start_, end_, {}};
    for (const auto& [conn, entries] : chunk_index_) {
      std::string h;
      field(h, "op", std::string(1, '\x04'));
      field(h, "ver", bytes32(1));
      field(h, "conn", bytes32(conn));
      field(h, "count", bytes32(static_cast<std::uint32_t>(entries.size())));
      std::string d;
      for (const IndexEntry& e : entries) {
        d += bytes64(e.time);
        put32(d, e.offset);
      }
      record(r, h, d);
      ci.counts.emplace_back(conn, static_cast<std::uint32_t>(entries.size()));
    }
    emit(r);
    infos_.push_back(std::move(ci));
    chunk_.clear();
    chunk_index_.clear();
    have_time_ = false;
  }

  void write_bag_header(std::int64_t index_pos, std::size_t conn_count, std::size_t chunk_count) {
    std::string h;
    field(h, "op", std::string(1, '\x03'));
    field(h, "index_pos", bytes64(static_cast<std::uint64_t>(index_pos)));
    field(h, "conn_count", bytes32(static_cast<std::uint32_t>(conn_count)));
    field(h, "chunk_count", bytes32(static_cast<std::uint32_t>(chunk_count)));
    // rosbag pads the bag header record to 4096 bytes with spaces, so it can be rewritten.
    const std::size_t padding = 4096 - 8 - h.size();
    std::string r;
    record(r, h, std::string(padding, ' '));
    if (!header_written_) {
      emit(r);
      header_written_ = true;
    } else {
      out_.write(r.data(), static_cast<std::streamsize>(r.size()));
    }
  }

  void emit(const std::string& bytes) {
    out_.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    pos_ += static_cast<std::int64_t>(bytes.size());
  }

  std::ofstream out_;
  Options options_;
  std::int64_t pos_ = 0;
  bool header_written_ = false;
  std::vector<Connection> conns_;
  std::string chunk_;
  std::map<std::uint32_t, std::vector<IndexEntry>> chunk_index_;
  bool have_time_ = false;
  std::uint64_t start_ = 0, end_ = 0;
  std::vector<ChunkInfo> infos_;
  std::vector<std::int64_t> chunk_positions_;
};

}  // namespace sigmatau::test
