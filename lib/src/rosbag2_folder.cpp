// Internal: a rosbag2 recording folder (what `ros2 bag record` writes): metadata.yaml and one or
// more storage files, read one after the other through the MCAP or SQLite backend.
//
// metadata.yaml (rosbag2_storage, metadata_io): a map rosbag2_bagfile_information with
// storage_identifier (sqlite3 | mcap), relative_file_paths (the files in recording order; rosbag2
// before version 4 wrote them with the folder's own name in front, resolved here too),
// compression_format (zstd or empty), compression_mode (NONE / MESSAGE / FILE, or empty) and
// topics_with_message_count (topic_metadata: name, type, serialization_format; message_count).
// Per-message compression is handled by the SQLite backend (each blob a zstd frame). File
// compression (each file one zstd stream: .db3.zstd, .mcap.zstd) is refused with what to do:
// SQLite needs random access, and decompressing a multi-GB file to a temporary copy is a choice
// left to the user.
// A recorder that died leaves its last file cut short (see BagBackend::allow_cut): that cut is the
// folder's; a cut in an earlier file (closed by a split) is corruption, always a ParseError.
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "bag_backend.hpp"
#include "sigmatau/error.hpp"

namespace sigmatau::detail {
namespace {

namespace fs = std::filesystem;

class Rosbag2Folder final : public BagBackend {
 public:
  explicit Rosbag2Folder(const std::string& dir)
      : dir_(dir), yaml_((fs::path(dir) / "metadata.yaml").string()) {
    if (!fs::is_regular_file(yaml_)) {
      throw Error(dir +
                  ": no metadata.yaml in this folder (a recording that was not closed "
                  "cleanly has none): read its .db3 or .mcap files one by one instead, or "
                  "run `ros2 bag reindex` on it");
    }
    YAML::Node root;
    try {
      root = YAML::LoadFile(yaml_);
    } catch (const YAML::Exception& e) {
      throw ParseError(yaml_, e.mark.line + 1, e.mark.column + 1, e.msg);
    }
    const YAML::Node info = root["rosbag2_bagfile_information"];
    if (!info.IsMap()) fail(root, "no map rosbag2_bagfile_information (not rosbag2 metadata)");
    const std::string storage = scalar(info, "storage_identifier");
    if (storage != "sqlite3" && storage != "mcap") {
      fail(info["storage_identifier"],
           "storage_identifier \"" + storage + "\" is not one read here (sqlite3 or mcap)");
    }
    mcap_ = storage == "mcap";
    const std::string mode = optional_scalar(info, "compression_mode");
    const std::string format = optional_scalar(info, "compression_format");
    const YAML::Node paths = info["relative_file_paths"];
    if (!paths.IsSequence() || paths.size() == 0) {
      fail(paths ? paths : info, "relative_file_paths is not a non-empty list of file names");
    }
    for (const YAML::Node& p : paths) {
      if (!p.IsScalar()) fail(p, "relative_file_paths holds an entry that is not a file name");
      files_.push_back(resolve(p));
    }
    std::string upper = mode;
    std::transform(upper.begin(), upper.end(), upper.begin(),
                   [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
    if (upper == "FILE") {
      throw ParseError(yaml_, 0, 0,
                       "the recording is compressed file by file (compression_mode FILE, format " +
                           format + "), e.g. " + files_.front() +
                           "; this is not read in place: run `ros2 bag decompress` on the folder, "
                           "or `zstd -d` on its files and read the resulting .db3 / .mcap files");
    }
    if (upper == "MESSAGE" && format != "zstd") {
      fail(info["compression_format"],
           "per-message compression_format \"" + format + "\" is not read here (zstd is)");
    }
    if (!upper.empty() && upper != "NONE" && upper != "MESSAGE") {
      fail(info["compression_mode"], "compression_mode \"" + mode + "\" is unknown");
    }
    read_topics(info["topics_with_message_count"]);
    for (const std::string& f : files_) total_ += static_cast<std::int64_t>(fs::file_size(f));
  }

  std::vector<BagTopic> topics(bool need_counts) override {
    if (!topics_.empty() && (!need_counts || counts_known_)) return topics_;
    std::vector<BagTopic> all;
    for (std::size_t i = 0; i < files_.size(); ++i) {
      const auto file = open(files_[i]);
      const std::vector<BagTopic> listed = file->topics(need_counts);
      take_cut(*file, i + 1 == files_.size());
      for (const BagTopic& t : listed) {
        auto it = std::find_if(all.begin(), all.end(),
                               [&](const BagTopic& a) { return a.name == t.name; });
        if (it == all.end()) {
          all.push_back(t);
        } else if (it->messages >= 0 && t.messages >= 0) {
          it->messages += t.messages;
        } else {
          it->messages = -1;
        }
      }
    }
    sort_topics(all);
    return all;
  }

  bool select(const std::string& topic) override {
    topic_ = topic;
    index_ = 0;
    current_.reset();
    if (topics_.empty()) return true;  // no topic list in metadata.yaml: each file decides
    const auto it = std::find_if(topics_.begin(), topics_.end(),
                                 [&](const BagTopic& t) { return t.name == topic; });
    if (it == topics_.end()) return false;
    if (!is_imu_type(it->type))
      throw_wrong_type(yaml_, "topics_with_message_count", topic, it->type);
    return true;
  }

  bool next(ImuSample& s) override {
    while (true) {
      if (current_ && current_->next(s)) return true;
      if (current_) {
        take_cut(*current_, index_ == files_.size());
        done_bytes_ += current_->total_bytes();
        current_.reset();
      }
      if (index_ >= files_.size()) {
        if (topics_.empty() && !seen_topic_) {
          throw Error(dir_ + ": no topic " + topic_ + " in any file of the recording");
        }
        return false;
      }
      const std::string& f = files_[index_++];
      current_ = open(f);
      // Topic lists are cheap with a summary or an SQLite topics table; a split file may lack
      // the topic, which a file-level select on a summary-less MCAP could only tell at its end.
      const auto list = current_->topics(false);
      take_cut(*current_, index_ == files_.size());
      const bool has = std::any_of(list.begin(), list.end(),
                                   [&](const BagTopic& t) { return t.name == topic_; });
      if (!has || !current_->select(topic_)) {
        done_bytes_ += current_->total_bytes();
        current_.reset();
        continue;
      }
      seen_topic_ = true;
    }
  }

  std::int64_t bytes_read() const override {
    return done_bytes_ + (current_ ? std::min(current_->bytes_read(), current_->total_bytes()) : 0);
  }
  std::int64_t total_bytes() const override { return total_; }

 private:
  [[noreturn]] void fail(const YAML::Node& node, const std::string& message) const {
    const YAML::Mark mark = node.Mark();
    throw ParseError(yaml_, mark.line >= 0 ? mark.line + 1 : 0,
                     mark.column >= 0 ? mark.column + 1 : 0, message);
  }

  std::string scalar(const YAML::Node& map, const char* key) const {
    const YAML::Node v = map[key];
    if (!v || !v.IsScalar()) fail(v ? v : map, std::string("missing or non-text ") + key);
    return v.Scalar();
  }

  std::string optional_scalar(const YAML::Node& map, const char* key) const {
    const YAML::Node v = map[key];
    if (!v || v.IsNull()) return {};
    if (!v.IsScalar()) fail(v, std::string(key) + " is not text");
    return v.Scalar();
  }

  /// A relative file path of metadata.yaml as an existing file.
  std::string resolve(const YAML::Node& node) const {
    const fs::path rel(node.Scalar());
    if (rel.is_absolute()) fail(node, "relative_file_paths entry " + rel.string() + " is absolute");
    const fs::path dir(dir_);
    for (const fs::path& candidate : {dir / rel, dir.parent_path() / rel}) {
      if (fs::is_regular_file(candidate)) return candidate.string();
    }
    fail(node, "relative_file_paths lists " + rel.string() + ", which is not a file in " + dir_);
  }

  void read_topics(const YAML::Node& list) {
    if (!list || list.IsNull()) return;
    if (!list.IsSequence()) fail(list, "topics_with_message_count is not a list");
    counts_known_ = true;
    for (const YAML::Node& entry : list) {
      const YAML::Node meta = entry["topic_metadata"];
      if (!meta.IsMap()) fail(entry, "topics_with_message_count entry without topic_metadata");
      BagTopic t{scalar(meta, "name"), scalar(meta, "type"), -1};
      const YAML::Node count = entry["message_count"];
      try {
        if (count) t.messages = count.as<std::int64_t>();
      } catch (const YAML::Exception&) {
        fail(count, "message_count is not an integer");
      }
      if (t.messages < 0) counts_known_ = false;
      topics_.push_back(std::move(t));
    }
    std::sort(topics_.begin(), topics_.end(),
              [](const BagTopic& a, const BagTopic& b) { return a.name < b.name; });
  }

  std::unique_ptr<BagBackend> open(const std::string& f) const {
    auto file = mcap_ ? open_mcap(f) : open_rosbag2_sqlite(f);
    if (cut_allowed_) file->allow_cut();
    return file;
  }
  /// A cut met in one of the files: the folder's cut when it is the last file (`last`: a
  /// recorder that died was writing it); before the last, the file was closed by a split and
  /// ending inside a record is corruption.
  void take_cut(const BagBackend& file, bool last) {
    const BagCut& c = file.cut();
    if (c.at_byte < 0) return;
    if (!last) {
      throw ParseError(c.file, 0, 0,
                       c.detail + " (a file before the last of the recording " + dir_ +
                           " ends inside a record: corrupt, not a recording cut short)");
    }
    cut_ = c;
  }

  std::string dir_, yaml_;
  bool mcap_ = false;
  std::vector<std::string> files_;
  std::vector<BagTopic> topics_;  // from metadata.yaml, sorted by name
  bool counts_known_ = false;
  std::int64_t total_ = 0, done_bytes_ = 0;
  std::string topic_;
  std::size_t index_ = 0;
  std::unique_ptr<BagBackend> current_;
  bool seen_topic_ = false;
};

}  // namespace

std::unique_ptr<BagBackend> open_rosbag2_folder(const std::string& dir) {
  return std::make_unique<Rosbag2Folder>(dir);
}

}  // namespace sigmatau::detail
