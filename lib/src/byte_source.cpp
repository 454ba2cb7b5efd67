// Internal: file / stdin input with transparent gzip (zlib inflate, concatenated members).
#include "byte_source.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <vector>

#include "sigmatau/error.hpp"
#include "sigmatau/log_reader.hpp"

namespace sigmatau::detail {
namespace {

/// Compressed bytes read per refill of the inflater.
constexpr std::size_t kGzipInputBytes = std::size_t{1} << 20;
/// zlib windowBits: 15 (the maximum window) + 16 = accept only the gzip wrapper.
constexpr int kGzipWindowBits = 15 + 16;
constexpr unsigned char kGzipMagic0 = 0x1f;
constexpr unsigned char kGzipMagic1 = 0x8b;

}  // namespace

struct ByteSource::Gzip {
  z_stream z{};
  std::vector<unsigned char> in = std::vector<unsigned char>(kGzipInputBytes);
  bool input_eof = false;
  bool member_done = false;
  Gzip() {
    if (inflateInit2(&z, kGzipWindowBits) != Z_OK) throw std::bad_alloc();
  }
  ~Gzip() { inflateEnd(&z); }
};

ByteSource::ByteSource(const std::string& path) : name_(path == "-" ? "<stdin>" : path) {
  if (path == "-") {
    fd_ = STDIN_FILENO;
  } else {
    fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd_ < 0) throw Error(name_ + ": cannot open: " + std::strerror(errno));
    own_fd_ = true;
  }
  struct stat st {};
  if (::fstat(fd_, &st) == 0) {
    if (S_ISDIR(st.st_mode)) {
      if (own_fd_) ::close(fd_);
      throw Error(name_ + ": cannot read: " + std::strerror(EISDIR));
    }
    if (S_ISREG(st.st_mode)) {
      total_ = static_cast<std::int64_t>(st.st_size);
      ::posix_fadvise(fd_, 0, 0, POSIX_FADV_SEQUENTIAL);
    }
  }
  // Look at the first two bytes (a pipe may deliver them one at a time).
  try {
    while (peek_len_ < 2) {
      const std::size_t got = raw_read(reinterpret_cast<char*>(peek_) + peek_len_, 2 - peek_len_);
      if (got == 0) break;
      peek_len_ += got;
    }
  } catch (...) {
    if (own_fd_) ::close(fd_);
    throw;
  }
  if (peek_len_ == 2 && peek_[0] == kGzipMagic0 && peek_[1] == kGzipMagic1) {
    gzip_ = std::make_unique<Gzip>();
  }
}

ByteSource::~ByteSource() {
  if (own_fd_) ::close(fd_);
}

std::size_t ByteSource::raw_read(char* dst, std::size_t n) {
  if (peek_pos_ < peek_len_) {
    std::size_t k = 0;
    while (k < n && peek_pos_ < peek_len_) dst[k++] = static_cast<char>(peek_[peek_pos_++]);
    return k;
  }
  for (;;) {
    const ssize_t got = ::read(fd_, dst, n);
    if (got >= 0) {
      consumed_ += got;
      return static_cast<std::size_t>(got);
    }
    if (errno != EINTR) throw Error(name_ + ": read error: " + std::strerror(errno));
  }
}

std::size_t ByteSource::read(char* dst, std::size_t n) {
  return gzip_ ? inflate_read(dst, n) : raw_read(dst, n);
}

std::size_t ByteSource::inflate_read(char* dst, std::size_t n) {
  Gzip& g = *gzip_;
  z_stream& z = g.z;
  // zlib counts in uInt; a read never asks for more than 4 GiB at once.
  const uInt want = static_cast<uInt>(std::min<std::size_t>(n, 1u << 30));
  z.next_out = reinterpret_cast<Bytef*>(dst);
  z.avail_out = want;
  const auto offset = [&] { return consumed_ - static_cast<std::int64_t>(z.avail_in); };
  while (z.avail_out == want) {
    if (z.avail_in == 0 && !g.input_eof) {
      const std::size_t got = raw_read(reinterpret_cast<char*>(g.in.data()), g.in.size());
      if (got == 0) g.input_eof = true;
      z.next_in = g.in.data();
      z.avail_in = static_cast<uInt>(got);
    }
    if (g.member_done) {
      if (z.avail_in == 0) return 0;  // clean end after the last member
      // Another member must follow (concatenated gzip files are one stream, as for gunzip).
      if (z.next_in[0] != kGzipMagic0) {
        throw ParseError(name_, 0, 0,
                         "corrupt gzip: unexpected data after the end of the compressed stream "
                         "at byte " +
                             std::to_string(offset()));
      }
      inflateReset(&z);
      g.member_done = false;
    }
    if (z.avail_in == 0 && g.input_eof) {
      throw ParseError(name_, 0, 0,
                       "corrupt gzip: the compressed data ends early at byte " +
                           std::to_string(offset()) + " (truncated file?)");
    }
    const int rc = inflate(&z, Z_NO_FLUSH);
    if (rc == Z_STREAM_END) {
      g.member_done = true;
    } else if (rc != Z_OK && rc != Z_BUF_ERROR) {
      throw ParseError(name_, 0, 0,
                       std::string("corrupt gzip: ") + (z.msg ? z.msg : "inflate failed") +
                           " near byte " + std::to_string(offset()));
    }
  }
  return want - z.avail_out;
}

}  // namespace sigmatau::detail

namespace sigmatau {

bool is_gzip_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  unsigned char magic[2] = {0, 0};
  in.read(reinterpret_cast<char*>(magic), 2);
  return in.gcount() == 2 && magic[0] == detail::kGzipMagic0 && magic[1] == detail::kGzipMagic1;
}

}  // namespace sigmatau
