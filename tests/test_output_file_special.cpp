// The output writer and special files (review D, findings 1 and 5): a device, FIFO or open
// descriptor is written straight into and never replaced; a symbolic link is followed, never
// replaced; missing parent directories are still created (finding 5: kept, the test suite
// relies on it, and documented). All in a scratch directory:
// the character device is made with mknod there (root only), never the real /dev/null.
#include <doctest/doctest.h>
#include <fcntl.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/un.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <future>
#include <sstream>
#include <string>

#include "sigmatau/error.hpp"
#include "sigmatau/output_file.hpp"
#include "temp_dir.hpp"
#include "test_support.hpp"

using namespace sigmatau;
namespace fs = std::filesystem;

namespace {

using test::error_of;

/// The file type of `p` itself (links not followed), as `stat -c %F` would name it.
std::string type_of(const fs::path& p) {
  struct stat st {};
  if (::lstat(p.c_str(), &st) != 0) return "missing";
  if (S_ISLNK(st.st_mode)) return "symlink";
  if (S_ISREG(st.st_mode)) return "regular";
  if (S_ISDIR(st.st_mode)) return "directory";
  if (S_ISCHR(st.st_mode)) return "character device";
  if (S_ISFIFO(st.st_mode)) return "fifo";
  if (S_ISSOCK(st.st_mode)) return "socket";
  return "other";
}

/// True when some name in `dir` holds ".tmp-" (a temporary file left behind).
bool has_temporary(const fs::path& dir) {
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().filename().string().find(".tmp-") != std::string::npos) return true;
  }
  return false;
}

/// Reads a FIFO to its end on another thread (a writer's open() waits for a reader).
std::future<std::string> read_fifo(const fs::path& fifo) {
  return std::async(std::launch::async, [fifo] { return test::file_text(fifo); });
}

/// What the reader of `fifo` got. Until the reader is done, opens and closes the FIFO for
/// writing, so that a reader still waiting (the writer under test never opened the FIFO, as
/// the old writer did not) sees an empty stream instead of waiting for ever.
std::string received(const fs::path& fifo, std::future<std::string>& reader) {
  while (reader.wait_for(std::chrono::milliseconds(10)) != std::future_status::ready) {
    const int fd = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK);
    if (fd >= 0) ::close(fd);
  }
  return reader.get();
}

}  // namespace

TEST_CASE("a FIFO is written straight into, with or without overwrite, and stays a FIFO") {
  test::TempDir dir("sigmatau_out_fifo");
  const fs::path fifo = dir.file("pipe");
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  for (const bool overwrite : {false, true}) {
    CAPTURE(overwrite);
    check_can_write(fifo, overwrite);  // must not open it: there is no reader yet
    auto reader = read_fifo(fifo);
    const std::string error =
        error_of([&] { write_file_atomically(fifo, "through the pipe\n", overwrite); });
    CHECK(error == "");
    CHECK(received(fifo, reader) == "through the pipe\n");
    CHECK(type_of(fifo) == "fifo");
    CHECK_FALSE(has_temporary(dir.file("")));
  }
}

TEST_CASE("a symbolic link to a FIFO is followed, and the link is kept") {
  test::TempDir dir("sigmatau_out_fifo_link");
  const fs::path fifo = dir.file("pipe");
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  fs::create_symlink("pipe", dir.file("link"));
  auto reader = read_fifo(fifo);
  write_file_atomically(dir.file("link"), "via the link\n", true);
  CHECK(received(fifo, reader) == "via the link\n");
  CHECK(type_of(dir.file("link")) == "symlink");
  CHECK(type_of(fifo) == "fifo");
}

TEST_CASE("a character device is written straight into and never replaced (mknod, root only)") {
  test::TempDir dir("sigmatau_out_device");
  const fs::path device = dir.file("null");
  // The null device's numbers (major 1, minor 3 on Linux): made here, a scratch copy.
  if (::mknod(device.c_str(), S_IFCHR | 0666, makedev(1, 3)) != 0) {
    MESSAGE("skipped: mknod needs root (CAP_MKNOD)");
    return;
  }
  fs::create_symlink("null", dir.file("link"));
  for (const fs::path& target : {device, dir.file("link")}) {
    CAPTURE(target);
    for (const bool overwrite : {false, true}) {
      write_file_atomically(target, "discarded\n", overwrite);
      AtomicOutputFile piecewise(target, overwrite);
      piecewise.write("also ");
      piecewise.write("discarded\n");
      piecewise.commit();
    }
  }
  CHECK(type_of(device) == "character device");
  CHECK(type_of(dir.file("link")) == "symlink");
  CHECK_FALSE(has_temporary(dir.file("")));
}

TEST_CASE("an open descriptor (/dev/fd/N, /proc/self/fd/N, a link to one) is written into") {
  test::TempDir dir("sigmatau_out_descriptor");
  SUBCASE("a pipe, as a process substitution gives") {
    int fds[2];
    REQUIRE(::pipe(fds) == 0);
    const std::string n = std::to_string(fds[1]);
    fs::create_symlink("/proc/self/fd/" + n, dir.file("link"));
    write_file_atomically("/dev/fd/" + n, "one\n", false);
    write_file_atomically("/proc/self/fd/" + n, "two\n", false);
    write_file_atomically(dir.file("link"), "three\n", true);
    ::close(fds[1]);
    std::string got;
    char buffer[64];
    ssize_t r;
    while ((r = ::read(fds[0], buffer, sizeof buffer)) > 0)
      got.append(buffer, static_cast<std::size_t>(r));
    ::close(fds[0]);
    CHECK(got == "one\ntwo\nthree\n");
    CHECK(type_of(dir.file("link")) == "symlink");
  }
  SUBCASE("a regular file opened for appending, as `>> file` gives: appended, not replaced") {
    const fs::path file = dir.file("log.txt");
    std::ofstream(file) << "kept\n";
    const int fd = ::open(file.c_str(), O_WRONLY | O_APPEND);
    REQUIRE(fd >= 0);
    struct stat before {};
    REQUIRE(::stat(file.c_str(), &before) == 0);
    write_file_atomically("/dev/fd/" + std::to_string(fd), "added\n", false);
    ::close(fd);
    struct stat after {};
    REQUIRE(::stat(file.c_str(), &after) == 0);
    CHECK(test::file_text(file) == "kept\nadded\n");
    CHECK(after.st_ino == before.st_ino);  // the same file, not a renamed copy
    CHECK_FALSE(has_temporary(dir.file("")));
  }
  SUBCASE("a descriptor that is not open, or open for reading only, is an error") {
    const int fd = ::open(dir.file("").c_str(), O_RDONLY | O_DIRECTORY);
    REQUIRE(fd >= 0);
    const std::string name = "/dev/fd/" + std::to_string(fd);
    CHECK(error_of([&] { check_can_write(name, true); }).find("open for reading only") !=
          std::string::npos);
    ::close(fd);
    CHECK(error_of([&] { check_can_write(name, true); }).find("is not open") != std::string::npos);
  }
}

TEST_CASE("a symbolic link to a regular file is followed: the target is replaced, not the link") {
  test::TempDir dir("sigmatau_out_link");
  fs::create_directories(dir.file("real"));
  fs::create_directories(dir.file("links"));
  const fs::path target = dir.file("real") / "a.txt";
  const fs::path link = dir.file("links") / "a.txt";
  std::ofstream(target) << "old\n";
  fs::create_symlink("../real/a.txt", link);
  const std::string refused = error_of([&] { write_file_atomically(link, "new\n", false); });
  CHECK(refused.find("exists; use --force") != std::string::npos);
  CHECK(refused.find("real/a.txt") != std::string::npos);  // says where the link leads
  CHECK(test::file_text(target) == "old\n");
  write_file_atomically(link, "new\n", true);
  CHECK(type_of(link) == "symlink");
  CHECK(fs::read_symlink(link) == "../real/a.txt");
  CHECK(test::file_text(target) == "new\n");
  CHECK_FALSE(has_temporary(dir.file("real")));
  CHECK_FALSE(has_temporary(dir.file("links")));
}

TEST_CASE("a dangling symbolic link is followed: its target is created, the link kept") {
  test::TempDir dir("sigmatau_out_dangling");
  fs::create_directories(dir.file("real"));
  fs::create_symlink("real/new.txt", dir.file("link"));
  write_file_atomically(dir.file("link"), "created\n", false);
  CHECK(type_of(dir.file("link")) == "symlink");
  CHECK(type_of(dir.file("real") / "new.txt") == "regular");
  CHECK(test::file_text(dir.file("real") / "new.txt") == "created\n");
  SUBCASE("a link into a missing directory creates that directory, not one beside the link") {
    fs::create_symlink("elsewhere/x.txt", dir.file("lost"));
    write_file_atomically(dir.file("lost"), "found\n", false);
    CHECK(type_of(dir.file("lost")) == "symlink");
    CHECK(test::file_text(dir.file("elsewhere") / "x.txt") == "found\n");
    CHECK_FALSE(has_temporary(dir.file("elsewhere")));
  }
  SUBCASE("a loop of links is an error") {
    fs::create_symlink("loop", dir.file("loop"));
    CHECK(error_of([&] { check_can_write(dir.file("loop"), true); }).find("Too many levels") !=
          std::string::npos);
  }
}

TEST_CASE("missing parent directories are created (kept: scripts and the test suite rely on it)") {
  test::TempDir dir("sigmatau_out_parents");
  const fs::path out = dir.file("missing") / "deeper" / "out.txt";
  check_can_write(out, false);
  CHECK(type_of(dir.file("missing")) == "missing");  // the early check creates nothing
  write_file_atomically(out, "x\n", false);
  CHECK(test::file_text(out) == "x\n");
  SUBCASE("a file in the way is named as before") {
    std::ofstream(dir.file("plain")) << "in the way\n";
    CHECK(error_of([&] { check_can_write(dir.file("plain") / "a" / "b.txt", true); }) ==
          "cannot create directory " + dir.file("plain").string() + ": Not a directory");
  }
}

TEST_CASE("a directory, a socket and a regular file without overwrite are refused") {
  test::TempDir dir("sigmatau_out_refused");
  fs::create_directories(dir.file("sub"));
  CHECK(error_of([&] {
          write_file_atomically(dir.file("sub"), "x", true);
        }).find("is a directory") != std::string::npos);
  std::ofstream(dir.file("kept")) << "kept\n";
  CHECK(error_of([&] {
          write_file_atomically(dir.file("kept"), "x", false);
        }).find("exists; use --force") != std::string::npos);
  CHECK(test::file_text(dir.file("kept")) == "kept\n");
  write_file_atomically(dir.file("kept"), "replaced\n", true);
  CHECK(test::file_text(dir.file("kept")) == "replaced\n");

  const int sock = ::socket(AF_UNIX, SOCK_STREAM, 0);
  REQUIRE(sock >= 0);
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  const std::string socket_path = dir.file("sock").string();
  if (socket_path.size() < sizeof address.sun_path) {
    std::copy(socket_path.begin(), socket_path.end(), address.sun_path);
    REQUIRE(::bind(sock, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0);
    CHECK(error_of([&] {
            write_file_atomically(dir.file("sock"), "x", true);
          }).find("it is a socket") != std::string::npos);
    CHECK(type_of(dir.file("sock")) == "socket");
  }
  ::close(sock);
}

TEST_CASE("check_output_directory: a link is followed, a device refused, nothing created") {
  test::TempDir dir("sigmatau_out_directory");
  // An earlier report (only that is replaced with --force: test_output_safety).
  write_directory_atomically(dir.file("real"), {{"results.json", "{}\n"}}, false);
  fs::create_symlink("real", dir.file("link"));
  CHECK(error_of([&] {
          check_output_directory(dir.file("link"), false);
        }).find("exists; use --force to replace it") != std::string::npos);
  CHECK(check_output_directory(dir.file("link"), true) == dir.file("real"));
  CHECK(check_output_directory(dir.file("new") / "", false) == dir.file("new"));
  CHECK(check_output_directory(dir.file("no") / "report", true) == dir.file("no") / "report");
  CHECK(type_of(dir.file("no")) == "missing");
  const fs::path fifo = dir.file("pipe");
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  CHECK(error_of([&] { check_output_directory(fifo, true); }).find("expected a directory name") !=
        std::string::npos);
  CHECK(type_of(fifo) == "fifo");
}
