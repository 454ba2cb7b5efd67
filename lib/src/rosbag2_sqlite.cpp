// Internal: rosbag2 SQLite storage (.db3) reader for sensor_msgs/Imu messages.
//
// Schema (rosbag2_storage_default_plugins, sqlite3 storage): a table topics(id INTEGER PRIMARY
// KEY, name TEXT, type TEXT, serialization_format TEXT, offered_qos_profiles TEXT, ...) and a
// table messages(id INTEGER PRIMARY KEY, topic_id INTEGER, timestamp INTEGER, data BLOB), the
// timestamp being the recorder's receive time [ns since the epoch] and data the serialized
// message ("cdr": a CDR encapsulation header then the message). With rosbag2's per-message
// compression (compression_mode MESSAGE) each data blob is one zstd frame; such blobs are
// recognised by the zstd magic (a CDR blob starts with 00). Whole-file compression
// (compression_mode FILE, a .db3.zstd file) cannot be read in place by SQLite: it is refused
// with what to do.
//
// The messages of the selected topic are streamed by one prepared statement in id (= insertion)
// order, so memory holds one row at a time; SQLite's own page cache is bounded (2 MiB default).
// The file is opened read-only through a "file:" URI built from the percent-encoded path, so a
// path that looks like a URI or holds '?' or '#' is never read as URI parameters.
#include <sqlite3.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>

#include "bag_backend.hpp"
#include "sigmatau/error.hpp"

namespace sigmatau::detail {
namespace {

/// The 16 bytes every SQLite 3 database starts with (sqlite.org/fileformat.html, 1.3).
constexpr std::string_view kSqliteMagic{"SQLite format 3\0", 16};

/// "file:" URI of `path` with every byte outside [A-Za-z0-9/._~-] percent-encoded.
std::string file_uri(const std::string& path) {
  const std::string absolute = std::filesystem::absolute(path).string();
  std::string uri = "file:";
  for (const char ch : absolute) {
    const auto c = static_cast<unsigned char>(ch);
    const bool plain = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                       c == '/' || c == '.' || c == '_' || c == '~' || c == '-';
    if (plain) {
      uri += ch;
    } else {
      char buf[4];
      std::snprintf(buf, sizeof buf, "%%%02X", c);
      uri += buf;
    }
  }
  return uri + "?mode=ro";
}

/// When a database file is shorter than its header says (a recording stopped before rosbag2
/// closed it, or an incomplete copy), the note SQLite's "malformed" errors get; else "". The
/// header (sqlite.org/fileformat.html, 1.3): page size at offset 16 (2 bytes big-endian, 1 for
/// 65536), file change counter at 24, size in pages at 28, valid only when the "version-valid-
/// for" number at 92 equals the change counter.
std::string cut_short_note(BagFile& file, std::int64_t size) {
  constexpr std::size_t kHeaderBytes = 100;
  if (size < static_cast<std::int64_t>(kHeaderBytes)) {
    return " (the file is " + std::to_string(size) +
           " bytes, shorter than the 100-byte SQLite header: it was cut short)";
  }
  const auto* h = reinterpret_cast<const unsigned char*>(file.view(0, kHeaderBytes, "SQLite header"));
  const auto be32 = [h](std::size_t at) {
    return (std::uint32_t{h[at]} << 24) | (std::uint32_t{h[at + 1]} << 16) |
           (std::uint32_t{h[at + 2]} << 8) | std::uint32_t{h[at + 3]};
  };
  const std::uint32_t page_field = (std::uint32_t{h[16]} << 8) | h[17];
  const std::int64_t page_bytes = page_field == 1 ? 65536 : page_field;
  const std::int64_t pages = be32(28);
  if (be32(92) != be32(24) || pages == 0 || page_bytes < 512) return "";  // size field not kept
  const std::int64_t expected = pages * page_bytes;
  if (size >= expected) return "";
  return " (the file is " + std::to_string(size) + " bytes but its header counts " +
         std::to_string(pages) + " pages of " + std::to_string(page_bytes) + " bytes, " +
         std::to_string(expected) +
         " bytes: it was cut short, by a recording stopped before rosbag2 closed it or by an "
         "incomplete copy, and SQLite cannot read it)";
}

struct Topic {
  std::int64_t id = 0;
  std::string name, type, format;
  std::int64_t messages = -1;
};

class Rosbag2Sqlite final : public BagBackend {
 public:
  explicit Rosbag2Sqlite(const std::string& path) : file_(path) {
    {
      BagFile probe(path);  // a clear error for a missing file or a directory
      size_ = probe.size();
      const std::size_t n = static_cast<std::size_t>(std::min<std::int64_t>(size_, 16));
      const char* head = probe.view(0, n, "SQLite header");
      if (is_zstd_frame(head, n)) {
        throw Error(path +
                    ": this file is compressed as a whole with zstd (rosbag2 "
                    "compression_mode FILE) and cannot be read in place; decompress it "
                    "first (zstd -d, or ros2 bag decompress) and read the .db3 it gives");
      }
      if (std::string_view(head, n) != kSqliteMagic) {
        throw ParseError(path, 0, 0,
                         "not an SQLite database: byte offset 0 does not hold \"SQLite format "
                         "3\" (a rosbag2 .db3 file is one)");
      }
      cut_note_ = cut_short_note(probe, size_);
    }
    const std::string uri = file_uri(path);
    sqlite3* db = nullptr;
    const int rc = sqlite3_open_v2(
        uri.c_str(), &db, SQLITE_OPEN_READONLY | SQLITE_OPEN_URI | SQLITE_OPEN_NOMUTEX, nullptr);
    db_.reset(db);
    if (rc != SQLITE_OK) {
      throw Error(path + ": cannot open as SQLite database: " +
                  (db ? sqlite3_errmsg(db) : sqlite3_errstr(rc)) + cut_note_);
    }
    read_topics();
    Statement max(*this, "SELECT MAX(id) FROM messages");
    if (step(max.get(), "reading the messages table") == SQLITE_ROW) {
      max_id_ = sqlite3_column_int64(max.get(), 0);
    }
  }

  std::vector<BagTopic> topics(bool need_counts) override {
    if (need_counts && !counted_) {
      Statement count(*this, "SELECT topic_id, COUNT(*) FROM messages GROUP BY topic_id");
      for (Topic& t : topics_) t.messages = 0;
      while (step(count.get(), "counting messages") == SQLITE_ROW) {
        const std::int64_t id = sqlite3_column_int64(count.get(), 0);
        for (Topic& t : topics_) {
          if (t.id == id) t.messages = sqlite3_column_int64(count.get(), 1);
        }
      }
      counted_ = true;
    }
    std::vector<BagTopic> list;
    for (const Topic& t : topics_) add_topic(list, t.name, t.type, t.messages, counted_);
    sort_topics(list);
    return list;
  }

  bool select(const std::string& topic) override {
    topic_ = topic;
    stmt_.reset();
    std::string ids;
    for (const Topic& t : topics_) {
      if (t.name != topic) continue;
      const std::string where = "topics table row id " + std::to_string(t.id);
      if (!is_imu_type(t.type)) throw_wrong_type(file_, where, t.name, t.type);
      if (t.format != "cdr" && t.format != "ros1") {
        throw ParseError(file_, 0, 0,
                         where + ": topic " + t.name + " has serialization_format \"" + t.format +
                             "\", expected cdr (or ros1)");
      }
      ros1_ = t.format == "ros1";
      ids += (ids.empty() ? "" : ",") + std::to_string(t.id);
    }
    if (ids.empty()) return false;
    // The ids are integers read from the topics table: nothing user-typed enters the SQL.
    const std::string sql =
        "SELECT id, timestamp, data FROM messages WHERE topic_id IN (" + ids + ") ORDER BY id";
    sqlite3_stmt* stmt = nullptr;
    const int rc = sqlite3_prepare_v2(db_.get(), sql.c_str(), -1, &stmt, nullptr);
    stmt_.reset(stmt);
    if (rc != SQLITE_OK) fail("preparing the message query");
    return true;
  }

  bool next(ImuSample& s) override {
    if (!stmt_) return false;
    sqlite3_stmt* stmt = stmt_.get();
    if (step(stmt, "reading messages") != SQLITE_ROW) {
      done_ = true;
      return false;
    }
    const std::int64_t id = sqlite3_column_int64(stmt, 0);
    const std::int64_t stamp = sqlite3_column_int64(stmt, 1);
    const auto* blob = static_cast<const char*>(sqlite3_column_blob(stmt, 2));
    auto n = static_cast<std::size_t>(sqlite3_column_bytes(stmt, 2));
    last_id_ = id;
    const std::string where = "messages row id " + std::to_string(id);
    if (blob != nullptr && is_zstd_frame(blob, n)) {
      decompress_zstd_frame(std::string_view(blob, n), inflated_, file_, 0,
                            ("the zstd-compressed data of " + where).c_str());
      blob = inflated_.data();
      n = inflated_.size();
    }
    DecodeError e;
    const bool ok = ros1_ ? decode_ros1_imu(blob ? blob : "", n, s, e)
                          : decode_cdr_imu(blob ? blob : "", n, s, e);
    if (!ok) throw_bad_message(file_, where, topic_, n, e);
    s.receive_ns = stamp;
    s.offset = -1;
    s.id = id;
    return true;
  }

  std::int64_t bytes_read() const override {
    if (done_ || max_id_ <= 0) return done_ ? size_ : 0;
    // Row ids grow with the file as it is written: the share of ids passed estimates progress.
    return static_cast<std::int64_t>(
        static_cast<double>(size_) *
        std::clamp(static_cast<double>(last_id_) / static_cast<double>(max_id_), 0.0, 1.0));
  }
  std::int64_t total_bytes() const override { return size_; }

 private:
  /// Owns one prepared statement.
  class Statement {
   public:
    Statement(Rosbag2Sqlite& bag, const char* sql) {
      if (sqlite3_prepare_v2(bag.db_.get(), sql, -1, &stmt_, nullptr) != SQLITE_OK) {
        bag.fail(std::string("running \"") + sql + "\"");
      }
    }
    ~Statement() { sqlite3_finalize(stmt_); }
    Statement(const Statement&) = delete;
    Statement& operator=(const Statement&) = delete;
    sqlite3_stmt* get() const { return stmt_; }

   private:
    sqlite3_stmt* stmt_ = nullptr;
  };

  [[noreturn]] void fail(const std::string& doing) const {
    std::string why = sqlite3_errmsg(db_.get());
    if (sqlite3_errcode(db_.get()) == SQLITE_ERROR &&
        why.find("no such table") != std::string::npos) {
      why += " (not a rosbag2 recording: it needs the tables topics and messages)";
    }
    std::string where;
    if (last_id_ >= 0) where = " after messages row id " + std::to_string(last_id_);
    throw ParseError(file_, 0, 0, "SQLite error " + doing + where + ": " + why + cut_note_);
  }

  int step(sqlite3_stmt* stmt, const char* doing) {
    const int rc = sqlite3_step(stmt);
    if (rc != SQLITE_ROW && rc != SQLITE_DONE) fail(doing);
    return rc;
  }

  static std::string text(sqlite3_stmt* stmt, int column) {
    const auto* p = reinterpret_cast<const char*>(sqlite3_column_text(stmt, column));
    return p ? std::string(p, static_cast<std::size_t>(sqlite3_column_bytes(stmt, column)))
             : std::string();
  }

  void read_topics() {
    Statement list(*this, "SELECT id, name, type, serialization_format FROM topics ORDER BY id");
    while (step(list.get(), "reading the topics table") == SQLITE_ROW) {
      Topic t;
      t.id = sqlite3_column_int64(list.get(), 0);
      t.name = text(list.get(), 1);
      t.type = text(list.get(), 2);
      t.format = text(list.get(), 3);
      topics_.push_back(std::move(t));
    }
  }

  std::string file_;
  std::int64_t size_ = 0;
  std::string cut_note_;  ///< what SQLite's errors gain when the file is shorter than its header says
  std::unique_ptr<sqlite3, int (*)(sqlite3*)> db_{nullptr, sqlite3_close};
  std::unique_ptr<sqlite3_stmt, int (*)(sqlite3_stmt*)> stmt_{nullptr,
                                                              sqlite3_finalize};  // after db_
  std::vector<Topic> topics_;
  bool counted_ = false;
  bool ros1_ = false;
  bool done_ = false;
  std::string topic_;
  std::int64_t max_id_ = 0;
  std::int64_t last_id_ = -1;
  std::vector<char> inflated_;
};

}  // namespace

std::unique_ptr<BagBackend> open_rosbag2_sqlite(const std::string& path) {
  return std::make_unique<Rosbag2Sqlite>(path);
}

}  // namespace sigmatau::detail
