#pragma once
// Internal: random access to a bag file, little-endian field loads, and the chunk codecs (bz2,
// lz4 frames, zstd) shared by the ROS 1 bag, MCAP and rosbag2 SQLite readers.
#include <bit>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

namespace sigmatau::detail {

/// Largest chunk accepted, compressed or not [bytes]. Recorders write chunks of 768 KiB (rosbag
/// record, MCAP's default) to a few MiB; a larger size field is corruption, and the limit keeps
/// memory bounded on hostile input.
constexpr std::uint64_t kMaxBagChunkBytes = std::uint64_t{256} << 20;

inline std::uint16_t load_le16(const char* p) {
  std::uint16_t v;
  std::memcpy(&v, p, sizeof v);
  if constexpr (std::endian::native == std::endian::big) v = __builtin_bswap16(v);
  return v;
}
inline std::uint32_t load_le32(const char* p) {
  std::uint32_t v;
  std::memcpy(&v, p, sizeof v);
  if constexpr (std::endian::native == std::endian::big) v = __builtin_bswap32(v);
  return v;
}
inline std::uint64_t load_le64(const char* p) {
  std::uint64_t v;
  std::memcpy(&v, p, sizeof v);
  if constexpr (std::endian::native == std::endian::big) v = __builtin_bswap64(v);
  return v;
}

/// A regular file read with pread through one cached window, so that walking small records in
/// order costs one system call per window and random access still works.
class BagFile {
 public:
  /// Opens `path`. Throws Error "<path>: cannot open: <strerror>" (or "is a directory").
  explicit BagFile(const std::string& path);
  ~BagFile();
  BagFile(const BagFile&) = delete;
  BagFile& operator=(const BagFile&) = delete;

  const std::string& name() const { return name_; }
  std::int64_t size() const { return size_; }
  /// Bytes delivered so far (for progress; counts re-reads).
  std::int64_t bytes_read() const { return delivered_; }

  /// `n` bytes at `offset`, valid until the next call. Throws ParseError "truncated <what> at byte
  /// offset <offset>: needs <n> bytes, the file ends at <size>" when the file is too short.
  const char* view(std::int64_t offset, std::size_t n, const char* what);
  /// Copies `n` bytes at `offset` into `dst` (large reads bypass the window unless it holds
  /// them). Throws like view.
  void read(std::int64_t offset, std::size_t n, char* dst, const char* what);

 private:
  [[noreturn]] void truncated(std::int64_t offset, std::size_t n, const char* what) const;
  void pread_all(std::int64_t offset, std::size_t n, char* dst);

  std::string name_;
  int fd_ = -1;
  std::int64_t size_ = 0;
  std::int64_t delivered_ = 0;
  std::vector<char> window_;
  std::int64_t window_start_ = 0;
  std::size_t window_len_ = 0;
};

/// The codecs a chunk may use.
enum class Codec { none, bz2, lz4, zstd };

/// Decompresses `src` into exactly `dst.size()` bytes. Throws ParseError (file, "<what> at byte
/// offset <offset>: corrupt <codec> data ..." or a size mismatch) on failure.
void decompress(Codec codec, std::string_view src, std::vector<char>& dst, const std::string& file,
                std::int64_t offset, const char* what);

/// zstd frames start with these bytes (RFC 8878 section 3.1.1: magic 0xFD2FB528, little endian).
inline bool is_zstd_frame(const char* p, std::size_t n) {
  return n >= 4 && static_cast<unsigned char>(p[0]) == 0x28 &&
         static_cast<unsigned char>(p[1]) == 0xb5 && static_cast<unsigned char>(p[2]) == 0x2f &&
         static_cast<unsigned char>(p[3]) == 0xfd;
}
/// Decompresses one zstd frame whose header states its content size (as rosbag2's per-message
/// compression writes it) into `dst`. Throws ParseError like decompress.
void decompress_zstd_frame(std::string_view src, std::vector<char>& dst, const std::string& file,
                           std::int64_t offset, const char* what);

/// CRC-32 (ISO-HDLC, the zlib/PNG polynomial), as MCAP uses it.
std::uint32_t crc32_of(const char* p, std::size_t n, std::uint32_t crc = 0);

/// "byte offset N" for messages.
std::string at_offset(std::int64_t offset);

}  // namespace sigmatau::detail
