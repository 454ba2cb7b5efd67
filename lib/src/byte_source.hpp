#pragma once
// Internal: a file, or stdin, delivered as bytes; gzip (one or more members) is inflated
// transparently when the input starts with the gzip magic bytes 1f 8b.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

namespace sigmatau::detail {

class ByteSource {
 public:
  /// Opens `path` ("-" is stdin). Throws Error "<path>: cannot open: <strerror>".
  explicit ByteSource(const std::string& path);
  ~ByteSource();
  ByteSource(const ByteSource&) = delete;
  ByteSource& operator=(const ByteSource&) = delete;

  /// Reads up to `n` > 0 bytes of (decompressed) data into `dst`. Returns the count, which is
  /// > 0 until the end of the input and 0 there. Throws ParseError on corrupt gzip data and
  /// Error on a read error.
  std::size_t read(char* dst, std::size_t n);

  /// Name for messages: the path, or "<stdin>".
  const std::string& name() const { return name_; }
  bool gzip() const { return gzip_ != nullptr; }
  std::int64_t bytes_consumed() const { return consumed_; }  ///< raw bytes read from the file
  std::int64_t total_bytes() const { return total_; }        ///< file size, -1 when unknown

 private:
  std::size_t raw_read(char* dst, std::size_t n);
  std::size_t inflate_read(char* dst, std::size_t n);

  struct Gzip;
  std::string name_;
  int fd_ = -1;
  bool own_fd_ = false;
  std::int64_t consumed_ = 0;
  std::int64_t total_ = -1;
  unsigned char peek_[2] = {0, 0};  // first bytes, read to look for the gzip magic
  std::size_t peek_len_ = 0;
  std::size_t peek_pos_ = 0;
  std::unique_ptr<Gzip> gzip_;
};

}  // namespace sigmatau::detail
