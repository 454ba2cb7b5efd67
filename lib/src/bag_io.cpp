// Internal: cached random access to bag files and the chunk codecs (see bag_io.hpp).
#include "bag_io.hpp"

#include <bzlib.h>
#include <fcntl.h>
#include <lz4frame.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>
#include <zstd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <memory>

#include "sigmatau/error.hpp"

namespace sigmatau::detail {
namespace {

/// Read window [bytes]: 4 MiB, like the text reader's buffer; ROS message records are ~400 bytes,
/// so a window serves about 10^4 of them per system call.
constexpr std::size_t kWindowBytes = std::size_t{4} << 20;
/// Reads at least this large bypass the window (a chunk goes straight into its own buffer).
constexpr std::size_t kDirectReadBytes = std::size_t{256} << 10;

const char* codec_name(Codec codec) {
  switch (codec) {
    case Codec::none:
      return "uncompressed";
    case Codec::bz2:
      return "bz2";
    case Codec::lz4:
      return "lz4";
    case Codec::zstd:
      return "zstd";
  }
  return "?";
}

[[noreturn]] void corrupt(Codec codec, const std::string& file, std::int64_t offset,
                          const char* what, const std::string& detail) {
  throw ParseError(file, 0, 0,
                   std::string(what) + " at " + at_offset(offset) + ": corrupt " +
                       codec_name(codec) + " data (" + detail + ")");
}

}  // namespace

std::string at_offset(std::int64_t offset) { return "byte offset " + std::to_string(offset); }

BagFile::BagFile(const std::string& path) : name_(path) {
  fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd_ < 0) throw Error(path + ": cannot open: " + std::strerror(errno));
  struct stat st {};
  if (::fstat(fd_, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd_);
    throw Error(path + ": cannot read: not a regular file");
  }
  size_ = static_cast<std::int64_t>(st.st_size);
}

BagFile::~BagFile() {
  if (fd_ >= 0) ::close(fd_);
}

void BagFile::truncated(std::int64_t offset, std::size_t n, const char* what) const {
  throw ParseError(name_, 0, 0,
                   std::string("truncated ") + what + " at " + at_offset(offset) + ": needs " +
                       std::to_string(n) + " bytes, the file ends at byte " +
                       std::to_string(size_));
}

void BagFile::pread_all(std::int64_t offset, std::size_t n, char* dst) {
  std::size_t done = 0;
  while (done < n) {
    const ssize_t got = ::pread(fd_, dst + done, n - done, static_cast<off_t>(offset) +
                                                               static_cast<off_t>(done));
    if (got < 0) {
      if (errno == EINTR) continue;
      throw Error(name_ + ": read error: " + std::strerror(errno));
    }
    if (got == 0) throw Error(name_ + ": the file shrank while being read");
    done += static_cast<std::size_t>(got);
  }
}

const char* BagFile::view(std::int64_t offset, std::size_t n, const char* what) {
  if (offset < 0 || offset > size_ || static_cast<std::uint64_t>(size_ - offset) < n) {
    truncated(offset, n, what);
  }
  delivered_ += static_cast<std::int64_t>(n);
  if (offset >= window_start_ &&
      static_cast<std::uint64_t>(offset - window_start_) + n <= window_len_) {
    return window_.data() + (offset - window_start_);
  }
  const std::size_t len = std::max(
      n, static_cast<std::size_t>(std::min<std::int64_t>(
             static_cast<std::int64_t>(kWindowBytes), size_ - offset)));
  if (window_.size() < len) window_.resize(len);
  window_len_ = 0;
  pread_all(offset, len, window_.data());
  window_start_ = offset;
  window_len_ = len;
  if (window_.size() > kWindowBytes && len <= kWindowBytes) window_.shrink_to_fit();
  return window_.data();
}

void BagFile::read(std::int64_t offset, std::size_t n, char* dst, const char* what) {
  if (n == 0) {  // e.g. an empty chunk: dst may be the null data() of an empty buffer
    if (offset < 0 || offset > size_) truncated(offset, 0, what);
    return;
  }
  if (n < kDirectReadBytes) {
    std::memcpy(dst, view(offset, n, what), n);
    return;
  }
  if (offset < 0 || offset > size_ || static_cast<std::uint64_t>(size_ - offset) < n) {
    truncated(offset, n, what);
  }
  delivered_ += static_cast<std::int64_t>(n);
  // A chunk that the window already holds (read with the record headers before it) is copied
  // from there: reading it again from the file made a bag's bytes cross the kernel twice.
  if (offset >= window_start_ &&
      static_cast<std::uint64_t>(offset - window_start_) + n <= window_len_) {
    std::memcpy(dst, window_.data() + (offset - window_start_), n);
    return;
  }
  pread_all(offset, n, dst);
}

void decompress(Codec codec, std::string_view src, std::vector<char>& dst, const std::string& file,
                std::int64_t offset, const char* what) {
  const std::size_t want = dst.size();
  switch (codec) {
    case Codec::none:
      if (src.size() != want) {
        throw ParseError(file, 0, 0,
                         std::string(what) + " at " + at_offset(offset) + ": holds " +
                             std::to_string(src.size()) + " bytes but states " +
                             std::to_string(want));
      }
      std::memcpy(dst.data(), src.data(), want);
      return;
    case Codec::bz2: {
      auto out_len = static_cast<unsigned int>(want);
      const int rc = BZ2_bzBuffToBuffDecompress(dst.data(), &out_len, const_cast<char*>(src.data()),
                                                static_cast<unsigned int>(src.size()), 0, 0);
      if (rc == BZ_OUTBUFF_FULL) {
        corrupt(codec, file, offset, what,
                "inflates to more than the stated " + std::to_string(want) + " bytes");
      }
      if (rc != BZ_OK) corrupt(codec, file, offset, what, "libbz2 error " + std::to_string(rc));
      if (out_len != want) {
        corrupt(codec, file, offset, what,
                "inflates to " + std::to_string(out_len) + " bytes, the chunk states " +
                    std::to_string(want));
      }
      return;
    }
    case Codec::lz4: {
      LZ4F_dctx* raw = nullptr;
      if (LZ4F_isError(LZ4F_createDecompressionContext(&raw, LZ4F_VERSION))) {
        throw Error("out of memory for an lz4 decompression context");
      }
      const std::unique_ptr<LZ4F_dctx, LZ4F_errorCode_t (*)(LZ4F_dctx*)> ctx(
          raw, LZ4F_freeDecompressionContext);
      std::size_t in_pos = 0;
      std::size_t out_pos = 0;
      std::size_t hint = 1;
      // One frame, or several concatenated, until the input is used up.
      while (in_pos < src.size()) {
        std::size_t in_len = src.size() - in_pos;
        std::size_t out_len = want - out_pos;
        hint = LZ4F_decompress(ctx.get(), dst.data() + out_pos, &out_len, src.data() + in_pos,
                               &in_len, nullptr);
        if (LZ4F_isError(hint)) corrupt(codec, file, offset, what, LZ4F_getErrorName(hint));
        in_pos += in_len;
        out_pos += out_len;
        if (in_len == 0 && out_len == 0) {
          corrupt(codec, file, offset, what,
                  "inflates to more than the stated " + std::to_string(want) + " bytes");
        }
      }
      if (hint != 0) corrupt(codec, file, offset, what, "the lz4 frame is cut short");
      if (out_pos != want) {
        corrupt(codec, file, offset, what,
                "inflates to " + std::to_string(out_pos) + " bytes, the chunk states " +
                    std::to_string(want));
      }
      return;
    }
    case Codec::zstd: {
      thread_local std::unique_ptr<ZSTD_DCtx, std::size_t (*)(ZSTD_DCtx*)> ctx(ZSTD_createDCtx(),
                                                                               ZSTD_freeDCtx);
      const std::size_t got = ZSTD_decompressDCtx(ctx.get(), dst.data(), want, src.data(),
                                                  src.size());
      if (ZSTD_isError(got)) corrupt(codec, file, offset, what, ZSTD_getErrorName(got));
      if (got != want) {
        corrupt(codec, file, offset, what,
                "inflates to " + std::to_string(got) + " bytes, the chunk states " +
                    std::to_string(want));
      }
      return;
    }
  }
}

void decompress_zstd_frame(std::string_view src, std::vector<char>& dst, const std::string& file,
                           std::int64_t offset, const char* what) {
  const unsigned long long size = ZSTD_getFrameContentSize(src.data(), src.size());
  if (size == ZSTD_CONTENTSIZE_ERROR || size == ZSTD_CONTENTSIZE_UNKNOWN ||
      size > kMaxBagChunkBytes) {
    corrupt(Codec::zstd, file, offset, what,
            "the frame header states no usable content size");
  }
  dst.resize(static_cast<std::size_t>(size));
  decompress(Codec::zstd, src, dst, file, offset, what);
}

std::uint32_t crc32_of(const char* p, std::size_t n, std::uint32_t crc) {
  // zlib's crc32 takes uInt lengths: feed it in pieces below 4 GiB.
  constexpr std::size_t kPiece = std::size_t{1} << 30;
  uLong c = crc;
  while (n > 0) {
    const std::size_t m = std::min(n, kPiece);
    c = ::crc32(c, reinterpret_cast<const Bytef*>(p), static_cast<uInt>(m));
    p += m;
    n -= m;
  }
  return static_cast<std::uint32_t>(c);
}

}  // namespace sigmatau::detail
